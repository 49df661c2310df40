// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkMultiVolumeRayCastMapper.h"

#include "vtkBrickAtlasAllocator.h"
#include "vtkCutPages.h"
#include "vtkFeedbackReadBack.h"
#include "vtkFeedbackReduction.h"
#include "vtkPageCache.h"
#include "vtkPagePoolFile.h"
#include "vtkPagePoolReader.h"
#include "vtkPreIntegrationTable.h"
#include "vtkStrataRenderUtilities.h"
#include "vtkTransferFunctionTable.h"
#include "vtkVolumeBSPTree.h"
#include "vtkVolumeBrickTree.h"
#include "vtkVolumeCut.h"
#include "vtkVolumeSkipGrid.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationStringKey.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiVolume.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "vtkMultiVolumeCompositeFS.h"
#include "vtkMultiVolumeCompositeVS.h"
#include "vtkMultiVolumeFragmentFS.h"
#include "vtkMultiVolumeFragmentVS.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

namespace
{
constexpr int TransferTableSize = vtkTransferFunctionTable::TableSize;
constexpr int MaxPlanes = 64;

void Replace(std::string& source, const std::string& tag, const std::string& code)
{
  const size_t at = source.find(tag);
  if (at != std::string::npos)
  {
    source.replace(at, tag.size(), code);
  }
}

void ToFloat(vtkMatrix4x4* m, float out[16])
{
  // Column-major, as vtkShaderProgram::SetUniformMatrix4x4 hands it to glUniformMatrix4fv.
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      out[4 * c + r] = static_cast<float>(m->GetElement(r, c));
}

void Translation(vtkMatrix4x4* m, const std::array<double, 3>& t)
{
  m->Identity();
  for (int i = 0; i < 3; ++i)
    m->SetElement(i, 3, t[i]);
}

constexpr int FeedbackLevels = vtkFeedbackReduction::MaxLevels;

// The root page of a pool from the image its reader produced at the coarsest level (`dims`
// points): the page is B^3 values, x fastest, and repeats the level's last point beyond it
// (vtkPagePoolFormat), converted to float like vtkPagePoolFile::ReadPage. False when the image
// is not that level.
bool RootFromImage(vtkImageData* image, const int dims[3], int B, float* page)
{
  int d[3];
  image->GetDimensions(d);
  vtkDataArray* scalars = image->GetPointData() ? image->GetPointData()->GetScalars() : nullptr;
  if (!scalars || d[0] != dims[0] || d[1] != dims[1] || d[2] != dims[2] || d[0] > B || d[1] > B ||
      d[2] > B || scalars->GetNumberOfTuples() != vtkIdType(d[0]) * d[1] * d[2])
  {
    return false;
  }
  for (int k = 0; k < B; ++k)
    for (int j = 0; j < B; ++j)
      for (int i = 0; i < B; ++i)
      {
        const vtkIdType at =
          (vtkIdType(std::min(k, d[2] - 1)) * d[1] + std::min(j, d[1] - 1)) * d[0] +
          std::min(i, d[0] - 1);
        page[(size_t(k) * B + j) * B + i] = static_cast<float>(scalars->GetComponent(at, 0));
      }
  return true;
}

// Level-of-detail feedback (paged scenes only). Every data fetch of a feedback ray checks the
// cut level of its brick (the index entry it reads anyway) against the level the footprint
// asks for, and the ray keeps the lacking brick that costs it most: the transmittance in front
// of the sample times 2^(levels too coarse), a first-order bound of what the brick's coarseness
// can change in the pixel. Only registers are written per fetch - llvmpipe executes both sides
// of every branch, so the per-sample cost must stay a few selects - and the page id is packed
// once, after the ray: volume i of the fragment is data set uFeedbackSet<i>, uLevelBricks<i>
// holds the bricks per axis of each level, and the level-l brick over level-0 brick b is b >> l
// (vtkVolumeCut::MapToAtlas), with index (z ny + y) nx + x, the tree's node order. Fragments
// compare their best with the texel's through a second (score) image. `footprint`: the wanted
// level follows the pixel footprint (LevelOfDetailThreshold > 0); otherwise level 0 is wanted and
// no footprint code exists.
std::string FeedbackGlobals(bool footprint)
{
  std::ostringstream dec;
  dec << "// Level-of-detail feedback: the costliest lacking brick of the centre ray of every\n"
      << "// uFeedbackScale-th pixel per axis, one texel each.\n"
      << "layout(r32ui) uniform uimage2D uFeedback;\n"
      << "uniform int uFeedbackScale;\n"
      << "layout(r32f) uniform image2D uFeedbackScore; // the reported brick's cost\n"
      << "bool gFeedbackRay = false;\n"
      << "bool gLackFound = false;\n"
      << "float gLackScore = 0.0;\n"
      << "float gTransmittance = 1.0; // in front of the current step\n"
      << "ivec4 gLack = ivec4(0); // level-0 brick, wanted level\n"
      << "int gLackVolume = 0;\n";
  if (footprint)
    dec << "uniform vec3 uFeedbackEye; // local frame\n"
        << "uniform vec2 uFeedbackFootprint; // threshold x pixel size = x + y * distance\n"
        << "float gFootprint = 0.0; // at the current step\n";
  return dec.str();
}

std::string FeedbackVolumeUniforms(const std::string& n, bool footprint)
{
  return "uniform int uFeedbackSet" + n + ";\nuniform int uLevelBricks" + n + "[" +
         std::to_string(3 * FeedbackLevels) + "];\n" +
         (footprint
             ? "uniform vec2 uFeedbackLod" + n + "; // 1 / level-0 voxel size, coarsest level\n"
             : "");
}

// Inside strataScalarAt<n>, after the index entry e of level-0 brick b was fetched. Among
// equal costs the nearer brick wins: the first one front to back, the last one back to front.
std::string FeedbackFetchCheck(const std::string& n, bool frontToBack, bool footprint)
{
  std::string code = "  if (gFeedbackRay)\n  {\n";
  if (footprint)
    code += "    int want = int(clamp(floor(log2(max(gFootprint * uFeedbackLod" + n +
            ".x, 1.0e-30))), 0.0, uFeedbackLod" + n + ".y));\n";
  else
    code += "    int want = 0;\n";
  code += "    float score = e.w != 65535u && e.w > uint(want) ? gTransmittance * "
          "exp2(float(min(int(e.w) - want, 16))) : 0.0;\n"
          "    bool better = score " +
          std::string(frontToBack ? ">" : ">=") +
          " gLackScore && score > 0.0;\n"
          "    gLackFound = gLackFound || better;\n"
          "    gLackScore = better ? score : gLackScore;\n"
          "    gLack = better ? ivec4(b, want) : gLack;\n"
          "    gLackVolume = better ? " +
          n + " : gLackVolume;\n  }\n";
  return code;
}

std::string FeedbackPacking(int k)
{
  std::ostringstream dec;
  dec << vtkFeedbackReduction::GetGLSLPackFunction() << "uint strataLackingPage()\n{\n"
      << "  ivec3 w = gLack.xyz >> gLack.w;\n"
      << "  int g = 3 * gLack.w;\n";
  for (int i = 0; i < k; ++i)
  {
    const std::string n = std::to_string(i);
    dec << "  if (gLackVolume == " << n << ")\n  {\n"
        << "    return strataPackPage(uint(uFeedbackSet" << n
        << "), uint(gLack.w), uint((w.z * uLevelBricks" << n << "[g + 1] + w.y) * uLevelBricks" << n
        << "[g] + w.x));\n  }\n";
  }
  dec << "  return 0u;\n}\n";
  return dec.str();
}

// The fragment shader for k volumes: one unrolled block per volume, the classification's segment
// code and the compositing loop of the order; nothing a fragment does not use.
std::string BuildFragmentShader(int k,
  vtkMultiVolumeRayCastMapper::Classifications classification,
  bool frontToBack,
  bool barrier,
  int rays,
  bool coherence,
  const std::vector<bool>& shaded,
  bool atlas,
  bool skipping,
  bool feedback,
  bool footprint)
{
  using C = vtkMultiVolumeRayCastMapper::Classifications;
  std::string fs = vtkMultiVolumeFragmentFS;
  std::ostringstream dec, seg;
  const std::string K = std::to_string(k);
  for (int i = 0; i < k; ++i)
  {
    const std::string n = std::to_string(i);
    // The data lookup, one function per volume in index coordinates (point (i, j, k) at
    // (i, j, k)): the only code that knows where the voxels live.
    if (atlas)
    {
      if (i == 0)
      {
        dec << "uniform sampler3D uAtlas;\nuniform vec3 uAtlasSize; // texels\n"
            << "uniform float uBrickSize;\n";
        if (feedback)
          dec << FeedbackGlobals(footprint);
      }
      if (feedback)
        dec << FeedbackVolumeUniforms(n, footprint);
      dec << "uniform usampler3D uIndex" << n << ";\n"
          << "uniform vec3 uTableDims" << n << ";\n"
          << "uniform float uEmptyScalar" << n
          << "; // a value the transfer function makes transparent\n"
          << "float strataScalarAt" << n << "(vec3 idx)\n{\n"
          << "  float S = uBrickSize - 1.0;\n"
          << "  vec3 x = clamp(idx, vec3(0.0), uTableDims" << n << " * S);\n"
          << "  ivec3 b = min(ivec3(floor(x / S)), ivec3(uTableDims" << n << ") - 1);\n"
          << "  uvec4 e = texelFetch(uIndex" << n << ", b, 0);\n"
          << (feedback ? FeedbackFetchCheck(n, frontToBack, footprint) : std::string())
          << "  if (e.w >= 65534u)\n  {\n    return uEmptyScalar" << n << ";\n  }\n"
          << "  vec3 t = vec3(e.xyz) * uBrickSize + x * exp2(-float(e.w)) - vec3(b >> int(e.w)) * "
             "S + 0.5;\n"
          << "  return texture(uAtlas, t / uAtlasSize).r;\n}\n";
    }
    else
    {
      dec << "uniform sampler3D uVolume" << n << ";\n"
          << "uniform vec3 uDims" << n << ";\n"
          << "float strataScalarAt" << n << "(vec3 idx)\n{\n"
          << "  return texture(uVolume" << n << ", (idx + 0.5) / uDims" << n << ").r;\n}\n";
    }
    dec << "uniform mat4 uLocalToIndex" << n << ";\n"
        << "uniform float uNearest" << n << "; // 1: nearest-point interpolation\n"
        << "float strataScalar" << n << "(vec3 p)\n{\n"
        << "  vec3 idx = (uLocalToIndex" << n << " * vec4(p, 1.0)).xyz;\n"
        << "  return strataScalarAt" << n << "(mix(idx, floor(idx + 0.5), uNearest" << n
        << "));\n}\n";
    if (shaded[i])
    {
      // Gradient by central differences one voxel apart in texture space, taken to the local
      // frame by the transpose of the local -> texture Jacobian; lit two-sided (a volume's
      // gradient has no inside), Blinn-Phong with the scene's lights.
      dec << "uniform vec4 uMaterial" << n << "; // ambient, diffuse, specular, specular power\n"
          << "vec3 strataShade" << n << "(vec3 p, vec3 color)\n{\n"
          << "  vec3 x = (uLocalToIndex" << n << " * vec4(p, 1.0)).xyz;\n"
          << "  vec3 g = 0.5 * vec3(strataScalarAt" << n
          << "(x + vec3(1.0, 0.0, 0.0)) - strataScalarAt" << n << "(x - vec3(1.0, 0.0, 0.0)),\n"
          << "    strataScalarAt" << n << "(x + vec3(0.0, 1.0, 0.0)) - strataScalarAt" << n
          << "(x - vec3(0.0, 1.0, 0.0)),\n"
          << "    strataScalarAt" << n << "(x + vec3(0.0, 0.0, 1.0)) - strataScalarAt" << n
          << "(x - vec3(0.0, 0.0, 1.0)));\n"
          << "  g = transpose(mat3(uLocalToIndex" << n << ")) * g;\n"
          << "  float len = length(g);\n"
          << "  vec4 m = uMaterial" << n << ";\n"
          << "  if (len <= 0.0)\n  {\n    return color * (m.x + m.y);\n  }\n"
          << "  vec3 N = g / len;\n"
          << "  vec3 diffuse = vec3(0.0);\n  vec3 specular = vec3(0.0);\n"
          << "  for (int l = 0; l < uNumLights; ++l)\n  {\n"
          << "    diffuse += abs(dot(N, uLightDirection[l])) * uLightColor[l];\n"
          << "    vec3 H = normalize(uLightDirection[l] + gViewDirection);\n"
          << "    specular += pow(abs(dot(N, H)), m.w) * uLightColor[l];\n  }\n"
          << "  return color * (m.x + m.y * diffuse) + m.z * specular;\n}\n";
    }
    if (classification == C::PostClassification)
    {
      dec << "uniform sampler2D uTransfer" << n << ";\n"
          << "uniform vec3 uTableRange" << n << ";\n";
    }
    else
    {
      // x = (s - min) * scale in [0, 1] over the table's scalar range; M samples.
      dec << "uniform sampler2D uPreTable" << n << ";\n"
          << "uniform vec3 uPreRange" << n << "; // min, scale, M\n";
      if (classification == C::PreIntegrated)
      {
        dec << "uniform float uPreStep" << n << ";\n"
            << "vec4 strataPre" << n << "(float sf, float sb, float len)\n{\n"
            << "  vec2 x = clamp((vec2(sf, sb) - uPreRange" << n << ".x) * uPreRange" << n
            << ".y, 0.0, 1.0);\n"
            << "  float m = uPreRange" << n << ".z;\n"
            << "  vec4 ca = texture(uPreTable" << n << ", (x * (m - 1.0) + 0.5) / m);\n"
            << "  if (len != uPreStep" << n << ")\n  {\n"
            << "    // A step cut short by a fragment face: opacity corrected to its length.\n"
            << "    float a = 1.0 - pow(max(1.0 - ca.a, 0.0), len / uPreStep" << n << ");\n"
            << "    ca = vec4(ca.a > 0.0 ? ca.rgb * (a / ca.a) : vec3(0.0), a);\n  }\n"
            << "  return ca;\n}\n";
      }
      else
      {
        dec << "uniform float uPreMaxColor" << n << ";\n"
            << "vec4 strataIntegral" << n << "(float x)\n{\n"
            << "  float f = x * (uPreRange" << n << ".z - 1.0);\n"
            << "  int i0 = min(int(floor(f)), int(uPreRange" << n << ".z) - 2);\n"
            << "  return mix(texelFetch(uPreTable" << n
            << ", ivec2(i0, 0), 0), texelFetch(uPreTable" << n
            << ", ivec2(i0 + 1, 0), 0), f - float(i0));\n}\n"
            << "vec4 strataPre" << n << "(float sf, float sb, float len)\n{\n"
            << "  float xf = clamp((sf - uPreRange" << n << ".x) * uPreRange" << n
            << ".y, 0.0, 1.0);\n"
            << "  float xb = clamp((sb - uPreRange" << n << ".x) * uPreRange" << n
            << ".y, 0.0, 1.0);\n"
            << "  float h = 1.0 / (uPreRange" << n << ".z - 1.0);\n"
            << "  float w = max(abs(xb - xf), h);\n"
            << "  float lo = clamp(0.5 * (xf + xb) - 0.5 * w, 0.0, 1.0 - w);\n"
            << "  float hi = lo + w;\n"
            << "  vec4 d = strataIntegral" << n << "(hi) - strataIntegral" << n << "(lo);\n"
            << "  float tau = max(d.a / (hi - lo), 0.0);\n"
            << "  vec3 k = clamp(d.rgb / (hi - lo), vec3(0.0), vec3(uPreMaxColor" << n
            << " * tau));\n"
            << "  float X = len * tau;\n"
            << "  float a = X < 0.01 ? X * (1.0 - X / 2.0 + X * X / 6.0) : 1.0 - exp(-X);\n"
            << "  vec3 c = X < 0.01 ? len * k * (1.0 - X / 2.0 + X * X / 6.0) : len * k * a / X;\n"
            << "  return vec4(c, a);\n}\n";
      }
    }
  }
  bool anyShaded = false;
  for (int i = 0; i < k; ++i)
    anyShaded = anyShaded || shaded[i];
  // The lights come before the volumes' shading functions that read them.
  const std::string lights =
    anyShaded
      ? "uniform int uNumLights;\nuniform vec3 uLightDirection[8]; // towards the light, unit\n"
        "uniform vec3 uLightColor[8];\nvec3 gViewDirection; // towards the eye, set per ray\n"
      : "";
  if (classification == C::PostClassification)
  {
    // Emission and extinction of the mixed media at p, one lattice step of length len.
    seg << "vec4 strataSegment(vec3 p, float len)\n{\n"
        << "  vec3 e = vec3(0.0);\n  float tau = 0.0;\n  vec4 tf;\n";
    for (int i = 0; i < k; ++i)
    {
      const std::string n = std::to_string(i);
      seg << "  tf = texture(uTransfer" << n << ", vec2((strataScalar" << n << "(p) - uTableRange"
          << n << ".x) * uTableRange" << n << ".y + uTableRange" << n << ".z, 0.5));\n";
      if (shaded[i])
        seg << "  if (tf.a > 0.0)\n  {\n    tf.rgb = strataShade" << n << "(p, tf.rgb);\n  }\n";
      seg << "  e += tf.rgb * tf.a;\n  tau += tf.a;\n";
    }
    seg << "  float a = 1.0 - exp(-tau * len);\n"
        << "  return tau > 0.0 ? vec4(e / tau * a, a) : vec4(0.0);\n}\n";
  }
  else
  {
    seg << "void strataSampleAll(vec3 p, out float s[" << K << "])\n{\n";
    for (int i = 0; i < k; ++i)
      seg << "  s[" << i << "] = strataScalar" << i << "(p);\n";
    seg << "}\n";
    seg << "vec4 strataPair(float sf[" << K << "], float sb[" << K
        << "], float len, vec3 mid)\n{\n";
    if (k == 1)
    {
      if (shaded[0])
        seg
          << "  vec4 ca = strataPre0(sf[0], sb[0], len);\n"
          << "  return ca.a > 0.0 ? vec4(strataShade0(mid, ca.rgb / ca.a) * ca.a, ca.a) : ca;\n}\n";
      else
        seg << "  return strataPre0(sf[0], sb[0], len);\n}\n";
    }
    else
    {
      // Overlap: each volume's segment as an optical depth and a mean colour; depths add,
      // colours weighted by depth (exact for one volume, the physical mix for constant media).
      seg << "  float X = 0.0;\n  vec3 e = vec3(0.0);\n  vec4 ca;\n  float x;\n";
      for (int i = 0; i < k; ++i)
      {
        seg << "  ca = strataPre" << i << "(sf[" << i << "], sb[" << i << "], len);\n"
            << "  x = -log(max(1.0 - ca.a, 1.0e-30));\n"
            << "  X += x;\n";
        if (shaded[i])
          seg << "  e += ca.a > 0.0 ? strataShade" << i
              << "(mid, ca.rgb / ca.a) * x : vec3(0.0);\n";
        else
          seg << "  e += ca.a > 0.0 ? ca.rgb / ca.a * x : vec3(0.0);\n";
      }
      seg << "  float a = 1.0 - exp(-X);\n"
          << "  return X > 0.0 ? vec4(e / X * a, a) : vec4(0.0);\n}\n";
    }
  }
  if (skipping)
  {
    // Empty-space skipping: from o + t d, moving along dir d (dir = 1 front to back, -1 back
    // to front), the t at which the ray leaves the empty box around its cell in every volume
    // (t itself if some volume's cell is visible). Cell c with distance D > 0 sits in the
    // empty box of cells c - (D - 1) .. c + (D - 1), index coordinates [lo, hi] below.
    for (int i = 0; i < k; ++i)
    {
      const std::string n = std::to_string(i);
      dec << "uniform usampler3D uSkip" << n << ";\n"
          << "uniform vec4 uSkipGrid" << n << "; // cells per axis, cell size in voxels\n";
    }
    seg << "float strataEmptyUntil(vec3 o, vec3 d, float t, float dir)\n{\n"
        << "  float until = 3.0e38;\n  vec3 x0;\n  vec3 dx;\n  ivec3 c;\n  float D;\n  vec3 lo;\n"
        << "  vec3 hi;\n  vec3 te;\n";
    for (int i = 0; i < k; ++i)
    {
      const std::string n = std::to_string(i);
      seg
        << "  x0 = (uLocalToIndex" << n << " * vec4(o + t * d, 1.0)).xyz;\n"
        << "  dx = dir * (mat3(uLocalToIndex" << n << ") * d);\n"
        << "  c = clamp(ivec3(floor(x0 / uSkipGrid" << n << ".w)), ivec3(0), ivec3(uSkipGrid" << n
        << ".xyz) - 1);\n"
        << "  D = float(texelFetch(uSkip" << n << ", c, 0).r);\n"
        << "  if (D == 0.0)\n  {\n    return t;\n  }\n"
        << "  lo = (vec3(c) - (D - 1.0)) * uSkipGrid" << n << ".w;\n"
        << "  hi = (vec3(c) + D) * uSkipGrid" << n << ".w;\n"
        << "  te = vec3(dx.x > 0.0 ? (hi.x - x0.x) / dx.x : (dx.x < 0.0 ? (lo.x - x0.x) / dx.x : "
           "3.0e38),\n"
        << "    dx.y > 0.0 ? (hi.y - x0.y) / dx.y : (dx.y < 0.0 ? (lo.y - x0.y) / dx.y : 3.0e38),\n"
        << "    dx.z > 0.0 ? (hi.z - x0.z) / dx.z : (dx.z < 0.0 ? (lo.z - x0.z) / dx.z : "
           "3.0e38));\n"
        << "  until = min(until, max(min(te.x, min(te.y, te.z)), 0.0));\n";
    }
    seg << "  return t + dir * until;\n}\n";
  }
  Replace(fs,
    "//STRATA::Extensions::Dec",
    feedback ? "#extension GL_ARB_shader_image_load_store : require\n" : "");
  Replace(fs, "//STRATA::Volumes::Dec", lights + dec.str() + (feedback ? FeedbackPacking(k) : ""));
  Replace(fs, "//STRATA::Segment::Dec", seg.str());
  if (frontToBack)
  {
    std::string dec = "uniform float uTerminationOpacity;\n";
    for (int r = 0; barrier && r < rays; ++r)
      dec += "uniform sampler2D uAccumulation" + std::to_string(r) + ";\n";
    Replace(fs, "//STRATA::Termination::Dec", dec);
    Replace(fs,
      "//STRATA::Termination::Impl",
      "if (prior >= uTerminationOpacity)\n  {\n    return vec4(0.0);\n  }\n"
      "  // This fragment's own opacity at which the whole ray reaches uTerminationOpacity.\n"
      "  float localStop = 1.0 - (1.0 - uTerminationOpacity) / (1.0 - prior);");
  }
  else
  {
    Replace(fs, "//STRATA::Termination::Dec", "");
    Replace(fs, "//STRATA::Termination::Impl", "");
  }
  // Rays: the first (the coherence leader), then the others at their sub-pixel offsets and
  // lattice phases.
  std::ostringstream raysCode;
  raysCode << "float tFirst0;\n  bool inside0;\n";
  for (int r = 0; r < rays; ++r)
  {
    double offset[2];
    vtkMultiVolumeRayCastMapper::GetRayOffset(r, rays, offset);
    const std::string R = std::to_string(r);
    const std::string prior =
      barrier ? "texelFetch(uAccumulation" + R + ", ivec2(gl_FragCoord.xy), 0).a" : "0.0";
    std::ostringstream pixel;
    pixel.precision(9);
    pixel << "gl_FragCoord.xy + vec2(" << offset[0] << ", " << offset[1] << ")";
    if (r == 0)
    {
      if (feedback)
        raysCode << "  gFeedbackRay = all(equal(ivec2(gl_FragCoord.xy) % uFeedbackScale, "
                    "ivec2(uFeedbackScale / 2)));\n";
      raysCode << "  gl_FragData[0] = strataCastRay("
               << (rays > 1 ? pixel.str() : "gl_FragCoord.xy") << ", 0.0, " << prior
               << ", 0.0, tFirst0, inside0);\n";
      if (feedback)
        raysCode << "  gFeedbackRay = false;\n";
      if (rays > 1)
        raysCode << "  float tFirst;\n  bool inside;\n";
      if (rays > 1 && coherence)
        raysCode << "  // Coherence: the others start where the centre ray left empty space.\n"
                 << "  float tStart = inside0 ? tFirst0 : 0.0;\n";
    }
    else
    {
      std::ostringstream phase;
      phase.precision(9);
      phase << double(r) / rays;
      raysCode << "  gl_FragData[" << r << "] = strataCastRay(" << pixel.str() << ", "
               << phase.str() << ", " << prior << ", " << (coherence ? "tStart" : "0.0")
               << ", tFirst, inside);\n";
    }
  }
  if (feedback)
  {
    // The fragment's costliest lacking brick replaces the texel's if it costs more (fragments
    // are drawn one after another with a barrier between; on a tie the nearer one wins).
    raysCode << "  if (gLackFound)\n  {\n"
             << "    ivec2 texel = ivec2(gl_FragCoord.xy) / uFeedbackScale;\n"
             << "    if (gLackScore " << (frontToBack ? ">" : ">=")
             << " imageLoad(uFeedbackScore, texel).r)\n    {\n"
             << "      imageStore(uFeedbackScore, texel, vec4(gLackScore));\n"
             << "      imageStore(uFeedback, texel, uvec4(strataLackingPage(), 0u, 0u, 0u));\n    "
                "}\n  }\n";
  }
  Replace(fs, "//STRATA::Rays::Impl", raysCode.str());
  const bool pre = classification != C::PostClassification;
  std::ostringstream loop;
  if (anyShaded)
  {
    loop << "gViewDirection = -normalize(d);\n  ";
  }
  if (frontToBack)
  {
    loop << "float kk = floor(tEnter / dt - phase);\n";
    if (feedback)
      loop << "  gTransmittance = 1.0 - prior;\n";
    if (skipping)
      loop << "  bool probe = true; // look for empty space: at the start and after transparent "
              "steps\n";
    if (pre)
      loop << "  float sA[" << K << "];\n  float sB[" << K << "];\n"
           << "  strataSampleAll(o + tEnter * d, sA);\n";
    loop << "  for (int it = 0; it < 1048576; ++it)\n  {\n"
         << "    float a = max((kk + phase) * dt, tEnter);\n"
         << "    float b = min((kk + 1.0 + phase) * dt, tExit);\n"
         << "    if (a >= tExit)\n    {\n      break;\n    }\n";
    if (skipping)
    {
      // Jump to the lattice step in which the empty space ends.
      loop << "    float skip = probe ? strataEmptyUntil(o, d, a, 1.0) : a;\n"
           << "    if (skip > b)\n    {\n"
           << "      kk = max(kk + 1.0, floor(skip / dt - phase));\n";
      if (pre)
        loop << "      strataSampleAll(o + min(max((kk + phase) * dt, tEnter), tExit) * d, sA);\n";
      loop << "      continue;\n    }\n";
    }
    loop << "    if (b > a)\n    {\n";
    if (feedback)
      loop << "      gTransmittance = (1.0 - prior) * (1.0 - acc.a);\n";
    if (footprint)
      loop << "      gFootprint = uFeedbackFootprint.x + uFeedbackFootprint.y * distance(o + 0.5 * "
              "(a + b) * d, uFeedbackEye);\n";
    if (pre)
      loop << "      strataSampleAll(o + b * d, sB);\n"
           << "      vec4 c = strataPair(sA, sB, (b - a) * segment, o + 0.5 * (a + b) * d);\n"
           << "      sA = sB;\n";
    else
      loop << "      vec4 c = strataSegment(o + 0.5 * (a + b) * d, (b - a) * segment);\n";
    loop << "      if (c.a > 0.0 && tFirst == tExit)\n      {\n        tFirst = max(a - dt, "
            "tEnter);\n      }\n"
         << (skipping ? "      probe = c.a <= 0.0;\n" : "") << "      acc += (1.0 - acc.a) * c;\n"
         << "      if (acc.a >= localStop)\n      {\n        break;\n      }\n    }\n"
         << "    kk += 1.0;\n  }";
  }
  else
  {
    loop << "float kb = ceil(tExit / dt - phase);\n";
    if (skipping)
      loop << "  bool probe = true;\n";
    if (pre)
      loop << "  float sA[" << K << "];\n  float sB[" << K << "];\n"
           << "  strataSampleAll(o + tExit * d, sB);\n";
    loop << "  for (int it = 0; it < 1048576; ++it)\n  {\n"
         << "    float b = min((kb + phase) * dt, tExit);\n"
         << "    float a = max((kb - 1.0 + phase) * dt, tEnter);\n"
         << "    if (b <= tEnter)\n    {\n      break;\n    }\n";
    if (skipping)
    {
      loop << "    float skip = probe ? strataEmptyUntil(o, d, b, -1.0) : b;\n"
           << "    if (skip < a)\n    {\n"
           << "      kb = min(kb - 1.0, ceil(skip / dt - phase));\n";
      if (pre)
        loop << "      strataSampleAll(o + min(max((kb + phase) * dt, tEnter), tExit) * d, sB);\n";
      loop << "      continue;\n    }\n";
    }
    loop << "    if (b > a)\n    {\n";
    if (footprint)
      loop << "      gFootprint = uFeedbackFootprint.x + uFeedbackFootprint.y * distance(o + 0.5 * "
              "(a + b) * d, uFeedbackEye);\n";
    if (pre)
      loop << "      strataSampleAll(o + a * d, sA);\n"
           << "      vec4 c = strataPair(sA, sB, (b - a) * segment, o + 0.5 * (a + b) * d);\n"
           << "      sB = sA;\n";
    else
      loop << "      vec4 c = strataSegment(o + 0.5 * (a + b) * d, (b - a) * segment);\n";
    loop << "      if (c.a > 0.0)\n      {\n        tFirst = max(a - dt, tEnter);\n      }\n"
         << (skipping ? "      probe = c.a <= 0.0;\n" : "")
         << "      acc = c + (1.0 - c.a) * acc;\n    }\n"
         << "    kb -= 1.0;\n  }";
  }
  Replace(fs, "//STRATA::Composite::Impl", loop.str());
  return fs;
}
}

// One volume of the current frame.
struct StrataVolumeEntry
{
  vtkImageData* Input = nullptr;
  vtkVolumeProperty* Property = nullptr;
  vtkSmartPointer<vtkMatrix4x4> IndexToWorld; ///< prop * image (origin, direction, spacing)
  float LocalToIndex[16];                     ///< the inverse from the local frame, for the GPU
  int Dims[3] = { 0, 0, 0 };
  bool Pooled = false; ///< the data stay in a page pool; Input is a coarse stand-in
};

// GPU resources of one input port.
struct StrataVolumeTextures
{
  vtkSmartPointer<vtkTextureObject> Data;
  vtkTransferFunctionTable Table; ///< the transfer function as the shaders sample it
  vtkMTimeType DataTime = 0;
  vtkImageData* DataInput = nullptr;
  double Range[3] = { 0,
    1,
    0 }; ///< scalar -> table coordinate: (s - Range[0]) * Range[1] + Range[2]
  vtkPreIntegrationTable PreIntegration;
  std::vector<float> Scalars;               ///< the input as float; the brick tree borrows it
  std::unique_ptr<vtkVolumeBrickTree> Tree; ///< bricks and octree (brick atlas on)
  unsigned int IndexTexture = 0;            ///< RGBA16UI, one texel per level-0 brick
  vtkVolumeSkipGrid Skip;                   ///< cell ranges and distances to visible cells
  unsigned int SkipTexture = 0;             ///< R8UI distances, one texel per cell
  unsigned long SkipTime = 0;               ///< distances classified for this table build
  vtkMTimeType SkipDataTime = 0;            ///< cell ranges built from this data
  // Paged volumes: the pool, the pages held for the cut and its ancestors (held pages are never
  // evicted, so a collapse always finds its parent), the root read when the pool was opened.
  std::shared_ptr<vtkPagePoolFile> Pool;
  std::string PoolName;
  std::map<int, vtkPageCache::Page> Held; ///< by node id

  // The largest opacity the linearly interpolated table reaches for scalars in [lo, hi]: the
  // entries whose interpolation intervals meet it (clamped at the ends, as the texture is).
  double MaxOpacity(double lo, double hi) const
  {
    const std::vector<float>& alpha = this->Table.GetOpacity();
    const int n = static_cast<int>(alpha.size());
    if (n == 0)
      return 1.0;
    const double* range = this->Table.GetScalarRange();
    const double scale = (n - 1) / (range[1] - range[0]);
    const double x0 = std::floor((lo - range[0]) * scale);
    const double x1 = std::ceil((hi - range[0]) * scale);
    const int i0 = static_cast<int>(std::min(std::max(x0, 0.0), n - 1.0));
    const int i1 = static_cast<int>(std::min(std::max(x1, 0.0), n - 1.0));
    return *std::max_element(alpha.begin() + i0, alpha.begin() + i1 + 1);
  }
  double EmptyScalar = 0.0; ///< a scalar of zero opacity
  vtkSmartPointer<vtkTextureObject> PreTable;
  unsigned long PreTableCount = 0; ///< build count of the uploaded table
  int PreTableKind = -1;           ///< classification it was uploaded for
};

class vtkMultiVolumeRayCastMapper::vtkInternals
{
public:
  vtkVolumeBSPTree Tree;
  std::map<int, StrataVolumeTextures> Textures; // by input port

  vtkInternals()
  {
    // After a brick loaded on demand: its six neighbours and its parent, ahead of the camera.
    this->Cache.SetNeighbourFunction(
      [this](const vtkPageCache::Key& key, std::vector<vtkPageCache::Key>& more)
      {
        if (!this->Prefetch)
          return;
        std::shared_ptr<vtkPagePoolFile> pool;
        {
          std::lock_guard<std::mutex> lock(this->PoolsMutex);
          auto it = this->PoolsByPort.find(key.Dataset);
          if (it != this->PoolsByPort.end())
            pool = it->second;
        }
        if (!pool || key.Level < 0 || key.Level >= pool->GetNumberOfLevels())
          return;
        const bool parent = key.Level + 1 < pool->GetNumberOfLevels();
        vtkPageCache::AddGridNeighbours(key,
          pool->GetLevel(key.Level).Pages,
          parent ? pool->GetLevel(key.Level + 1).Pages : nullptr,
          more);
      });
    this->Cache.SetLoadFunction(
      [this](const vtkPageCache::Key& key, std::vector<uint8_t>& out, std::string& error)
      {
        std::shared_ptr<vtkPagePoolFile> pool;
        {
          std::lock_guard<std::mutex> lock(this->PoolsMutex);
          auto it = this->PoolsByPort.find(key.Dataset);
          if (it != this->PoolsByPort.end())
            pool = it->second;
        }
        if (!pool)
        {
          error = "no page pool on port " + std::to_string(key.Dataset);
          return false;
        }
        out.resize(pool->GetPageValues() * sizeof(float));
        return pool->ReadPage(
          key.Level, static_cast<uint64_t>(key.Page), reinterpret_cast<float*>(out.data()), &error);
      });
  }
  unsigned int FragmentVAO = 0;
  unsigned int FragmentVBO = 0;
  unsigned int EmptyVAO = 0;
  std::vector<int> FragmentFirst, FragmentCount;
  std::vector<std::array<float, 3>> FragmentCentroid; ///< local frame, for the outline dilation
  std::vector<std::vector<float>> FragmentPlanes;     ///< 4 floats per face, local frame
  std::map<std::string, std::string> ShaderSources;   ///< generated sources by feature key
  bool GeometryValid = false;
  std::vector<vtkSmartPointer<vtkTextureObject>> Accumulation; ///< one integration buffer per ray
  vtkSmartPointer<vtkTextureObject> SceneDepth;
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  std::map<int, std::string> Sources; // fragment shader per number of volumes, last frame
  vtkBrickAtlasAllocator Atlas;
  vtkVolumeCut Cut;
  unsigned int AtlasTexture = 0;
  std::vector<std::pair<int, vtkVolumeBrickTree*>> CutVolumes; // (port, tree) per cut volume
  int AtlasBrickSize = 0;
  int ResidentBricks = 0;
  double AtlasBudget = 0.0;
  vtkShaderProgram* VaoProgram = nullptr; ///< the program the VAO's attribute was set up for
  int LastFragments = 0;

  // Paging: one RAM cache for every pooled volume, keyed (port, level, page in level); the
  // loader finds the pool of a port under a lock (the render thread may open new ones).
  vtkPageCache Cache;
  std::mutex PoolsMutex;
  std::map<int, std::shared_ptr<vtkPagePoolFile>> PoolsByPort;
  vtkMultiVolumeRayCastMapper::PagingStatistics Paging;
  int RequestLimit = 256;              ///< page requests per frame: 4 x PagesPerFrame
  std::atomic<bool> Prefetch{ false }; ///< read by the neighbour function on the workers

  // Level-of-detail feedback: the texture the rays write, the pixel buffer it is read into
  // after the frame (mapped at the next one), and per cut volume and node the pixels that
  // asked for detail below the node (the split priority).
  using ViewKey = std::array<double, 18>; ///< world -> clip, viewport width and height
  unsigned int FeedbackTexture = 0;
  unsigned int FeedbackScoreTexture = 0; ///< R32F: the cost of the brick each texel reports
  unsigned int FeedbackBuffer = 0;
  int FeedbackSize[2] = { 0, 0 };
  bool FeedbackPending = false; ///< the buffer holds a frame not reduced yet
  ViewKey FeedbackView{};       ///< the view that frame was rendered from
  ViewKey LastView{};           ///< the view of the last frame
  vtkFeedbackReduction Reduction;
  std::vector<std::vector<double>> Demand;
  bool FeedbackUnsupportedWarned = false;

  /// The cut's volume number of input port `port` as the last frame drew it, -1 if none.
  int CutVolumeOf(int port) const
  {
    for (size_t v = 0; v < this->CutVolumes.size(); ++v)
      if (this->CutVolumes[v].first == port && static_cast<int>(v) < this->Cut.GetNumberOfVolumes())
        return static_cast<int>(v);
    return -1;
  }

  // Fixed cuts by port ((level, index) per brick), and whether they changed since the cut last
  // followed them; HeldValid: the cut, atlas and index textures are complete for HoldCut.
  std::map<int, std::vector<std::array<int, 2>>> FixedCuts;
  bool FixedCutsChanged = false;
  bool HeldValid = false;

  /// Node of the cut volume that a packed page id names, -1 if none.
  int NodeOf(uint32_t page, int& volume) const
  {
    volume = vtkFeedbackReduction::GetDataSet(page);
    if (volume < 0 || volume >= static_cast<int>(this->CutVolumes.size()))
      return -1;
    const vtkVolumeBrickTree* tree = this->CutVolumes[volume].second;
    const int level = vtkFeedbackReduction::GetLevel(page);
    if (level >= tree->GetNumberOfLevels())
      return -1;
    const int* b = tree->GetLevelBricks(level);
    const uint32_t index = vtkFeedbackReduction::GetPageIndex(page);
    if (index >= static_cast<uint32_t>(b[0]) * b[1] * b[2])
      return -1;
    return tree->GetLevelOffset(level) + static_cast<int>(index);
  }

  /**
   * Maps the pixel buffer of the last frame's feedback, reduces it and raises each node's
   * demand to the pixels that asked for a page strictly below it (PropagateToAncestors less
   * the node's own requests). Returns false when no feedback was pending.
   */
  bool TakeFeedback(bool openCL)
  {
    if (!this->FeedbackPending || !this->FeedbackBuffer)
      return false;
    this->FeedbackPending = false;
    const auto start = std::chrono::steady_clock::now();
    const size_t count = static_cast<size_t>(this->FeedbackSize[0]) * this->FeedbackSize[1];
    std::vector<vtkFeedbackReduction::Entry> asked;
    bool usedOpenCL = false;
    vtkFeedbackReadBack::Map(this->FeedbackBuffer,
      count,
      [&](const uint32_t* ids)
      {
        usedOpenCL = openCL && this->Reduction.ReduceOpenCL(ids, count, asked);
        if (!usedOpenCL)
          this->Reduction.ReduceCPU(ids, count, asked);
      });
    std::vector<vtkFeedbackReduction::Entry> below = asked;
    vtkFeedbackReduction::PropagateToAncestors(below,
      [this](uint32_t page)
      {
        int v = -1;
        const int node = this->NodeOf(page, v);
        const int parent = node < 0 ? -1 : this->CutVolumes[v].second->GetParent(node);
        if (parent < 0)
          return vtkFeedbackReduction::NoPage;
        const vtkVolumeBrickTree* tree = this->CutVolumes[v].second;
        const int level = tree->GetNode(parent).Level;
        return vtkFeedbackReduction::PackPage(
          v, level, static_cast<uint32_t>(parent - tree->GetLevelOffset(level)));
      });
    // Both lists are sorted by page id: one merge subtracts the node's own requests.
    auto own = asked.begin();
    long long pixels = 0;
    for (const auto& e : below)
    {
      while (own != asked.end() && own->Page < e.Page)
        ++own;
      const uint32_t self = own != asked.end() && own->Page == e.Page ? own->Coverage : 0;
      int v = -1;
      const int node = this->NodeOf(e.Page, v);
      if (node >= 0 && v < static_cast<int>(this->Demand.size()))
      {
        double& d = this->Demand[v][node];
        d = std::max(d, static_cast<double>(e.Coverage - self));
      }
    }
    for (const auto& e : asked)
      pixels += e.Coverage;
    this->Paging.FeedbackPages = static_cast<int>(asked.size());
    this->Paging.FeedbackPixels = static_cast<int>(pixels);
    this->Paging.FeedbackOpenCL = usedOpenCL;
    this->Paging.FeedbackMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return true;
  }

  void Release(vtkWindow* window)
  {
    for (auto& t : this->Textures)
    {
      if (t.second.Data)
        t.second.Data->ReleaseGraphicsResources(window);
      t.second.Table.ReleaseGraphicsResources(window);
      if (t.second.PreTable)
        t.second.PreTable->ReleaseGraphicsResources(window);
    }
    for (auto& a : this->Accumulation)
      a->ReleaseGraphicsResources(window);
    if (this->SceneDepth)
      this->SceneDepth->ReleaseGraphicsResources(window);
    if (this->Framebuffer)
      this->Framebuffer->ReleaseGraphicsResources(window);
    this->Accumulation.clear();
    this->SceneDepth = nullptr;
    this->Framebuffer = nullptr;
    for (auto& t : this->Textures)
    {
      if (t.second.IndexTexture)
        glDeleteTextures(1, &t.second.IndexTexture);
      if (t.second.SkipTexture)
        glDeleteTextures(1, &t.second.SkipTexture);
    }
    if (this->AtlasTexture)
      glDeleteTextures(1, &this->AtlasTexture);
    this->AtlasTexture = 0;
    if (this->FeedbackTexture)
      glDeleteTextures(1, &this->FeedbackTexture);
    if (this->FeedbackScoreTexture)
      glDeleteTextures(1, &this->FeedbackScoreTexture);
    this->FeedbackScoreTexture = 0;
    if (this->FeedbackBuffer)
      glDeleteBuffers(1, &this->FeedbackBuffer);
    this->FeedbackTexture = this->FeedbackBuffer = 0;
    this->FeedbackSize[0] = this->FeedbackSize[1] = 0;
    this->FeedbackPending = false;
    this->Demand.clear();
    this->CutVolumes.clear();
    this->Textures.clear();
    if (this->FragmentVAO)
      glDeleteVertexArrays(1, &this->FragmentVAO);
    if (this->EmptyVAO)
      glDeleteVertexArrays(1, &this->EmptyVAO);
    if (this->FragmentVBO)
      glDeleteBuffers(1, &this->FragmentVBO);
    this->FragmentVAO = this->EmptyVAO = this->FragmentVBO = 0;
    this->GeometryValid = false;
    this->VaoProgram = nullptr;
  }
};

vtkStandardNewMacro(vtkMultiVolumeRayCastMapper);

vtkMultiVolumeRayCastMapper::vtkMultiVolumeRayCastMapper()
  : Internals(new vtkInternals)
{
  // A fixed sample distance unless the user asks otherwise: accuracy is a setting, not a
  // by-product of the frame rate.
  this->AutoAdjustSampleDistances = 0;
}

vtkMultiVolumeRayCastMapper::~vtkMultiVolumeRayCastMapper() = default;

void vtkMultiVolumeRayCastMapper::GetRayOffset(int ray, int rays, double offset[2])
{
  // A rotated-grid-like pattern in pixels from the centre; the first R of these for R rays.
  static const double pattern[8][2] = { { 0.0, 0.0 },
    { 0.25, 0.25 },
    { -0.25, -0.25 },
    { 0.375, -0.125 },
    { -0.375, 0.125 },
    { -0.125, 0.375 },
    { 0.125, -0.375 },
    { 0.4375, 0.4375 } };
  // Re-centred so that the mean of the R rays is the pixel centre for every R (otherwise two
  // rays would shift the image by 1/8 pixel).
  const int count = std::min(std::max(rays, 1), 8);
  double mean[2] = { 0.0, 0.0 };
  for (int i = 0; i < count; ++i)
  {
    mean[0] += pattern[i][0] / count;
    mean[1] += pattern[i][1] / count;
  }
  const int r = std::min(std::max(ray, 0), count - 1);
  offset[0] = pattern[r][0] - mean[0];
  offset[1] = pattern[r][1] - mean[1];
}

void vtkMultiVolumeRayCastMapper::SetClassification(Classifications classification)
{
  if (classification != this->Classification)
  {
    this->Classification = classification;
    this->Modified();
  }
}

void vtkMultiVolumeRayCastMapper::SetCompositeOrder(CompositeOrders order)
{
  if (order != this->CompositeOrder)
  {
    this->CompositeOrder = order;
    this->Modified();
  }
}

int vtkMultiVolumeRayCastMapper::GetNumberOfResidentBricks() const
{
  return this->Internals->ResidentBricks;
}

std::vector<int> vtkMultiVolumeRayCastMapper::GetResidentBricksPerLevel(int port) const
{
  const vtkInternals& in = *this->Internals;
  std::vector<int> counts;
  const int v = in.CutVolumeOf(port);
  if (v < 0)
    return counts;
  const vtkVolumeBrickTree* tree = in.CutVolumes[v].second;
  counts.assign(tree->GetNumberOfLevels(), 0);
  for (int n : in.Cut.GetCutNodes(v))
    counts[tree->GetNode(n).Level] += in.Cut.IsEmpty(v, n) ? 0 : 1;
  return counts;
}

int vtkMultiVolumeRayCastMapper::GetNumberOfAtlasSlots() const
{
  return this->Internals->Atlas.GetNumberOfSlots();
}

std::vector<std::array<int, 2>> vtkMultiVolumeRayCastMapper::GetCutBricks(int port) const
{
  const vtkInternals& in = *this->Internals;
  std::vector<std::array<int, 2>> bricks;
  const int v = in.CutVolumeOf(port);
  if (v < 0)
    return bricks;
  const vtkVolumeBrickTree* tree = in.CutVolumes[v].second;
  for (int n : in.Cut.GetCutNodes(v))
  {
    const int level = tree->GetNode(n).Level;
    bricks.push_back({ level, n - tree->GetLevelOffset(level) });
  }
  return bricks;
}

void vtkMultiVolumeRayCastMapper::SetFixedCut(int port,
  const std::vector<std::array<int, 2>>& bricks)
{
  this->Internals->FixedCuts[port] = bricks;
  this->Internals->FixedCutsChanged = true;
  this->Modified();
}

void vtkMultiVolumeRayCastMapper::RemoveAllFixedCuts()
{
  if (this->Internals->FixedCuts.empty())
    return;
  this->Internals->FixedCuts.clear();
  this->Internals->FixedCutsChanged = true;
  this->Modified();
}

int vtkMultiVolumeRayCastMapper::GetNumberOfFragments() const
{
  return this->Internals->LastFragments;
}

std::string vtkMultiVolumeRayCastMapper::GetFragmentShaderSource(int numberOfVolumes) const
{
  auto it = this->Internals->Sources.find(numberOfVolumes);
  return it == this->Internals->Sources.end() ? std::string() : it->second;
}

void vtkMultiVolumeRayCastMapper::GetReductionRatio(double ratio[3])
{
  ratio[0] = ratio[1] = ratio[2] = 1.0;
}

void vtkMultiVolumeRayCastMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->Release(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkMultiVolumeRayCastMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  // A page pool behind an input: ask its reader for the coarsest level only (one page); the
  // ray caster pages the rest itself (see GPURender).
  for (int port = 0; port < this->GetNumberOfInputPorts(); ++port)
  {
    if (this->GetNumberOfInputConnections(port) == 0)
      continue;
    this->GetInputAlgorithm(port, 0)->UpdateInformation();
    vtkPagePoolReader::RequestCoarsestLevel(this->GetInputInformation(port, 0));
  }
  this->Superclass::Render(ren, vol);
}

vtkTypeBool vtkMultiVolumeRayCastMapper::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const vtkTypeBool result = this->Superclass::ProcessRequest(request, inputVector, outputVector);
  // Whatever updates the inputs (GetBounds, the render), a pool's reader serves its coarsest
  // level only: the bricks are paged, not read through the pipeline.
  vtkPagePoolReader::RequestCoarsestLevels(request, inputVector, this->GetNumberOfInputPorts());
  return result;
}

vtkMultiVolumeRayCastMapper::PagingStatistics vtkMultiVolumeRayCastMapper::GetPagingStatistics()
  const
{
  return this->Internals->Paging;
}

void vtkMultiVolumeRayCastMapper::RetryFailedPages()
{
  this->Internals->Cache.RetryAll();
}

void vtkMultiVolumeRayCastMapper::GPURender(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!renWin)
  {
    vtkErrorMacro("vtkMultiVolumeRayCastMapper needs an OpenGL render window.");
    return;
  }
  vtkOpenGLState* state = renWin->GetState();

  // --- The volumes of this frame: a vtkMultiVolume's members on their ports, or one volume.
  std::vector<StrataVolumeEntry> volumes;
  std::vector<int> ports;
  auto* multi = vtkMultiVolume::SafeDownCast(vol);
  const int count = multi ? this->GetInputCount() : 1;
  for (int port = 0; port < this->GetNumberOfInputPorts() && int(ports.size()) < count; ++port)
  {
    if (this->GetNumberOfInputConnections(port) == 0)
    {
      continue;
    }
    vtkVolume* member = multi ? multi->GetVolume(port) : vol;
    auto* image = vtkImageData::SafeDownCast(this->GetTransformedInput(port));
    if (!member || !image || !member->GetProperty())
    {
      continue;
    }
    StrataVolumeEntry e;
    e.Input = image;
    e.Property = member->GetProperty();
    image->GetDimensions(e.Dims);
    const double* o = image->GetOrigin();
    const double* s = image->GetSpacing();
    const double* d = image->GetDirectionMatrix()->GetData();
    // A page pool behind the input (vtkPagePoolReader): its level 0 is the volume, paged.
    // (The image handed over is a transformed copy: the key is read from the pipeline.)
    vtkInformation* portInfo = this->GetInputInformation(port, 0);
    const char* pool = portInfo ? portInfo->Get(vtkPagePoolReader::POOL_FILE_NAME()) : nullptr;
    if (pool && *pool)
    {
      StrataVolumeTextures& tex = in.Textures[port];
      if (tex.PoolName != pool || !tex.Pool)
      {
        auto file = std::make_shared<vtkPagePoolFile>();
        if (!file->Open(pool) || file->GetKind() != vtkPagePoolFormat::Kind::BrickPool)
        {
          vtkErrorMacro("Cannot page the volume on port "
                        << port << " from \"" << pool << "\": "
                        << (file->IsOpen() ? "not a brick pool" : file->GetErrorMessage()));
          continue;
        }
        tex.Pool = file;
        tex.PoolName = pool;
        tex.Tree.reset();
        tex.Held.clear();
        std::lock_guard<std::mutex> lock(in.PoolsMutex);
        in.PoolsByPort[port] = file;
      }
      const vtkPagePoolFile::Header& h = tex.Pool->GetHeader();
      e.Pooled = true;
      std::copy(h.Dimensions, h.Dimensions + 3, e.Dims);
      o = h.Origin;
      s = h.Spacing;
      d = h.Direction;
    }
    // index -> world: prop * [D diag(spacing) | origin].
    vtkNew<vtkMatrix4x4> imageMatrix;
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
        imageMatrix->SetElement(r, c, d[3 * r + c] * s[c]);
      imageMatrix->SetElement(r, 3, o[r]);
    }
    e.IndexToWorld = vtkSmartPointer<vtkMatrix4x4>::New();
    vtkMatrix4x4::Multiply4x4(member->GetMatrix(), imageMatrix, e.IndexToWorld);
    volumes.push_back(e);
    ports.push_back(port);
  }
  // Pools fix the brick size (their page size) and need the atlas.
  int brickSize = this->BrickSize;
  bool anyPooled = false;
  for (size_t v = 0; v < volumes.size(); ++v)
  {
    if (!volumes[v].Pooled)
      continue;
    const int B = in.Textures[ports[v]].Pool->GetPageSize();
    if (anyPooled && B != brickSize)
    {
      vtkErrorMacro(
        "Paged volumes of page sizes " << brickSize << " and " << B << " cannot share one atlas.");
      return;
    }
    brickSize = B;
    anyPooled = true;
  }
  const bool atlas = this->UseBrickAtlas || anyPooled;
  if (volumes.empty())
  {
    return;
  }
  // Feedback ranks the bricks of every volume while any is paged. It needs image load/store,
  // and page ids of 32 bits: at most 62 volumes and 2^21 bricks per level (vtkFeedbackReduction).
  bool idsFit = static_cast<int>(volumes.size()) <= vtkFeedbackReduction::MaxDataSets;
  for (const auto& e : volumes)
  {
    uint64_t bricks = 1;
    for (int a = 0; a < 3; ++a)
      bricks *= e.Dims[a] <= 1
                  ? 1
                  : (static_cast<uint64_t>(e.Dims[a]) - 1 + brickSize - 2) / (brickSize - 1);
    idsFit = idsFit && bricks <= vtkFeedbackReduction::MaxPagesPerLevel;
  }
  const bool imageStore = GLEW_VERSION_4_2 || GLEW_ARB_shader_image_load_store;
  if (anyPooled && this->LevelOfDetailFeedback && (!imageStore || !idsFit) &&
      !in.FeedbackUnsupportedWarned)
  {
    vtkWarningMacro(<< (imageStore ? "More than 62 volumes or 2^21 bricks in a level"
                                   : "No image load/store (OpenGL 4.2)")
                    << ": paging without level-of-detail feedback (the screen-space cut).");
    in.FeedbackUnsupportedWarned = true;
  }
  const bool feedback = anyPooled && this->LevelOfDetailFeedback && imageStore && idsFit;

  // --- BSP over the boxes (index range [0, n-1], or one spacing thick for n == 1).
  std::vector<vtkVolumeBSPTree::Box> boxes;
  for (size_t v = 0; v < volumes.size(); ++v)
  {
    vtkNew<vtkMatrix4x4> unitToIndex;
    for (int a = 0; a < 3; ++a)
    {
      const bool thin = volumes[v].Dims[a] == 1;
      unitToIndex->SetElement(a, a, thin ? 1.0 : volumes[v].Dims[a] - 1.0);
      unitToIndex->SetElement(a, 3, thin ? -0.5 : 0.0);
    }
    vtkNew<vtkMatrix4x4> unitToWorld;
    vtkMatrix4x4::Multiply4x4(volumes[v].IndexToWorld, unitToIndex, unitToWorld);
    vtkVolumeBSPTree::Box box;
    std::copy(unitToWorld->GetData(), unitToWorld->GetData() + 16, box.Matrix.begin());
    box.VolumeId = static_cast<int>(v);
    boxes.push_back(box);
  }
  if (in.Tree.SetBoxes(boxes))
  {
    in.GeometryValid = false;
  }
  in.Tree.Update();
  const auto& origin = in.Tree.GetOrigin();
  const int numFragments = in.Tree.GetNumberOfFragments();

  // --- Fragment faces in one vertex buffer, outward triangles in the local frame.
  if (!in.GeometryValid)
  {
    std::vector<float> verts;
    in.FragmentFirst.assign(numFragments, 0);
    in.FragmentCount.assign(numFragments, 0);
    in.FragmentCentroid.assign(numFragments, { 0.f, 0.f, 0.f });
    in.FragmentPlanes.assign(numFragments, {});
    for (int f = 0; f < numFragments; ++f)
    {
      const auto& frag = in.Tree.GetFragment(f);
      in.FragmentFirst[f] = static_cast<int>(verts.size() / 3);
      for (int idx : frag.Triangles)
      {
        for (int a = 0; a < 3; ++a)
          verts.push_back(static_cast<float>(frag.Vertices[idx][a]));
      }
      in.FragmentCount[f] = static_cast<int>(frag.Triangles.size());
      for (const auto& vtx : frag.Vertices)
        for (int c = 0; c < 3; ++c)
          in.FragmentCentroid[f][c] += static_cast<float>(vtx[c] / frag.Vertices.size());
      for (const auto& plane : frag.Planes)
        for (int c = 0; c < 4; ++c)
          in.FragmentPlanes[f].push_back(static_cast<float>(plane[c]));
    }
    if (!in.FragmentVBO)
    {
      glGenBuffers(1, &in.FragmentVBO);
    }
    glBindBuffer(GL_ARRAY_BUFFER, in.FragmentVBO);
    glBufferData(GL_ARRAY_BUFFER, verts.size() * sizeof(float), verts.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    in.VaoProgram = nullptr;
    in.GeometryValid = true;
  }

  // --- Textures per volume: scalars as R32F (exact for every input type) and the transfer table.
  for (size_t v = 0; v < volumes.size(); ++v)
  {
    StrataVolumeTextures& tex = in.Textures[ports[v]];
    const StrataVolumeEntry& e = volumes[v];
    if (e.Pooled)
    {
      if (!tex.Tree)
      {
        // The structure from the page table: page i is node i, its min/max the node's range.
        const vtkPagePoolFile& file = *tex.Pool;
        std::vector<float> lo(file.GetNumberOfPages()), hi(file.GetNumberOfPages());
        for (uint64_t id = 0; id < file.GetNumberOfPages(); ++id)
        {
          lo[id] = file.GetPageEntry(id).Min;
          hi[id] = file.GetPageEntry(id).Max;
        }
        tex.Tree.reset(new vtkVolumeBrickTree);
        if (!tex.Tree->BuildStructure(e.Dims, brickSize, lo.data(), hi.data()) ||
            static_cast<uint64_t>(tex.Tree->GetNumberOfNodes()) != file.GetNumberOfPages())
        {
          vtkErrorMacro("The pool \"" << tex.PoolName << "\" does not match its brick tree.");
          tex.Tree.reset();
          return;
        }
        tex.SkipDataTime = 0;
        in.CutVolumes.clear();
      }
    }
    else if (tex.Scalars.empty() || tex.DataInput != e.Input || tex.DataTime < e.Input->GetMTime())
    {
      int cellFlag = 0;
      vtkDataArray* scalars = vtkAbstractMapper::GetScalars(
        e.Input, this->ScalarMode, this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
      if (!scalars || cellFlag)
      {
        vtkErrorMacro("Volume on port " << ports[v] << " has no point scalars.");
        return;
      }
      const vtkIdType n = vtkIdType(e.Dims[0]) * e.Dims[1] * e.Dims[2];
      tex.Scalars.resize(n);
      for (vtkIdType i = 0; i < n; ++i)
        tex.Scalars[i] = static_cast<float>(scalars->GetComponent(i, 0));
      tex.DataTime = e.Input->GetMTime();
      tex.DataInput = e.Input;
      tex.Tree.reset();
      if (tex.Data)
      {
        tex.Data->ReleaseGraphicsResources(renWin);
        tex.Data = nullptr;
      }
    }
    if (!e.Pooled && atlas && (!tex.Tree || tex.Tree->GetBrickSize() != brickSize))
    {
      tex.Tree.reset(new vtkVolumeBrickTree);
      if (!tex.Tree->Build(tex.Scalars.data(), e.Dims, brickSize))
      {
        vtkErrorMacro(
          "Cannot brick the volume on port " << ports[v] << ": " << tex.Tree->GetErrorMessage());
        return;
      }
      in.CutVolumes.clear(); // the cut must be rebuilt with this tree
    }
    if (!atlas && !tex.Data)
    {
      tex.Data = vtkSmartPointer<vtkTextureObject>::New();
      tex.Data->SetContext(renWin);
      tex.Data->Create3DFromRaw(e.Dims[0], e.Dims[1], e.Dims[2], 1, VTK_FLOAT, tex.Scalars.data());
      tex.Data->SetWrapS(vtkTextureObject::ClampToEdge);
      tex.Data->SetWrapT(vtkTextureObject::ClampToEdge);
      tex.Data->SetWrapR(vtkTextureObject::ClampToEdge);
      // Nearest volumes snap to voxel centres in the shader: linear filtering serves both.
      tex.Data->SetMinificationFilter(vtkTextureObject::Linear);
      tex.Data->SetMagnificationFilter(vtkTextureObject::Linear);
    }
    if (tex.Table.Update(renWin, e.Property))
    {
      const double* range = tex.Table.GetScalarRange();
      const std::vector<float>& table = tex.Table.GetRGBTau();
      const std::vector<float>& alpha = tex.Table.GetOpacity();
      std::vector<double> rgbD(3 * TransferTableSize), tauD(TransferTableSize);
      for (int i = 0; i < TransferTableSize; ++i)
      {
        for (int c = 0; c < 3; ++c)
          rgbD[3 * i + c] = table[4 * i + c];
        tauD[i] = table[4 * i + 3];
      }
      tex.PreIntegration.SetTransferFunction(
        range[0], range[1], TransferTableSize, rgbD.data(), tauD.data());
      // What the shader reads: for the cut's transparent bricks, the skip grid and the scalar an
      // empty brick reads.
      tex.EmptyScalar = range[0];
      for (int i = 0; i < TransferTableSize; ++i)
      {
        if (alpha[i] <= 0.0f)
        {
          tex.EmptyScalar = range[0] + (range[1] - range[0]) * i / (TransferTableSize - 1.0);
          break;
        }
      }
    }
  }

  // --- Empty-space skipping: cell ranges when the data change, distances when the table does.
  for (size_t v = 0; this->EmptySpaceSkipping && v < volumes.size(); ++v)
  {
    StrataVolumeTextures& tex = in.Textures[ports[v]];
    const bool build = volumes[v].Pooled ? tex.SkipDataTime == 0
                                         : tex.SkipDataTime != tex.DataTime ||
                                             tex.Skip.GetCellSize() != this->SkipCellSize ||
                                             tex.Skip.GetMinima().empty();
    if (build && volumes[v].Pooled)
    {
      // Paged: the level-0 bricks' ranges are the cells (stride B - 1), nothing is read.
      const vtkVolumeBrickTree& tree = *tex.Tree;
      const int* nb = tree.GetLevelBricks(0);
      std::vector<float> lo(tree.GetLevelOffset(0) + size_t(nb[0]) * nb[1] * nb[2]), hi(lo.size());
      for (size_t id = 0; id < lo.size(); ++id)
      {
        lo[id] = tree.GetNode(static_cast<int>(id)).Min;
        hi[id] = tree.GetNode(static_cast<int>(id)).Max;
      }
      tex.Skip.BuildFromRanges(nb, tree.GetBrickStride(), lo.data(), hi.data());
      tex.SkipDataTime = 1;
    }
    else if (build)
    {
      tex.Skip.Build(tex.Scalars.data(), volumes[v].Dims, this->SkipCellSize);
      tex.SkipDataTime = tex.DataTime;
    }
    if (build || tex.SkipTime != tex.Table.GetBuildCount() || !tex.SkipTexture)
    {
      tex.Skip.Classify([&tex](double lo, double hi) { return tex.MaxOpacity(lo, hi); });
      const int* cd = tex.Skip.GetCellDimensions();
      if (!tex.SkipTexture)
        glGenTextures(1, &tex.SkipTexture);
      glBindTexture(GL_TEXTURE_3D, tex.SkipTexture);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTexImage3D(GL_TEXTURE_3D,
        0,
        GL_R8UI,
        cd[0],
        cd[1],
        cd[2],
        0,
        GL_RED_INTEGER,
        GL_UNSIGNED_BYTE,
        tex.Skip.GetDistances().data());
      glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glBindTexture(GL_TEXTURE_3D, 0);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      tex.SkipTime = tex.Table.GetBuildCount();
    }
  }

  // --- Camera, composed in double relative to the tree's local origin.
  int vp[4];
  ren->GetTiledSizeAndOrigin(&vp[2], &vp[3], &vp[0], &vp[1]);
  const int width = vp[2], height = vp[3];
  vtkCamera* camera = ren->GetActiveCamera();
  vtkNew<vtkMatrix4x4> worldToClip, toWorld, localToClip, clipToLocal;
  worldToClip->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1));
  Translation(toWorld, origin);
  vtkMatrix4x4::Multiply4x4(worldToClip, toWorld, localToClip);
  vtkMatrix4x4::Invert(localToClip, clipToLocal);
  // The mapper's clipping planes (world; VTK keeps the side the normal points to) in the
  // fragments' convention, dot(n, p) + w <= 0 inside, in the local frame: each fragment's ray
  // is clipped by them like by its own faces, on the same sample lattice.
  std::vector<float> clipPlanes;
  if (this->ClippingPlanes)
  {
    for (int i = 0; i < this->ClippingPlanes->GetNumberOfItems(); ++i)
    {
      vtkPlane* plane = this->ClippingPlanes->GetItem(i);
      double n[3], o[3];
      plane->GetNormal(n);
      plane->GetOrigin(o);
      double w = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        clipPlanes.push_back(static_cast<float>(-n[c]));
        w += n[c] * (o[c] - origin[c]);
      }
      clipPlanes.push_back(static_cast<float>(w));
    }
  }
  vtkInternals::ViewKey view;
  std::copy(worldToClip->GetData(), worldToClip->GetData() + 16, view.begin());
  view[16] = width;
  view[17] = height;
  const bool moved = view != in.LastView;
  in.LastView = view;
  for (auto& e : volumes)
  {
    // local -> index: IndexToWorld^-1 (local + origin), once per frame for all fragments.
    vtkNew<vtkMatrix4x4> worldToIndex, localToIndex;
    vtkMatrix4x4::Invert(e.IndexToWorld, worldToIndex);
    vtkMatrix4x4::Multiply4x4(worldToIndex, toWorld, localToIndex);
    ToFloat(localToIndex, e.LocalToIndex);
  }

  // --- Brick atlas: the cut through all volumes' octrees for this camera, bricks uploaded
  // into the shared atlas, one index texture per volume.
  bool hold = false;
  if (atlas)
  {
    bool rebuild = in.CutVolumes.size() != volumes.size() || in.AtlasBrickSize != brickSize ||
                   in.AtlasBudget != this->AtlasBudget || !in.AtlasTexture;
    for (size_t v = 0; !rebuild && v < volumes.size(); ++v)
    {
      rebuild = in.CutVolumes[v].first != ports[v] ||
                in.CutVolumes[v].second != in.Textures[ports[v]].Tree.get();
    }
    if (rebuild)
    {
      GLint max3D = 2048;
      glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3D);
      // No larger than every brick of every level: small scenes do not pay for the whole budget.
      double allBricks = 0.0;
      for (size_t v = 0; v < volumes.size(); ++v)
        allBricks += in.Textures[ports[v]].Tree->GetNumberOfNodes();
      const double brickMB = std::pow(double(brickSize), 3) * 4.0 / (1024.0 * 1024.0);
      const double budget = std::min(this->AtlasBudget, (allBricks + 0.5) * brickMB);
      if (!in.Atlas.InitializeFromBudget(budget, brickSize, 4, std::min(max3D, 2048)))
      {
        vtkErrorMacro("An atlas budget of " << this->AtlasBudget << " MB holds no brick of "
                                            << brickSize << "^3 float voxels.");
        return;
      }
      const auto size = in.Atlas.GetTextureSize();
      if (!in.AtlasTexture)
        glGenTextures(1, &in.AtlasTexture);
      glBindTexture(GL_TEXTURE_3D, in.AtlasTexture);
      glTexImage3D(
        GL_TEXTURE_3D, 0, GL_R32F, size[0], size[1], size[2], 0, GL_RED, GL_FLOAT, nullptr);
      glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
      glBindTexture(GL_TEXTURE_3D, 0);
      in.Cut.RemoveAllVolumes();
      in.CutVolumes.clear();
      for (size_t v = 0; v < volumes.size(); ++v)
      {
        vtkVolumeBrickTree* tree = in.Textures[ports[v]].Tree.get();
        in.Cut.AddVolume(tree, volumes[v].IndexToWorld->GetData());
        in.CutVolumes.emplace_back(ports[v], tree);
      }
      in.Cut.SetBudget(in.Atlas.GetNumberOfSlots());
      in.AtlasBrickSize = brickSize;
      for (auto& t : in.Textures)
        t.second.Held.clear(); // a new cut starts from the roots
      in.AtlasBudget = this->AtlasBudget;
      in.Demand.clear();
    }
    // Held (HoldCut): the last render's cut, atlas and index textures as they are.
    hold = this->HoldCut && in.HeldValid && !rebuild;
    if (!hold)
    {
      in.HeldValid = false;
      // Feedback: the last frame's buffer raises the demand of the nodes its rays asked below;
      // demand is kept while the camera is still and halves each frame it moves.
      bool feedbackCurrent = false;
      if (feedback)
      {
        if (in.Demand.size() != volumes.size())
        {
          in.Demand.resize(volumes.size());
          for (size_t v = 0; v < volumes.size(); ++v)
            in.Demand[v].assign(in.CutVolumes[v].second->GetNumberOfNodes(), 0.0);
          in.FeedbackPending = false; // written for another cut
        }
        if (moved)
        {
          for (auto& d : in.Demand)
            for (double& x : d)
              x *= 0.5;
        }
        const bool sameView = in.FeedbackView == view;
        feedbackCurrent = in.TakeFeedback(this->FeedbackOpenCL) && sameView;
      }
      else
      {
        in.Demand.clear();
        in.FeedbackPending = false;
      }
      in.Cut.SetErrorThreshold(feedback ? 0.0 : this->LevelOfDetailThreshold);
      for (size_t v = 0; v < volumes.size(); ++v)
      {
        in.Cut.SetVolumeMatrix(static_cast<int>(v), volumes[v].IndexToWorld->GetData());
        StrataVolumeTextures* tex = &in.Textures[ports[v]];
        in.Cut.SetVolumeOpacity(
          static_cast<int>(v), [tex](double lo, double hi) { return tex->MaxOpacity(lo, hi); });
        if (feedback)
        {
          const std::vector<double>* demand = &in.Demand[v];
          in.Cut.SetVolumePriority(
            static_cast<int>(v), [demand](int node, double) { return (*demand)[node]; });
        }
        else
        {
          in.Cut.SetVolumePriority(static_cast<int>(v), nullptr);
        }
        // A fixed cut: split exactly the strict ancestors of its bricks, first of all.
        const auto fixed = in.FixedCuts.find(ports[v]);
        if (fixed != in.FixedCuts.end())
        {
          const vtkVolumeBrickTree* tree = tex->Tree.get();
          auto split = std::make_shared<std::vector<char>>(tree->GetNumberOfNodes(), 0);
          for (const auto& b : fixed->second)
          {
            if (b[0] < 0 || b[0] >= tree->GetNumberOfLevels() || b[1] < 0)
              continue;
            const int* n = tree->GetLevelBricks(b[0]);
            if (b[1] >= n[0] * n[1] * n[2])
              continue;
            for (int a = tree->GetParent(tree->GetLevelOffset(b[0]) + b[1]); a >= 0 && !(*split)[a];
                 a = tree->GetParent(a))
              (*split)[a] = 1;
          }
          in.Cut.SetVolumePriority(
            static_cast<int>(v), [split](int node, double) { return (*split)[node] ? 1e30 : 0.0; });
        }
        if (volumes[v].Pooled)
        {
          // A brick may enter the cut only with its page in RAM: found now (and pinned for this
          // frame), or queued at the parent's screen-space priority for a later frame.
          const int port = ports[v];
          vtkInternals* internals = &in;
          in.Cut.SetVolumeAvailability(static_cast<int>(v),
            [tex, port, internals](int node, double priority)
            {
              if (tex->Held.count(node))
                return true;
              const auto& n = tex->Tree->GetNode(node);
              vtkPageCache::Key key;
              key.Dataset = port;
              key.Level = n.Level;
              key.Page = node - tex->Tree->GetLevelOffset(n.Level);
              if (vtkPageCache::Page page = internals->Cache.Find(key))
              {
                tex->Held[node] = page;
                return true;
              }
              // Ask for no more than a few frames' worth of uploads at a time: a longer queue
              // would load pages the cache evicts again before the cut can use them.
              if (internals->Paging.MissesThisFrame < internals->RequestLimit)
                internals->Cache.Request(key, priority);
              ++internals->Paging.MissesThisFrame;
              return false;
            });
        }
        else
        {
          in.Cut.SetVolumeAvailability(static_cast<int>(v), nullptr);
        }
      }
      in.Cut.SetMaxNewBricksPerUpdate(anyPooled ? this->PagesPerFrame : 0);
      if (anyPooled)
      {
        in.Cache.SetBudgetMiB(this->PageCacheBudget);
        in.Prefetch = this->Prefetch;
        in.Cache.Start();
        in.Cache.BeginFrame();
        // Roots first, so that a volume is never a hole. The reader was asked for its coarsest
        // level, which is the root page: taken from the input image, no read here. Only an input
        // of other dimensions (a filter between reader and mapper) makes this thread read it.
        for (size_t v = 0; v < volumes.size(); ++v)
        {
          StrataVolumeTextures& tex = in.Textures[ports[v]];
          const int root = volumes[v].Pooled ? tex.Tree->GetRootId() : -1;
          if (root < 0 || tex.Held.count(root))
            continue;
          auto page =
            std::make_shared<std::vector<uint8_t>>(tex.Pool->GetPageValues() * sizeof(float));
          const int level = tex.Tree->GetNode(root).Level;
          if (RootFromImage(volumes[v].Input,
                tex.Tree->GetLevelDimensions(level),
                brickSize,
                reinterpret_cast<float*>(page->data())))
          {
            ++in.Paging.RootPagesFromPipeline;
          }
          else
          {
            std::string error;
            if (!tex.Pool->ReadPage(level, 0, reinterpret_cast<float*>(page->data()), &error))
            {
              vtkErrorMacro("Cannot read the root page of \"" << tex.PoolName << "\": " << error);
              return;
            }
            ++in.Paging.RootPagesRead;
          }
          tex.Held[root] = page;
        }
      }
      const vtkVolumeCut::Camera cutCamera = vtkStrataRenderUtilities::GetCutCamera(ren);
      in.Paging.MissesThisFrame = 0;
      in.RequestLimit = 4 * this->PagesPerFrame;
      if (in.FixedCutsChanged)
      {
        in.Cut.Reset(); // a fixed cut may be coarser than the cut: start from the roots
        in.FixedCutsChanged = false;
      }
      const int entered = in.Cut.Update(cutCamera);
      if (anyPooled)
      {
        // Keep the pages of the cut and of its ancestors (for collapses), release the rest.
        for (size_t v = 0; v < volumes.size(); ++v)
        {
          if (!volumes[v].Pooled)
            continue;
          StrataVolumeTextures& tex = in.Textures[ports[v]];
          vtkCutPages::Prune(tex.Held, in.Cut, static_cast<int>(v), *tex.Tree);
        }
        // Requests this frame's cut did not renew are for views gone by: drop them.
        in.Cache.CancelStale(in.Cache.GetFrame());
        for (const auto& failure : in.Cache.TakeNewFailures())
        {
          vtkErrorMacro("Page " << failure.PageKey.Level << "/" << failure.PageKey.Page
                                << " of the volume on port " << failure.PageKey.Dataset
                                << " failed to load (" << failure.Error
                                << "); showing the coarser level.");
          ++in.Paging.Failures;
        }
        const vtkPageCache::Statistics stats = in.Cache.GetStatistics();
        in.Paging.PendingPages = static_cast<int>(stats.QueueLength + stats.InFlight);
        // The cache's reads plus the root pages, read here or by the readers, a page of floats
        // each.
        in.Paging.BytesRead =
          stats.BytesRead + (in.Paging.RootPagesRead + in.Paging.RootPagesFromPipeline) *
                              static_cast<long long>(std::pow(brickSize, 3) * sizeof(float));
        in.Paging.CacheBytes = static_cast<long long>(stats.CurrentBytes);
        in.Paging.Converged = entered == 0 && in.Paging.MissesThisFrame == 0 &&
                              in.Paging.PendingPages == 0 && (!feedback || feedbackCurrent);
      }
      in.Atlas.BeginFrame();
      std::vector<vtkVolumeCut::Upload> uploads;
      const int missing = in.Cut.AssignSlots(in.Atlas, uploads);
      if (missing > 0)
      {
        vtkWarningMacro(<< missing << " bricks found no atlas slot: raise AtlasBudget.");
      }
      const int B = brickSize;
      std::vector<float> brick(size_t(B) * B * B);
      glBindTexture(GL_TEXTURE_3D, in.AtlasTexture);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      in.Paging.BytesUploaded = 0;
      for (const auto& u : uploads)
      {
        const float* data = brick.data();
        const StrataVolumeTextures& tex = in.Textures[in.CutVolumes[u.Volume].first];
        if (tex.Tree->HasData())
        {
          tex.Tree->ExtractBrick(u.Node, brick.data());
        }
        else
        {
          // Paged: the cut only holds bricks whose pages are held (see the availability).
          auto it = tex.Held.find(u.Node);
          if (it == tex.Held.end())
          {
            vtkErrorMacro("Brick " << u.Node << " entered the cut without its page.");
            std::fill(brick.begin(), brick.end(), static_cast<float>(tex.EmptyScalar));
          }
          else
          {
            data = reinterpret_cast<const float*>(it->second->data());
          }
        }
        const auto pos = in.Atlas.GetSlotPosition(u.Slot);
        glTexSubImage3D(
          GL_TEXTURE_3D, 0, pos[0] * B, pos[1] * B, pos[2] * B, B, B, B, GL_RED, GL_FLOAT, data);
        in.Paging.BytesUploaded += static_cast<long long>(brick.size() * sizeof(float));
      }
      glBindTexture(GL_TEXTURE_3D, 0);
      for (size_t v = 0; v < volumes.size(); ++v)
      {
        StrataVolumeTextures& tex = in.Textures[ports[v]];
        std::vector<uint16_t> table;
        in.Cut.BuildIndexTable(static_cast<int>(v), in.Atlas, table);
        const int* dims = tex.Tree->GetLevelBricks(0);
        if (!tex.IndexTexture)
          glGenTextures(1, &tex.IndexTexture);
        glBindTexture(GL_TEXTURE_3D, tex.IndexTexture);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
        glTexImage3D(GL_TEXTURE_3D,
          0,
          GL_RGBA16UI,
          dims[0],
          dims[1],
          dims[2],
          0,
          GL_RGBA_INTEGER,
          GL_UNSIGNED_SHORT,
          table.data());
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindTexture(GL_TEXTURE_3D, 0);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      }
      in.ResidentBricks = in.Atlas.GetNumberOfUsedSlots();
      in.HeldValid = true;
    }
  }

  // --- Integration buffer and the scene's depth.
  const int rays = this->RaysPerPixel;
  if (!in.Framebuffer)
  {
    in.Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    in.SceneDepth = vtkSmartPointer<vtkTextureObject>::New();
  }
  in.Framebuffer->SetContext(renWin);
  in.SceneDepth->SetContext(renWin);
  if (int(in.SceneDepth->GetWidth()) != width || int(in.SceneDepth->GetHeight()) != height)
  {
    in.SceneDepth->ReleaseGraphicsResources(renWin);
    in.SceneDepth->SetContext(renWin);
    in.SceneDepth->AllocateDepth(width, height, vtkTextureObject::Float32);
  }
  while (static_cast<int>(in.Accumulation.size()) < rays)
  {
    in.Accumulation.push_back(vtkSmartPointer<vtkTextureObject>::New());
  }
  for (int r = 0; r < rays; ++r)
  {
    vtkTextureObject* acc = in.Accumulation[r];
    acc->SetContext(renWin);
    if (int(acc->GetWidth()) != width || int(acc->GetHeight()) != height || !acc->GetHandle())
    {
      acc->ReleaseGraphicsResources(renWin);
      acc->SetContext(renWin);
      acc->Allocate2D(width, height, 4, VTK_FLOAT);
    }
  }
  in.SceneDepth->Activate();
  in.SceneDepth->CopyFromFrameBuffer(vp[0], vp[1], 0, 0, width, height);
  in.SceneDepth->Deactivate();

  const bool frontToBack = this->CompositeOrder == CompositeOrders::FrontToBack;
  // Early termination across fragments reads the integration buffer's own pixel while drawing
  // into it: defined under a texture barrier (each pixel is read and written once per fragment).
  const bool barrier =
    frontToBack && (GLEW_VERSION_4_5 || GLEW_ARB_texture_barrier || GLEW_NV_texture_barrier);

  state->PushFramebufferBindings();
  in.Framebuffer->Bind();
  for (int r = 0; r < rays; ++r)
  {
    in.Framebuffer->AddColorAttachment(r, in.Accumulation[r]);
  }
  in.Framebuffer->ActivateDrawBuffers(rays);
  vtkOpenGLState::ScopedglViewport viewportSaver(state);
  vtkOpenGLState::ScopedglClearColor clearSaver(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendSaver(state);
  vtkOpenGLState::ScopedglEnableDisable blendEnable(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthEnable(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cullEnable(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  state->vtkglViewport(0, 0, width, height);
  state->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglEnable(GL_BLEND);
  if (frontToBack)
  {
    state->vtkglBlendFuncSeparate(GL_ONE_MINUS_DST_ALPHA, GL_ONE, GL_ONE_MINUS_DST_ALPHA, GL_ONE);
  }
  else
  {
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }
  // Back faces: every ray through a convex fragment crosses exactly one, also when the camera is
  // inside it; depth clamping keeps faces beyond the far plane.
  state->vtkglEnable(GL_CULL_FACE);
  state->vtkglCullFace(GL_FRONT);
  glEnable(GL_DEPTH_CLAMP);

  // --- Fragments in order, each with the shader for its number of volumes.
  std::vector<int> order;
  const double* eye = camera->GetPosition();
  const double* dop = camera->GetDirectionOfProjection();
  const vtkVolumeBSPTree::Vector3 eyeV = { eye[0], eye[1], eye[2] };
  const vtkVolumeBSPTree::Vector3 dirV = { dop[0], dop[1], dop[2] };
  if (frontToBack)
    in.Tree.SortFrontToBack(eyeV, camera->GetParallelProjection() != 0, dirV, order);
  else
    in.Tree.SortBackToFront(eyeV, camera->GetParallelProjection() != 0, dirV, order);

  double sampleDistance = this->SampleDistance;
  if (this->AutoAdjustSampleDistances)
  {
    // Half the smallest voxel edge of any volume, in world units.
    sampleDistance = VTK_DOUBLE_MAX;
    for (const auto& e : volumes)
      for (int c = 0; c < 3; ++c)
      {
        const double len = std::sqrt(std::pow(e.IndexToWorld->GetElement(0, c), 2) +
                                     std::pow(e.IndexToWorld->GetElement(1, c), 2) +
                                     std::pow(e.IndexToWorld->GetElement(2, c), 2));
        sampleDistance = std::min(sampleDistance, 0.5 * len);
      }
  }

  // Pre-integration tables, rebuilt only when a transfer function or the step changed.
  if (this->Classification != Classifications::PostClassification)
  {
    const bool full = this->Classification == Classifications::PreIntegrated;
    for (size_t v = 0; v < volumes.size(); ++v)
    {
      StrataVolumeTextures& tex = in.Textures[ports[v]];
      tex.PreIntegration.SetTableSize(this->PreIntegrationTableSize);
      tex.PreIntegration.SetStepLength(sampleDistance);
      if (full)
        tex.PreIntegration.UpdateFullTable();
      else
        tex.PreIntegration.UpdateIntegralTable();
      const unsigned long count = full ? tex.PreIntegration.GetFullTableBuildCount()
                                       : tex.PreIntegration.GetIntegralTableBuildCount();
      const int kind = static_cast<int>(this->Classification);
      if (!tex.PreTable || tex.PreTableCount != count || tex.PreTableKind != kind)
      {
        if (!tex.PreTable)
        {
          tex.PreTable = vtkSmartPointer<vtkTextureObject>::New();
        }
        const int m = tex.PreIntegration.GetTableSize();
        tex.PreTable->SetContext(renWin);
        tex.PreTable->ReleaseGraphicsResources(renWin);
        tex.PreTable->SetContext(renWin);
        const std::vector<float>& data =
          full ? tex.PreIntegration.GetFullTable() : tex.PreIntegration.GetIntegralTable();
        tex.PreTable->Create2DFromRaw(
          m, full ? m : 1, 4, VTK_FLOAT, const_cast<float*>(data.data()));
        tex.PreTable->SetWrapS(vtkTextureObject::ClampToEdge);
        tex.PreTable->SetWrapT(vtkTextureObject::ClampToEdge);
        // The full table is read with bilinear filtering; the integral table with texelFetch
        // and mix in float (filter weights would be amplified by its division).
        tex.PreTable->SetMinificationFilter(
          full ? vtkTextureObject::Linear : vtkTextureObject::Nearest);
        tex.PreTable->SetMagnificationFilter(
          full ? vtkTextureObject::Linear : vtkTextureObject::Nearest);
        tex.PreTableCount = count;
        tex.PreTableKind = kind;
      }
    }
  }
  std::vector<float> lightDirections, lightColors;
  vtkStrataRenderUtilities::GetLights(ren, lightDirections, lightColors);
  const bool lit = ren->GetLights()->GetNumberOfItems() > 0;
  vtkTextureUnitManager* units = renWin->GetTextureUnitManager();
  in.Sources.clear();
  in.LastFragments = 0;

  // Feedback: one R32UI texel per FeedbackScale x FeedbackScale pixels, cleared to 0 (no page),
  // and its R32F cost, on image units 0 and 1 for the whole frame; the ids' pixel buffer is
  // read at the next frame.
  const int feedbackScale = this->FeedbackScale;
  const bool footprint = feedback && this->LevelOfDetailThreshold > 0.0;
  float feedbackFootprint[2] = { 0.f, 0.f };
  float feedbackEye[3] = { 0.f, 0.f, 0.f };
  std::vector<std::array<float, 2>> feedbackLod(volumes.size());
  std::vector<std::vector<int>> levelBricks(volumes.size());
  if (feedback)
  {
    const int fw = (width + feedbackScale - 1) / feedbackScale;
    const int fh = (height + feedbackScale - 1) / feedbackScale;
    const int unit = units->Allocate();
    state->vtkglActiveTexture(GL_TEXTURE0 + unit);
    if (!in.FeedbackTexture || in.FeedbackSize[0] != fw || in.FeedbackSize[1] != fh)
    {
      if (!in.FeedbackTexture)
        glGenTextures(1, &in.FeedbackTexture);
      if (!in.FeedbackScoreTexture)
        glGenTextures(1, &in.FeedbackScoreTexture);
      glBindTexture(GL_TEXTURE_2D, in.FeedbackTexture);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_R32UI, fw, fh, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glBindTexture(GL_TEXTURE_2D, in.FeedbackScoreTexture);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, fw, fh, 0, GL_RED, GL_FLOAT, nullptr);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      vtkFeedbackReadBack::Allocate(in.FeedbackBuffer, size_t(fw) * fh);
      in.FeedbackSize[0] = fw;
      in.FeedbackSize[1] = fh;
      in.FeedbackPending = false;
    }
    const GLuint zero = 0;
    const GLfloat zeroScore = 0.f;
    if (hold)
    {
      // Held: add to what the frame's earlier passes wrote.
    }
    else if (GLEW_VERSION_4_4 || GLEW_ARB_clear_texture)
    {
      glClearTexImage(in.FeedbackTexture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      glClearTexImage(in.FeedbackScoreTexture, 0, GL_RED, GL_FLOAT, &zeroScore);
    }
    else
    {
      // All-zero bits are 0u and 0.0f alike.
      const std::vector<GLuint> zeros(static_cast<size_t>(fw) * fh, 0u);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      glBindTexture(GL_TEXTURE_2D, in.FeedbackTexture);
      glTexSubImage2D(
        GL_TEXTURE_2D, 0, 0, 0, fw, fh, GL_RED_INTEGER, GL_UNSIGNED_INT, zeros.data());
      glBindTexture(GL_TEXTURE_2D, in.FeedbackScoreTexture);
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, fw, fh, GL_RED, GL_FLOAT, zeros.data());
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    units->Free(unit);
    glBindImageTexture(0, in.FeedbackTexture, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(1, in.FeedbackScoreTexture, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    // The size of one pixel at distance r from the eye, times the error threshold: what a
    // voxel of the wanted level may cover.
    const double tau = this->LevelOfDetailThreshold;
    if (camera->GetParallelProjection())
      feedbackFootprint[0] = static_cast<float>(tau * 2.0 * camera->GetParallelScale() / height);
    else
      feedbackFootprint[1] =
        static_cast<float>(tau / vtkVolumeCut::PixelsPerRadian(height, camera->GetViewAngle()));
    for (int c = 0; c < 3; ++c)
      feedbackEye[c] = static_cast<float>(eye[c] - origin[c]);
    for (size_t v = 0; v < volumes.size(); ++v)
    {
      const vtkVolumeBrickTree* tree = in.Textures[ports[v]].Tree.get();
      // The longest level-0 voxel edge over the axes with voxels (vtkVolumeCut's voxel size).
      double longest = 0.0, any = 0.0;
      for (int a = 0; a < 3; ++a)
      {
        const double edge = std::sqrt(std::pow(volumes[v].IndexToWorld->GetElement(0, a), 2) +
                                      std::pow(volumes[v].IndexToWorld->GetElement(1, a), 2) +
                                      std::pow(volumes[v].IndexToWorld->GetElement(2, a), 2));
        any = std::max(any, edge);
        longest = volumes[v].Dims[a] > 1 ? std::max(longest, edge) : longest;
      }
      feedbackLod[v] = { static_cast<float>(
                           1.0 / (longest > 0.0 ? longest : (any > 0.0 ? any : 1.0))),
        static_cast<float>(std::min(tree->GetNumberOfLevels(), FeedbackLevels) - 1) };
      levelBricks[v].assign(3 * FeedbackLevels, 1);
      for (int l = 0; l < tree->GetNumberOfLevels() && l < FeedbackLevels; ++l)
        std::copy(
          tree->GetLevelBricks(l), tree->GetLevelBricks(l) + 3, levelBricks[v].begin() + 3 * l);
    }
  }
  for (int f : order)
  {
    const auto& frag = in.Tree.GetFragment(f);
    const int k = static_cast<int>(frag.BoxIndices.size());
    if (k == 0 || in.FragmentCount[f] == 0)
    {
      continue;
    }
    if (static_cast<int>(frag.Planes.size() + clipPlanes.size() / 4) > MaxPlanes)
    {
      vtkErrorMacro("A BSP fragment has " << frag.Planes.size() << " faces and there are "
                                          << clipPlanes.size() / 4 << " clipping planes; at most "
                                          << MaxPlanes << " in all are supported.");
      continue;
    }
    std::vector<bool> shaded(k);
    bool anyShaded = false;
    for (int i = 0; i < k; ++i)
    {
      shaded[i] = lit && volumes[frag.BoxIndices[i]].Property->GetShade(0) != 0;
      anyShaded = anyShaded || shaded[i];
    }
    // One source per feature set, generated once.
    const bool coherent = this->RayCoherence && rays > 1;
    std::string key =
      std::to_string(k) + "/" + std::to_string(static_cast<int>(this->Classification)) +
      (frontToBack ? "f" : "b") + (barrier ? "t" : "-") + std::to_string(rays) +
      (coherent ? "c" : "-") + (atlas ? "a" : "-") + (this->EmptySpaceSkipping ? "e" : "-") +
      (feedback ? (footprint ? "P" : "F") : "-");
    for (bool sh : shaded)
      key += sh ? 's' : '-';
    std::string& fs = in.ShaderSources[key];
    if (fs.empty())
    {
      fs = BuildFragmentShader(k,
        this->Classification,
        frontToBack,
        barrier,
        rays,
        coherent,
        shaded,
        atlas,
        this->EmptySpaceSkipping,
        feedback,
        footprint);
    }
    vtkShaderProgram* program =
      renWin->GetShaderCache()->ReadyShaderProgram(vtkMultiVolumeFragmentVS, fs.c_str(), "");
    if (!program)
    {
      vtkErrorMacro("The multi-volume shader for " << k << " volumes did not compile or link.");
      break;
    }
    in.Sources[k] = fs;
    if (!in.FragmentVAO)
    {
      glGenVertexArrays(1, &in.FragmentVAO);
    }
    glBindVertexArray(in.FragmentVAO);
    if (in.VaoProgram != program)
    {
      glBindBuffer(GL_ARRAY_BUFFER, in.FragmentVBO);
      const GLint location = glGetAttribLocation(program->GetHandle(), "vertexLocal");
      glEnableVertexAttribArray(location);
      glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
      glBindBuffer(GL_ARRAY_BUFFER, 0);
      in.VaoProgram = program;
    }

    float m[16];
    ToFloat(localToClip, m);
    program->SetUniformMatrix4x4("uLocalToClip", m);
    ToFloat(clipToLocal, m);
    program->SetUniformMatrix4x4("uClipToLocal", m);
    const float viewport[4] = { 0.f, 0.f, float(width), float(height) };
    program->SetUniform4f("uViewport", viewport);
    const float viewportSize[2] = { float(width), float(height) };
    program->SetUniform2f("uViewportSize", viewportSize);
    program->SetUniform3f("uCentroid", in.FragmentCentroid[f].data());
    // Sub-pixel rays reach half a pixel diagonal from the centre: 1.5 pixels of dilation covers
    // them also along edges that are not perpendicular to the direction from the centre.
    program->SetUniformf("uDilate", rays > 1 ? 1.5f : 0.0f);
    program->SetUniformf("uSampleDistance", static_cast<float>(sampleDistance));
    if (feedback)
    {
      program->SetUniformi("uFeedback", 0);
      program->SetUniformi("uFeedbackScore", 1);
      program->SetUniformi("uFeedbackScale", feedbackScale);
      program->SetUniform3f("uFeedbackEye", feedbackEye);
      program->SetUniform2f("uFeedbackFootprint", feedbackFootprint);
      for (int i = 0; i < k; ++i)
      {
        const int v = frag.BoxIndices[i];
        const std::string n = std::to_string(i);
        program->SetUniformi(("uFeedbackSet" + n).c_str(), v);
        program->SetUniform1iv(
          ("uLevelBricks" + n).c_str(), 3 * FeedbackLevels, levelBricks[v].data());
        program->SetUniform2f(("uFeedbackLod" + n).c_str(), feedbackLod[v].data());
      }
    }
    if (anyShaded)
    {
      program->SetUniformi("uNumLights", static_cast<int>(lightDirections.size() / 3));
      if (!lightDirections.empty())
      {
        program->SetUniform3fv("uLightDirection",
          static_cast<int>(lightDirections.size() / 3),
          reinterpret_cast<const float(*)[3]>(lightDirections.data()));
        program->SetUniform3fv("uLightColor",
          static_cast<int>(lightColors.size() / 3),
          reinterpret_cast<const float(*)[3]>(lightColors.data()));
      }
    }
    std::vector<float> planes = in.FragmentPlanes[f];
    planes.insert(planes.end(), clipPlanes.begin(), clipPlanes.end());
    program->SetUniformi("uNumPlanes", static_cast<int>(planes.size() / 4));
    program->SetUniform4fv("uPlanes",
      static_cast<int>(planes.size() / 4),
      reinterpret_cast<const float(*)[4]>(planes.data()));
    in.SceneDepth->Activate();
    program->SetUniformi("uSceneDepth", in.SceneDepth->GetTextureUnit());
    if (frontToBack)
    {
      program->SetUniformf("uTerminationOpacity", static_cast<float>(this->TerminationOpacity));
    }
    for (int r = 0; barrier && r < rays; ++r)
    {
      in.Accumulation[r]->Activate();
      program->SetUniformi(
        ("uAccumulation" + std::to_string(r)).c_str(), in.Accumulation[r]->GetTextureUnit());
    }
    std::vector<int> rawUnits;
    if (atlas)
    {
      const int unit = units->Allocate();
      rawUnits.push_back(unit);
      state->vtkglActiveTexture(GL_TEXTURE0 + unit);
      glBindTexture(GL_TEXTURE_3D, in.AtlasTexture);
      program->SetUniformi("uAtlas", unit);
      const auto size = in.Atlas.GetTextureSize();
      const float atlasSize[3] = { float(size[0]), float(size[1]), float(size[2]) };
      program->SetUniform3f("uAtlasSize", atlasSize);
      program->SetUniformf("uBrickSize", static_cast<float>(brickSize));
    }
    for (int i = 0; i < k; ++i)
    {
      const int v = frag.BoxIndices[i];
      StrataVolumeTextures& tex = in.Textures[ports[v]];
      const StrataVolumeEntry& e = volumes[v];
      const std::string n = std::to_string(i);
      program->SetUniformMatrix4x4(
        ("uLocalToIndex" + n).c_str(), const_cast<float*>(e.LocalToIndex));
      program->SetUniformf(("uNearest" + n).c_str(),
        e.Property->GetInterpolationType() == VTK_NEAREST_INTERPOLATION ? 1.0f : 0.0f);
      if (atlas)
      {
        const int unit = units->Allocate();
        rawUnits.push_back(unit);
        state->vtkglActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_3D, tex.IndexTexture);
        program->SetUniformi(("uIndex" + n).c_str(), unit);
        const int* b = tex.Tree->GetLevelBricks(0);
        const float tableDims[3] = { float(b[0]), float(b[1]), float(b[2]) };
        program->SetUniform3f(("uTableDims" + n).c_str(), tableDims);
        program->SetUniformf(("uEmptyScalar" + n).c_str(), static_cast<float>(tex.EmptyScalar));
      }
      else
      {
        tex.Data->Activate();
        program->SetUniformi(("uVolume" + n).c_str(), tex.Data->GetTextureUnit());
        const float dims[3] = { float(e.Dims[0]), float(e.Dims[1]), float(e.Dims[2]) };
        program->SetUniform3f(("uDims" + n).c_str(), dims);
      }
      if (this->EmptySpaceSkipping)
      {
        const int unit = units->Allocate();
        rawUnits.push_back(unit);
        state->vtkglActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_3D, tex.SkipTexture);
        program->SetUniformi(("uSkip" + n).c_str(), unit);
        const int* cd = tex.Skip.GetCellDimensions();
        const float grid[4] = {
          float(cd[0]), float(cd[1]), float(cd[2]), float(tex.Skip.GetCellSize())
        };
        program->SetUniform4f(("uSkipGrid" + n).c_str(), grid);
      }
      if (shaded[i])
      {
        vtkVolumeProperty* p = e.Property;
        const float material[4] = { float(p->GetAmbient(0)),
          float(p->GetDiffuse(0)),
          float(p->GetSpecular(0)),
          float(p->GetSpecularPower(0)) };
        program->SetUniform4f(("uMaterial" + n).c_str(), material);
      }
      if (this->Classification == Classifications::PostClassification)
      {
        tex.Table.GetTexture()->Activate();
        program->SetUniformi(("uTransfer" + n).c_str(), tex.Table.GetTexture()->GetTextureUnit());
        const double* r = tex.Table.GetTableRange();
        const float range[3] = { float(r[0]), float(r[1]), float(r[2]) };
        program->SetUniform3f(("uTableRange" + n).c_str(), range);
      }
      else
      {
        tex.PreTable->Activate();
        program->SetUniformi(("uPreTable" + n).c_str(), tex.PreTable->GetTextureUnit());
        const double* sr = tex.Table.GetScalarRange();
        const float preRange[3] = {
          float(sr[0]), float(1.0 / (sr[1] - sr[0])), float(tex.PreIntegration.GetTableSize())
        };
        program->SetUniform3f(("uPreRange" + n).c_str(), preRange);
        if (this->Classification == Classifications::PreIntegrated)
          program->SetUniformf(("uPreStep" + n).c_str(), static_cast<float>(sampleDistance));
        else
          program->SetUniformf(
            ("uPreMaxColor" + n).c_str(), static_cast<float>(tex.PreIntegration.GetMaximumColor()));
      }
    }
    glDrawArrays(GL_TRIANGLES, in.FragmentFirst[f], in.FragmentCount[f]);
    if (feedback)
    {
      // The next fragment's comparison must see this one's reports.
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    if (barrier)
    {
      if (GLEW_VERSION_4_5 || GLEW_ARB_texture_barrier)
        glTextureBarrier();
      else
        glTextureBarrierNV();
    }
    for (int i = 0; i < k; ++i)
    {
      StrataVolumeTextures& tex = in.Textures[ports[frag.BoxIndices[i]]];
      if (tex.Data && !atlas)
        tex.Data->Deactivate();
      if (this->Classification == Classifications::PostClassification)
        tex.Table.GetTexture()->Deactivate();
      else
        tex.PreTable->Deactivate();
    }
    for (int r = 0; barrier && r < rays; ++r)
    {
      in.Accumulation[r]->Deactivate();
    }
    for (int unit : rawUnits)
    {
      state->vtkglActiveTexture(GL_TEXTURE0 + unit);
      glBindTexture(GL_TEXTURE_3D, 0);
      units->Free(unit);
    }
    in.SceneDepth->Deactivate();
    glBindVertexArray(0);
    ++in.LastFragments;
  }
  glDisable(GL_DEPTH_CLAMP);
  state->vtkglCullFace(GL_BACK);
  state->PopFramebufferBindings();
  if (feedback)
  {
    // Copied into the pixel buffer now, mapped at the next frame: no wait for the GPU here.
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    vtkFeedbackReadBack::Queue(renWin, in.FeedbackTexture, in.FeedbackBuffer);
    in.FeedbackPending = true;
    in.FeedbackView = view;
  }

  // --- Blend the integration buffer over the scene.
  // The pixel is the mean of its rays' composites.
  std::string compositeFS = vtkMultiVolumeCompositeFS;
  {
    std::ostringstream dec, impl;
    for (int r = 0; r < rays; ++r)
    {
      dec << "uniform sampler2D uAccumulation" << r << ";\n";
      impl << (r ? " + " : "") << "texelFetch(uAccumulation" << r << ", pixel, 0)";
    }
    Replace(compositeFS, "//STRATA::Accumulation::Dec", dec.str());
    Replace(compositeFS,
      "//STRATA::Accumulation::Impl",
      "fragOutput0 = (" + impl.str() + ") / " + std::to_string(rays) + ".0;");
  }
  vtkShaderProgram* composite = renWin->GetShaderCache()->ReadyShaderProgram(
    vtkMultiVolumeCompositeVS, compositeFS.c_str(), "");
  if (composite)
  {
    state->vtkglViewport(vp[0], vp[1], width, height);
    state->vtkglDisable(GL_CULL_FACE);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    for (int r = 0; r < rays; ++r)
    {
      in.Accumulation[r]->Activate();
      composite->SetUniformi(
        ("uAccumulation" + std::to_string(r)).c_str(), in.Accumulation[r]->GetTextureUnit());
    }
    const float vpOrigin[2] = { float(vp[0]), float(vp[1]) };
    composite->SetUniform2f("uViewportOrigin", vpOrigin);
    if (!in.EmptyVAO)
    {
      glGenVertexArrays(1, &in.EmptyVAO);
    }
    glBindVertexArray(in.EmptyVAO);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    for (int r = 0; r < rays; ++r)
    {
      in.Accumulation[r]->Deactivate();
    }
  }
  vtkOpenGLCheckErrorMacro("failed after multi-volume ray casting");
}

void vtkMultiVolumeRayCastMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CompositeOrder: "
     << (this->CompositeOrder == CompositeOrders::FrontToBack ? "FrontToBack" : "BackToFront")
     << "\n";
  os << indent << "Classification: " << static_cast<int>(this->Classification) << "\n";
  os << indent << "PreIntegrationTableSize: " << this->PreIntegrationTableSize << "\n";
  os << indent << "UseBrickAtlas: " << this->UseBrickAtlas << "\n";
  os << indent << "BrickSize: " << this->BrickSize << "\n";
  os << indent << "AtlasBudget: " << this->AtlasBudget << " MB\n";
  os << indent << "RaysPerPixel: " << this->RaysPerPixel << "\n";
  os << indent << "RayCoherence: " << this->RayCoherence << "\n";
  os << indent << "TerminationOpacity: " << this->TerminationOpacity << "\n";
  os << indent << "EmptySpaceSkipping: " << this->EmptySpaceSkipping << "\n";
  os << indent << "SkipCellSize: " << this->SkipCellSize << "\n";
  os << indent << "PageCacheBudget: " << this->PageCacheBudget << " MB\n";
  os << indent << "PagesPerFrame: " << this->PagesPerFrame << "\n";
  os << indent << "Prefetch: " << this->Prefetch << "\n";
  os << indent << "LevelOfDetailFeedback: " << this->LevelOfDetailFeedback << "\n";
  os << indent << "FeedbackScale: " << this->FeedbackScale << "\n";
  os << indent << "FeedbackOpenCL: " << this->FeedbackOpenCL << "\n";
  os << indent << "LevelOfDetailThreshold: " << this->LevelOfDetailThreshold << " pixels\n";
  os << indent << "Fragments (last frame): " << this->Internals->LastFragments << "\n";
}
