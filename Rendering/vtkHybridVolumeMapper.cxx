// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkHybridVolumeMapper.h"

#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkStrataRenderUtilities.h"
#include "vtkTransferFunctionTable.h"

#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPagePoolReader.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "vtkHybridPointsFS.h"
#include "vtkHybridPointsVS.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace
{
void Replace(std::string& source, const std::string& tag, const std::string& code)
{
  const size_t at = source.find(tag);
  if (at != std::string::npos)
    source.replace(at, tag.size(), code);
}

// The point shaders for one shape, with or without shading: nothing else is compiled.
void BuildPointShaders(bool splats, bool shaded, std::string& vs, std::string& fs)
{
  vs = vtkHybridPointsVS;
  fs = vtkHybridPointsFS;
  if (splats)
  {
    // A Gaussian of standard deviation sigma = size / sqrt(2 pi) integrates to size^2, the
    // square's area; the sprite spans +- 3 sigma.
    Replace(vs, "//STRATA::Splat::VSDec", "out float vSigma;\nout float vSide;");
    Replace(vs,
      "//STRATA::Splat::VSImpl",
      "float px = max(size, 1.0);\n"
      "  vSigma = px * 0.3989422804;\n"
      "  vSide = ceil(6.0 * vSigma);\n"
      "  gl_PointSize = vSide;\n"
      "  vColor = vec4(c, a) * min(size * size / (px * px), 1.0);");
    Replace(fs, "//STRATA::Splat::FSDec", "in float vSigma;\nin float vSide;");
    Replace(fs,
      "//STRATA::Splat::FSImpl",
      "vec2 r = (gl_PointCoord - 0.5) * vSide;\n"
      "  gl_FragData[0] = vColor * exp(-dot(r, r) / (2.0 * vSigma * vSigma));");
  }
  else
  {
    Replace(vs, "//STRATA::Splat::VSDec", "");
    Replace(vs,
      "//STRATA::Splat::VSImpl",
      "float side = max(ceil(size), 1.0);\n"
      "  gl_PointSize = side;\n"
      "  vColor = vec4(c, a) * min(size * size / (side * side), 1.0);");
    Replace(fs, "//STRATA::Splat::FSDec", "");
    Replace(fs, "//STRATA::Splat::FSImpl", "gl_FragData[0] = vColor;");
  }
  if (shaded)
  {
    // Two-sided Blinn-Phong with the scene's directional lights, as the ray caster shades.
    Replace(vs,
      "//STRATA::Normal::Dec",
      "in vec3 pointNormal;\n"
      "uniform mat3 uNormalToWorld;\n"
      "uniform vec4 uMaterial; // ambient, diffuse, specular, specular power\n"
      "uniform int uNumLights;\n"
      "uniform vec3 uLightDirection[8];\n"
      "uniform vec3 uLightColor[8];\n"
      "uniform vec3 uViewDirection; // towards the eye");
    Replace(vs,
      "//STRATA::Normal::Impl",
      "vec3 N = normalize(uNormalToWorld * pointNormal);\n"
      "  vec3 diffuse = vec3(0.0);\n  vec3 specular = vec3(0.0);\n"
      "  for (int l = 0; l < uNumLights; ++l)\n  {\n"
      "    diffuse += abs(dot(N, uLightDirection[l])) * uLightColor[l];\n"
      "    specular += pow(abs(dot(N, normalize(uLightDirection[l] + uViewDirection))), "
      "uMaterial.w) * uLightColor[l];\n"
      "  }\n"
      "  c = c * (uMaterial.x + uMaterial.y * diffuse) + uMaterial.z * specular * a;");
  }
  else
  {
    Replace(vs, "//STRATA::Normal::Dec", "");
    Replace(vs, "//STRATA::Normal::Impl", "");
  }
}

void ToFloat(const double m[16], float out[16])
{
  // Row-major double -> column-major float, as glUniformMatrix4fv wants it.
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      out[4 * c + r] = static_cast<float>(m[4 * r + c]);
}
}

class vtkHybridVolumeMapper::vtkInternals
{
public:
  vtkNew<vtkMultiVolumeRayCastMapper> Volume;
  vtkNew<vtkPlaneCollection> Slab;
  vtkNew<vtkPlane> Near;
  vtkNew<vtkPlane> Far;

  // Points on the GPU: position relative to Origin (float keeps UTM-scale scenes precise),
  // value, error, normal.
  vtkPolyData* PointsInput = nullptr;
  vtkMTimeType PointsTime = 0;
  std::array<double, 3> Origin = { 0, 0, 0 };
  std::vector<double> Positions; // double, relative to Origin, for the per-frame depth sort
  bool HasNormals = false;
  unsigned int VBO = 0;
  unsigned int IBO = 0;
  unsigned int VAO = 0;
  vtkShaderProgram* VaoProgram = nullptr;
  vtkIdType Count = 0;
  vtkIdType Drawn = 0;

  vtkTransferFunctionTable Transfer; ///< the volume property's table, as the ray caster's

  std::string VS;
  std::string FS;

  void Release(vtkWindow* window)
  {
    if (this->VBO)
      glDeleteBuffers(1, &this->VBO);
    if (this->IBO)
      glDeleteBuffers(1, &this->IBO);
    if (this->VAO)
      glDeleteVertexArrays(1, &this->VAO);
    this->VBO = this->IBO = this->VAO = 0;
    this->VaoProgram = nullptr;
    this->PointsInput = nullptr;
    this->PointsTime = 0;
    this->Transfer.ReleaseGraphicsResources(window);
  }
};

vtkStandardNewMacro(vtkHybridVolumeMapper);

vtkHybridVolumeMapper::vtkHybridVolumeMapper()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(2);
  this->Internals->Slab->AddItem(this->Internals->Near);
  this->Internals->Slab->AddItem(this->Internals->Far);
}

vtkHybridVolumeMapper::~vtkHybridVolumeMapper() = default;

int vtkHybridVolumeMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

vtkTypeBool vtkHybridVolumeMapper::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const vtkTypeBool result = this->Superclass::ProcessRequest(request, inputVector, outputVector);
  // Whatever updates the input (GetBounds, the render), a pool's reader serves its coarsest
  // level only: the bricks are paged by the volume mapper.
  vtkPagePoolReader::RequestCoarsestLevels(request, inputVector, 1);
  return result;
}

void vtkHybridVolumeMapper::SetPointShape(PointShapes shape)
{
  if (this->PointShape != shape)
  {
    this->PointShape = shape;
    this->Modified();
  }
}

void vtkHybridVolumeMapper::SetPointsInputData(vtkPolyData* points)
{
  this->SetInputDataInternal(1, points);
}

void vtkHybridVolumeMapper::SetPointsInputConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

vtkMultiVolumeRayCastMapper* vtkHybridVolumeMapper::GetVolumeMapper()
{
  return this->Internals->Volume;
}

vtkIdType vtkHybridVolumeMapper::GetNumberOfPointsDrawn() const
{
  return this->Internals->Drawn;
}

std::string vtkHybridVolumeMapper::GetPointVertexShaderSource() const
{
  return this->Internals->VS;
}

std::string vtkHybridVolumeMapper::GetPointFragmentShaderSource() const
{
  return this->Internals->FS;
}

void vtkHybridVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->Release(window);
  this->Internals->Volume->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkHybridVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!renWin)
  {
    vtkErrorMacro("vtkHybridVolumeMapper needs an OpenGL render window.");
    return;
  }
  for (int port = 0; port < 2; ++port)
  {
    if (this->GetNumberOfInputConnections(port) == 0)
      continue;
    this->GetInputAlgorithm(port, 0)->UpdateInformation();
    vtkPagePoolReader::RequestCoarsestLevel(this->GetInputInformation(port, 0));
    this->GetInputAlgorithm(port, 0)->Update();
  }
  auto* low = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  vtkPolyData* points = this->GetNumberOfInputConnections(1) > 0
                          ? vtkPolyData::SafeDownCast(this->GetInputDataObject(1, 0))
                          : nullptr;
  if (!low)
  {
    vtkErrorMacro("No low-resolution volume on input 0.");
    return;
  }
  // A page pool behind input 0: the volume mapper pages it from the reader's output port.
  vtkInformation* lowInfo = this->GetInputInformation(0, 0);
  if (lowInfo && lowInfo->Has(vtkPagePoolReader::POOL_FILE_NAME()))
  {
    if (in.Volume->GetInputConnection(0, 0) != this->GetInputConnection(0, 0))
      in.Volume->SetInputConnection(this->GetInputConnection(0, 0));
  }
  else if (in.Volume->GetInput() != low)
  {
    in.Volume->SetInputData(low);
  }
  in.Volume->HoldCutOff();
  // The user's clipping planes apply to the volume and, through the slabs, to nothing else:
  // points are dropped by the depth sort only.
  vtkNew<vtkPlaneCollection> planes;
  if (this->ClippingPlanes)
  {
    for (int i = 0; i < this->ClippingPlanes->GetNumberOfItems(); ++i)
      planes->AddItem(this->ClippingPlanes->GetItem(i));
  }

  // --- Points: uploaded when they change.
  vtkDataArray* values = points ? points->GetPointData()->GetArray("Value") : nullptr;
  vtkDataArray* errors = points ? points->GetPointData()->GetArray("Error") : nullptr;
  const vtkIdType count = values && errors ? points->GetNumberOfPoints() : 0;
  if (points && count == 0 && points->GetNumberOfPoints() > 0)
  {
    vtkErrorMacro(
      "The points input has no \"Value\" and \"Error\" point data: drawing the volume alone.");
  }
  in.Drawn = 0;
  if (count == 0)
  {
    in.Volume->SetClippingPlanes(planes);
    in.Volume->Render(ren, vol);
    return;
  }
  double cell = this->PointSpacing;
  if (cell <= 0.0)
  {
    vtkDataArray* spacing = points->GetFieldData()->GetArray("PointSpacing");
    if (!spacing || spacing->GetNumberOfTuples() * spacing->GetNumberOfComponents() < 3)
    {
      vtkErrorMacro(
        "No PointSpacing: set it, or give the points field data \"PointSpacing\" (3 values).");
      return;
    }
    double g[3];
    for (int c = 0; c < 3; ++c)
      g[c] = spacing->GetNumberOfComponents() >= 3 ? spacing->GetComponent(0, c)
                                                   : spacing->GetComponent(c, 0);
    cell = std::cbrt(std::abs(g[0] * g[1] * g[2]));
  }
  vtkDataArray* normals = points->GetPointData()->GetArray("Normals");
  vtkVolumeProperty* property = vol->GetProperty();
  const bool shaded = property->GetShade(0) != 0 && normals &&
                      normals->GetNumberOfComponents() == 3 &&
                      ren->GetLights()->GetNumberOfItems() > 0;
  if (in.PointsInput != points || in.PointsTime < points->GetMTime() || in.Count != count ||
      in.HasNormals != shaded)
  {
    double b[6];
    points->GetBounds(b);
    in.Origin = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
    const int stride = shaded ? 8 : 5;
    std::vector<float> vbo(size_t(count) * stride);
    in.Positions.resize(3 * size_t(count));
    for (vtkIdType i = 0; i < count; ++i)
    {
      double p[3];
      points->GetPoint(i, p);
      float* v = &vbo[size_t(i) * stride];
      for (int c = 0; c < 3; ++c)
      {
        in.Positions[3 * size_t(i) + c] = p[c] - in.Origin[c];
        v[c] = static_cast<float>(p[c] - in.Origin[c]);
      }
      v[3] = static_cast<float>(values->GetComponent(i, 0));
      v[4] = static_cast<float>(errors->GetComponent(i, 0));
      for (int c = 0; shaded && c < 3; ++c)
        v[5 + c] = static_cast<float>(normals->GetComponent(i, c));
    }
    if (!in.VBO)
      glGenBuffers(1, &in.VBO);
    glBindBuffer(GL_ARRAY_BUFFER, in.VBO);
    glBufferData(GL_ARRAY_BUFFER, vbo.size() * sizeof(float), vbo.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    in.PointsInput = points;
    in.PointsTime = points->GetMTime();
    in.Count = count;
    in.HasNormals = shaded;
    in.VaoProgram = nullptr;
  }

  // --- The transfer table of the volume property, as the ray caster samples it.
  in.Transfer.Update(renWin, property);

  // --- Slabs: depth along the view direction over the volume's and the points' extent.
  vtkCamera* camera = ren->GetActiveCamera();
  double eye[3], focal[3], dir[3];
  camera->GetPosition(eye);
  camera->GetFocalPoint(focal);
  camera->GetDirectionOfProjection(dir);
  const double* m = vol->GetMatrix()->GetData();
  auto depthOf = [&](const double local[3])
  {
    // local (relative to the points' origin) -> world by the prop's matrix -> depth.
    double d = 0.0;
    for (int r = 0; r < 3; ++r)
    {
      double w = m[4 * r + 3];
      for (int c = 0; c < 3; ++c)
        w += m[4 * r + c] * (local[c] + in.Origin[c]);
      d += (w - eye[r]) * dir[r];
    }
    return d;
  };
  double lo = 1e300, hi = -1e300;
  const double* vb = vol->GetBounds();
  for (int k = 0; k < 8; ++k)
  {
    const double corner[3] = { vb[k & 1], vb[2 + ((k >> 1) & 1)], vb[4 + ((k >> 2) & 1)] };
    double d = 0.0;
    for (int c = 0; c < 3; ++c)
      d += (corner[c] - eye[c]) * dir[c];
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  std::vector<double> depth(static_cast<size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    depth[i] = depthOf(&in.Positions[3 * size_t(i)]);
    lo = std::min(lo, depth[i]);
    hi = std::max(hi, depth[i]);
  }
  const int S = this->NumberOfSlabs;
  const double width = std::max(hi - lo, 1e-300);
  // Counting sort, far to near: slab s (0 nearest) in SubBuckets buckets of its own.
  constexpr int SubBuckets = 64;
  const int buckets = S * SubBuckets;
  std::vector<unsigned int> bucketOf(static_cast<size_t>(count));
  std::vector<size_t> start(buckets + 1, 0);
  for (vtkIdType i = 0; i < count; ++i)
  {
    const int nearToFar =
      std::min(buckets - 1, std::max(0, int((depth[i] - lo) / width * buckets)));
    bucketOf[i] = static_cast<unsigned int>(buckets - 1 - nearToFar);
    ++start[bucketOf[i] + 1];
  }
  for (int k = 0; k < buckets; ++k)
    start[k + 1] += start[k];
  std::vector<unsigned int> order(static_cast<size_t>(count));
  {
    std::vector<size_t> fill(start.begin(), start.end() - 1);
    for (vtkIdType i = 0; i < count; ++i)
      order[fill[bucketOf[i]]++] = static_cast<unsigned int>(i);
  }
  if (!in.IBO)
    glGenBuffers(1, &in.IBO);

  // --- The point program.
  const bool splats = this->PointShape == PointShapes::GaussianSplats;
  BuildPointShaders(splats, shaded, in.VS, in.FS);
  vtkOpenGLState* state = renWin->GetState();
  vtkShaderProgram* program = nullptr;

  // Projection: a cell of size g at clip w covers g * P11 * height / 2 / w pixels.
  int vp[4];
  ren->GetTiledSizeAndOrigin(&vp[2], &vp[3], &vp[0], &vp[1]);
  const double aspect = ren->GetTiledAspectRatio();
  vtkNew<vtkMatrix4x4> toLocal, localToClip;
  vtkMatrix4x4* worldToClip = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  const double p11 = camera->GetProjectionTransformMatrix(aspect, -1, 1)->GetElement(1, 1);
  toLocal->DeepCopy(vol->GetMatrix());
  vtkNew<vtkMatrix4x4> shift;
  for (int c = 0; c < 3; ++c)
    shift->SetElement(c, 3, in.Origin[c]);
  vtkMatrix4x4::Multiply4x4(toLocal, shift, toLocal);
  vtkMatrix4x4::Multiply4x4(worldToClip, toLocal, localToClip);
  float mat[16];
  ToFloat(localToClip->GetData(), mat);
  // The prop's scale: a cell of size g in data units is g times its cube root of |det| in world.
  vtkNew<vtkMatrix4x4> linear;
  linear->DeepCopy(vol->GetMatrix());
  for (int c = 0; c < 3; ++c)
    linear->SetElement(c, 3, 0.0);
  const double scale = std::cbrt(std::abs(linear->Determinant()));

  for (int s = S - 1; s >= 0; --s)
  {
    // The volume between depths lo + s w / S and lo + (s + 1) w / S; the nearest slab is open
    // towards the eye and the farthest away from it.
    vtkNew<vtkPlaneCollection> slabPlanes;
    for (int i = 0; i < planes->GetNumberOfItems(); ++i)
      slabPlanes->AddItem(planes->GetItem(i));
    const double d0 = lo + width * s / S, d1 = lo + width * (s + 1) / S;
    if (s > 0)
    {
      in.Near->SetOrigin(eye[0] + d0 * dir[0], eye[1] + d0 * dir[1], eye[2] + d0 * dir[2]);
      in.Near->SetNormal(dir);
      slabPlanes->AddItem(in.Near);
    }
    if (s < S - 1)
    {
      in.Far->SetOrigin(eye[0] + d1 * dir[0], eye[1] + d1 * dir[1], eye[2] + d1 * dir[2]);
      in.Far->SetNormal(-dir[0], -dir[1], -dir[2]);
      slabPlanes->AddItem(in.Far);
    }
    in.Volume->SetClippingPlanes(slabPlanes);
    in.Volume->Render(ren, vol);
    in.Volume->HoldCutOn(); // one cut for the whole frame

    // Then the slab's points, far to near, over it.
    const size_t first = start[size_t(S - 1 - s) * SubBuckets];
    const size_t last = start[size_t(S - s) * SubBuckets];
    if (last == first)
      continue;
    if (!program)
    {
      program = renWin->GetShaderCache()->ReadyShaderProgram(in.VS.c_str(), in.FS.c_str(), "");
      if (!program)
      {
        vtkErrorMacro("The hybrid point shader did not compile or link.");
        return;
      }
      if (!in.VAO)
        glGenVertexArrays(1, &in.VAO);
      glBindVertexArray(in.VAO);
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, in.IBO);
      glBufferData(
        GL_ELEMENT_ARRAY_BUFFER, order.size() * sizeof(unsigned int), order.data(), GL_STREAM_DRAW);
      if (in.VaoProgram != program)
      {
        glBindBuffer(GL_ARRAY_BUFFER, in.VBO);
        const GLsizei stride = (shaded ? 8 : 5) * sizeof(float);
        auto attribute = [&](const char* name, int size, size_t offset)
        {
          const GLint location = glGetAttribLocation(program->GetHandle(), name);
          if (location >= 0)
          {
            glEnableVertexAttribArray(location);
            glVertexAttribPointer(location,
              size,
              GL_FLOAT,
              GL_FALSE,
              stride,
              reinterpret_cast<const void*>(offset * sizeof(float)));
          }
        };
        attribute("vertexLocal", 3, 0);
        attribute("pointValue", 1, 3);
        attribute("pointError", 1, 4);
        if (shaded)
          attribute("pointNormal", 3, 5);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        in.VaoProgram = program;
      }
      program->SetUniformMatrix4x4("uLocalToClip", mat);
      program->SetUniformf("uCellSize", static_cast<float>(cell * scale));
      program->SetUniformf("uPixelsPerUnit", static_cast<float>(p11 * vp[3] / 2.0));
      in.Transfer.GetTexture()->Activate();
      program->SetUniformi("uTransfer", in.Transfer.GetTexture()->GetTextureUnit());
      const float range[3] = { float(in.Transfer.GetTableRange()[0]),
        float(in.Transfer.GetTableRange()[1]),
        float(in.Transfer.GetTableRange()[2]) };
      program->SetUniform3f("uTableRange", range);
      if (shaded)
      {
        std::vector<float> lightDirections, lightColors;
        vtkStrataRenderUtilities::GetLights(ren, lightDirections, lightColors);
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
        // Normals go to world by the inverse transpose of the prop's linear part.
        vtkNew<vtkMatrix4x4> inv;
        vtkMatrix4x4::Invert(linear, inv);
        float n3[9];
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            n3[3 * c + r] = static_cast<float>(inv->GetElement(c, r)); // column-major transpose
        program->SetUniformMatrix3x3("uNormalToWorld", n3);
        const float material[4] = { float(property->GetAmbient(0)),
          float(property->GetDiffuse(0)),
          float(property->GetSpecular(0)),
          float(property->GetSpecularPower(0)) };
        program->SetUniform4f("uMaterial", material);
        const float view[3] = { float(-dir[0]), float(-dir[1]), float(-dir[2]) };
        program->SetUniform3f("uViewDirection", view);
      }
    }
    else
    {
      renWin->GetShaderCache()->ReadyShaderProgram(program, nullptr);
      glBindVertexArray(in.VAO);
      in.Transfer.GetTexture()->Activate();
      program->SetUniformi("uTransfer", in.Transfer.GetTexture()->GetTextureUnit());
    }
    vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
    vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglDepthMask depthMask(state);
    vtkOpenGLState::ScopedglBlendFuncSeparate blendFunc(state);
    state->vtkglEnable(GL_BLEND);
    state->vtkglEnable(GL_DEPTH_TEST);
    state->vtkglDepthMask(GL_FALSE);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glDrawElements(GL_POINTS,
      static_cast<GLsizei>(last - first),
      GL_UNSIGNED_INT,
      reinterpret_cast<const void*>(first * sizeof(unsigned int)));
    glDisable(GL_PROGRAM_POINT_SIZE);
    glBindVertexArray(0);
    in.Transfer.GetTexture()->Deactivate();
    in.Drawn += static_cast<vtkIdType>(last - first);
  }
  in.Volume->SetClippingPlanes(planes);
}

void vtkHybridVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "PointShape: " << (this->PointShape == PointShapes::Squares ? "Squares" : "GaussianSplats")
     << "\n";
  os << indent << "NumberOfSlabs: " << this->NumberOfSlabs << "\n";
  os << indent << "PointSpacing: " << this->PointSpacing << "\n";
}
