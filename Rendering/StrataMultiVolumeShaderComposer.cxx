// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataMultiVolumeShaderComposer.h"

#include "StrataBrickAtlasTexture.h"
#include "StrataFeedbackReduction.h"
#include "StrataShaderCache.h"

#include "vtkMultiVolumeBackToFront.h"
#include "vtkMultiVolumeComponentsAtlasLookup.h"
#include "vtkMultiVolumeComponentsColorOpacity.h"
#include "vtkMultiVolumeComponentsIndependent.h"
#include "vtkMultiVolumeComponentsIndependentTable.h"
#include "vtkMultiVolumeComponentsLookup.h"
#include "vtkMultiVolumeComponentsRGBA.h"
#include "vtkMultiVolumeCompositeFS.h"
#include "vtkMultiVolumeCompositeVS.h"
#include "vtkMultiVolumeCrop.h"
#include "vtkMultiVolumeFeedback.h"
#include "vtkMultiVolumeFeedbackCheck.h"
#include "vtkMultiVolumeFragmentFS.h"
#include "vtkMultiVolumeFragmentVS.h"
#include "vtkMultiVolumeFrontToBack.h"
#include "vtkMultiVolumeGradientOpacity.h"
#include "vtkMultiVolumeIso.h"
#include "vtkMultiVolumeLayerDec.h"
#include "vtkMultiVolumeLayerVolume.h"
#include "vtkMultiVolumePair.h"
#include "vtkMultiVolumePlainLookup.h"
#include "vtkMultiVolumePreIntegrated.h"
#include "vtkMultiVolumePreIntegratedApproximate.h"
#include "vtkMultiVolumeReduce.h"
#include "vtkMultiVolumeReduceDec.h"
#include "vtkMultiVolumeSample.h"
#include "vtkMultiVolumeSegment.h"
#include "vtkMultiVolumeSegmentComponents.h"
#include "vtkMultiVolumeSegmentVolume.h"
#include "vtkMultiVolumeShade.h"
#include "vtkMultiVolumeSkip.h"
#include "vtkMultiVolumeSkipUniforms.h"
#include "vtkMultiVolumeSkipVolume.h"
#include "vtkMultiVolumeSurfaces.h"

#include "vtkVolumeMapper.h"

#include <algorithm>
#include <sstream>
#include <tuple>

namespace strata
{

namespace
{
using Key = MultiVolumeShaderComposer::FragmentKey;
using C = MultiVolumeShaderComposer::Classifications;
constexpr int FeedbackLevels = strata::FeedbackReduction::MaxLevels;

void Replace(std::string& source, const std::string& tag, const std::string& code)
{
  strata::ShaderCache<int>::Replace(source, tag, code);
}

/// `n` copies of `zero` joined by commas: the body of an array constructor, so that a GLSL
/// array is initialised where it is declared (`float[3](0.0, 0.0, 0.0)`).
std::string Zeros(const std::string& zero, int n)
{
  std::string list;
  for (int i = 0; i < n; ++i)
    list += (i ? ", " : "") + zero;
  return list;
}

/// A per-volume snippet for volume `n` of the fragment.
std::string ForVolume(const char* snippet, int n)
{
  std::string code = snippet;
  Replace(code, "@n@", std::to_string(n));
  return code;
}

bool AnyShaded(const Key& key)
{
  for (bool s : key.Shaded)
    if (s)
      return true;
  return false;
}

// --- Blend modes. Composite volumes are the media; an isosurface volume is sampled for its
// contours; the others are reduced by a pass of their own and read here as layers.
int Mode(const Key& key, int n)
{
  return n < static_cast<int>(key.Modes.size()) ? key.Modes[n] : vtkVolumeMapper::COMPOSITE_BLEND;
}

bool IsReduced(int mode)
{
  return mode == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ||
         mode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND ||
         mode == vtkVolumeMapper::AVERAGE_INTENSITY_BLEND ||
         mode == vtkVolumeMapper::ADDITIVE_BLEND;
}

/// Whether the program samples volume n (a reduction pass samples its one volume).
bool Sampled(const Key& key, int n)
{
  return key.Reduce || !IsReduced(Mode(key, n));
}

bool Medium(const Key& key, int n)
{
  return !key.Reduce && Mode(key, n) == vtkVolumeMapper::COMPOSITE_BLEND;
}

bool IsIso(const Key& key, int n)
{
  return !key.Reduce && Mode(key, n) == vtkVolumeMapper::ISOSURFACE_BLEND;
}

int CountIf(const Key& key, bool (*test)(const Key&, int))
{
  int count = 0;
  for (int i = 0; i < key.Volumes; ++i)
    count += test(key, i) ? 1 : 0;
  return count;
}

bool IsLayer(const Key& key, int n)
{
  return !Sampled(key, n);
}

bool GradientOpacity(const Key& key, int n)
{
  return n < static_cast<int>(key.GradientOpacity.size()) && key.GradientOpacity[n] &&
         Medium(key, n) && key.Classification == C::PostClassification;
}

bool Cropped(const Key& key, int n)
{
  return n < static_cast<int>(key.Cropped.size()) && key.Cropped[n];
}

// --- Components: a volume of several reads them from its own texture and classifies them into
// one medium (strataMedium@n@: colour and extinction) by its component mode.
using Comps = MultiVolumeShaderComposer::Components;

Comps ComponentMode(const Key& key, int n)
{
  return n < static_cast<int>(key.ComponentModes.size()) ? key.ComponentModes[n] : Comps::One;
}

bool HasComponents(const Key& key, int n)
{
  return ComponentMode(key, n) != Comps::One;
}

/// Whether component c of volume n is read: not an independent component of weight 0.
bool Heard(const Key& key, int n, int c)
{
  return n >= static_cast<int>(key.SilentComponents.size()) ||
         !(key.SilentComponents[n] & (1 << c));
}

/// Independent components: a table per component (component 0's is the volume's uTransfer@n@);
/// a component of weight 0 has none.
std::string IndependentMedium(const Key& key, int n, int count)
{
  std::string dec, impl;
  for (int i = 0; i < count; ++i)
  {
    if (!Heard(key, n, i))
      continue;
    const std::string c = i == 0 ? std::string() : "_" + std::to_string(i);
    dec += "uniform sampler2D uTransfer@n@" + c + ";\nuniform vec3 uTableRange@n@" + c + ";\n";
    std::string table = vtkMultiVolumeComponentsIndependentTable;
    Replace(table, "@c@", c);
    Replace(table, "@i@", std::to_string(i));
    impl += table;
  }
  std::string code = vtkMultiVolumeComponentsIndependent;
  Replace(code, "//STRATA::ComponentTables::Dec", dec);
  Replace(code, "//STRATA::ComponentTables::Impl", impl);
  return ForVolume(code.c_str(), n);
}

std::string Lookup(const Key& key, int n, bool first);
std::string FeedbackFetchCheck(const Key& key, int n, int component = 0);

/// The feedback rays' number of component c of fragment volume n (gLackVolume); n < 64, as a
/// fragment has at most the 62 volumes feedback can name (strata::FeedbackReduction::MaxDataSets).
int LackId(int n, int c)
{
  return n + 64 * c;
}

/// Several components in the atlas: a lookup per component, each reporting its own lacking
/// bricks to feedback (data set uFeedbackSet<n>c<c>, the component's volume in the pager), and
/// their vector.
std::string ComponentAtlasLookups(const Key& key, int n, bool first)
{
  const bool normalized = n < static_cast<int>(key.Normalized.size()) && key.Normalized[n];
  std::string code = Lookup(key, n, first);
  std::string fetches = ForVolume("strataScalarAt@n@(idx)", n);
  const int count = MultiVolumeShaderComposer::GetNumberOfComponents(ComponentMode(key, n));
  for (int c = 1; c < 4; ++c)
  {
    const std::string name = std::to_string(n) + "c" + std::to_string(c);
    const bool read = c < count && Heard(key, n, c);
    if (read && key.Feedback)
      code += "uniform int uFeedbackSet" + name + ";\n";
    if (read)
      code += strata::BrickAtlasTexture::GetLookupFunction(
        name, key.Feedback ? FeedbackFetchCheck(key, n, c) : "", normalized);
    fetches += read ? ", strataScalarAt" + name + "(idx)" : std::string(", 0.0");
  }
  std::string vector = ForVolume(vtkMultiVolumeComponentsAtlasLookup, n);
  Replace(vector, "//STRATA::ComponentFetches::Impl", fetches);
  return code + vector;
}

/// Volumes::Dec of a volume of several components: its lookup (plain texture or atlas),
/// cropping and medium.
std::string ComponentVolume(const Key& key, int n, bool first)
{
  std::string code =
    key.Atlas ? ComponentAtlasLookups(key, n, first) : ForVolume(vtkMultiVolumeComponentsLookup, n);
  if (Cropped(key, n))
    code += ForVolume(vtkMultiVolumeCrop, n);
  const Comps mode = ComponentMode(key, n);
  switch (mode)
  {
    case Comps::ColorOpacity:
      return code + ForVolume(vtkMultiVolumeComponentsColorOpacity, n);
    case Comps::RGBA:
      return code + ForVolume(vtkMultiVolumeComponentsRGBA, n);
    default:
      return code +
             IndependentMedium(key, n, MultiVolumeShaderComposer::GetNumberOfComponents(mode));
  }
}

/// The factor that masks volume n's contribution at `point` by its cropping ("" if uncropped).
std::string CropMask(const Key& key, int n, const std::string& point)
{
  return Cropped(key, n) ? ForVolume(" * strataCrop@n@(", n) + point + ")" : std::string();
}

// --- Feedback (paged scenes). Every data fetch of a feedback ray checks the cut level of its
// brick (the index entry it reads anyway) against the level the footprint asks for, and the
// ray keeps the lacking brick that costs it most: the transmittance in front of the sample
// times 2^(levels too coarse), a first-order bound of what the brick's coarseness can change in
// the pixel. Only registers are written per fetch - llvmpipe executes both sides of every
// branch, so the per-sample cost must stay a few selects - and the page id is packed once,
// after the ray: volume i of the fragment is data set uFeedbackSet<i>, uLevelBricks<i> holds
// the bricks per axis of each level, and the level-l brick over level-0 brick b is b >> l
// (strata::VolumeCut::MapToAtlas), with index (z ny + y) nx + x, the tree's node order. Fragments
// compare their best with the texel's through a second (score) image. With Footprint the
// wanted level follows the pixel footprint (LevelOfDetailThreshold > 0); otherwise level 0 is
// wanted and no footprint code exists.
std::string FeedbackGlobals(const Key& key)
{
  std::string code = vtkMultiVolumeFeedback;
  Replace(code,
    "//STRATA::Footprint::Dec",
    key.Footprint
      ? "uniform vec3 uFeedbackEye; // local frame\n"
        "uniform vec2 uFeedbackFootprint; // threshold x pixel size = x + y * distance\n"
        "float gFootprint = 0.0; // at the current step\n"
      : "");
  return code;
}

std::string FeedbackVolumeUniforms(const Key& key, int n)
{
  const std::string N = std::to_string(n);
  return "uniform int uFeedbackSet" + N + ";\nuniform int uLevelBricks" + N + "[" +
         std::to_string(3 * FeedbackLevels) + "];\n" +
         (key.Footprint
             ? "uniform vec2 uFeedbackLod" + N + "; // 1 / level-0 voxel size, coarsest level\n"
             : "");
}

// Inside the atlas lookup, after the index entry e of level-0 brick b was fetched. Among equal
// costs the nearer brick wins: the first one front to back, the last one back to front.
std::string FeedbackFetchCheck(const Key& key, int n, int component)
{
  std::string code = vtkMultiVolumeFeedbackCheck;
  Replace(code, "better ? @n@ :", "better ? " + std::to_string(LackId(n, component)) + " :");
  code = ForVolume(code.c_str(), n);
  Replace(code, "@better@", key.FrontToBack ? ">" : ">=");
  Replace(code,
    "//STRATA::Want::Impl",
    key.Footprint
      ? ForVolume("int want = int(clamp(floor(log2(max(gFootprint * uFeedbackLod@n@.x, 1.0e-30))), "
                  "0.0, uFeedbackLod@n@.y));",
          n)
      : "int want = 0;");
  return code;
}

std::string FeedbackPacking(const Key& key)
{
  std::ostringstream dec;
  dec << strata::FeedbackReduction::GetGLSLPackFunction() << "uint strataLackingPage()\n{\n"
      << "  ivec3 w = gLack.xyz >> gLack.w;\n"
      << "  int g = 3 * gLack.w;\n";
  for (int i = 0; i < key.Volumes; ++i)
  {
    if (!Sampled(key, i))
      continue;
    const int count =
      key.Atlas ? MultiVolumeShaderComposer::GetNumberOfComponents(ComponentMode(key, i)) : 1;
    for (int c = 0; c < count; ++c)
    {
      if (!Heard(key, i, c))
        continue;
      std::string branch =
        "  if (gLackVolume == @id@)\n  {\n    return strataPackPage(uint(uFeedbackSet@set@), "
        "uint(gLack.w), uint((w.z * uLevelBricks@n@[g + 1] + w.y) * "
        "uLevelBricks@n@[g] + w.x));\n  }\n";
      Replace(branch, "@id@", std::to_string(LackId(i, c)));
      Replace(branch, "@set@", c == 0 ? "@n@" : "@n@c" + std::to_string(c));
      dec << ForVolume(branch.c_str(), i);
    }
  }
  dec << "  return 0u;\n}\n";
  return dec.str();
}

// --- The data: the lookup (atlas or plain texture), the sample at a point, shading.
std::string Lookup(const Key& key, int n, bool first)
{
  const bool normalized = n < static_cast<int>(key.Normalized.size()) && key.Normalized[n];
  if (!key.Atlas)
  {
    std::string code = vtkMultiVolumePlainLookup;
    Replace(code,
      "//STRATA::Decode::Dec",
      normalized ? "uniform vec2 uDecode@n@; // value = texel x + y (strata::BrickAtlasFormat)"
                 : "");
    Replace(code, "@decode@", normalized ? " * uDecode@n@.x + uDecode@n@.y" : "");
    return ForVolume(code.c_str(), n);
  }
  std::string code;
  if (first)
  {
    code += strata::BrickAtlasTexture::GetShaderDeclarations();
    if (key.Feedback)
      code += FeedbackGlobals(key);
  }
  if (key.Feedback)
    code += FeedbackVolumeUniforms(key, n);
  return code + strata::BrickAtlasTexture::GetLookupFunction(
                  n, key.Feedback ? FeedbackFetchCheck(key, n) : "", normalized);
}

std::string Lights(const Key& key)
{
  return AnyShaded(key) ? "uniform int uNumLights;\n"
                          "uniform vec3 uLightDirection[8]; // towards the light, unit\n"
                          "uniform vec3 uLightColor[8];\n"
                          "vec3 gViewDirection = vec3(0.0); // towards the eye, set per ray\n"
                        : "";
}

// --- Classification: the transfer table (post) or the pre-integration table of a volume.
std::string Classification(const Key& key, int n)
{
  switch (key.Classification)
  {
    case C::PostClassification:
      return ForVolume("uniform sampler2D uTransfer@n@;\nuniform vec3 uTableRange@n@;\n", n);
    case C::PreIntegrated:
      return ForVolume(vtkMultiVolumePreIntegrated, n);
    case C::PreIntegratedApproximate:
      return ForVolume(vtkMultiVolumePreIntegratedApproximate, n);
  }
  return std::string();
}

std::string SkipUniforms(const Key& key)
{
  std::string code;
  for (int i = 0; key.Skipping && i < key.Volumes; ++i)
    if (Sampled(key, i))
      code += ForVolume(vtkMultiVolumeSkipUniforms, i);
  return code;
}

// A reduced volume read as a layer: its table, one sampler per ray, and its state to colour.
std::string LayerVolume(const Key& key, int n)
{
  std::string samplers;
  for (int r = 0; r < key.Rays; ++r)
    samplers += "uniform sampler2D uLayer@n@_" + std::to_string(r) + ";\n";
  std::string color;
  switch (Mode(key, n))
  {
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      color =
        "vec4 tf = textureLod(uTransfer@n@, vec2((st.x - uTableRange@n@.x) * uTableRange@n@.y + "
        "uTableRange@n@.z, 0.5), 0.0);\n  float alpha = 1.0 - exp(-tf.a * uUnit@n@);\n"
        "  color = vec4(tf.rgb * alpha, alpha);\n  return st.w > 0.0 ? st.z : 3.0e38;";
      break;
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      color = "float g = st.y > 0.0 ? clamp(st.x / st.y, 0.0, 1.0) : 0.0;\n"
              "  color = vec4(vec3(g), 1.0);\n  return st.y > 0.0 ? st.z : 3.0e38;";
      break;
    default: // additive
      color = "float g = clamp(st.x, 0.0, 1.0);\n"
              "  color = vec4(vec3(g), 1.0);\n  return st.w > 0.0 ? st.z : 3.0e38;";
  }
  std::string code = vtkMultiVolumeLayerVolume;
  Replace(code, "//STRATA::LayerSamplers::Dec", samplers);
  Replace(code, "//STRATA::LayerColor::Impl", color);
  return ForVolume(code.c_str(), n);
}

std::string IsoVolume(const Key& key, int n)
{
  std::string code = ForVolume(vtkMultiVolumeIso, n);
  Replace(code,
    "//STRATA::IsoCrop::Impl",
    Cropped(key, n) ? ForVolume("alpha *= strataCrop@n@(mix(pa, pb, (v - sa) / (sb - sa)));", n)
                    : "");
  Replace(code,
    "//STRATA::IsoShade::Impl",
    key.Shaded[n] ? ForVolume("rgb = strataShade@n@(mix(pa, pb, (v - sa) / (sb - sa)), rgb);", n)
                  : "");
  return code;
}

/// Volumes::Dec: the scene's lights, then per volume its lookup, sample, shading and table (or
/// its contours, or its layer).
std::string Volumes(const Key& key)
{
  std::string code = Lights(key);
  bool first = true;
  for (int i = 0; i < key.Volumes; ++i)
  {
    if (!Sampled(key, i))
    {
      code += LayerVolume(key, i);
      continue;
    }
    if (HasComponents(key, i))
    {
      code += ComponentVolume(key, i, first);
      first = first && !key.Atlas;
      continue;
    }
    code += Lookup(key, i, first);
    first = false;
    code += ForVolume(vtkMultiVolumeSample, i);
    if (Cropped(key, i))
      code += ForVolume(vtkMultiVolumeCrop, i);
    if (GradientOpacity(key, i))
      code += ForVolume(vtkMultiVolumeGradientOpacity, i);
    if (key.Shaded[i])
      code += ForVolume(vtkMultiVolumeShade, i);
    if (key.Reduce)
    {
      code += vtkMultiVolumeReduceDec;
      for (int r = 0; r < key.Rays; ++r)
        code += "uniform sampler2D uAccumulation" + std::to_string(r) + ";\n";
    }
    else if (IsIso(key, i))
      code += IsoVolume(key, i);
    else
      code += Classification(key, i);
  }
  const int layers = CountIf(key, IsLayer);
  if (layers > 0)
  {
    std::string dec = vtkMultiVolumeLayerDec;
    Replace(dec, "@L0@", Zeros("0.0", layers));
    Replace(dec, "@L0V@", Zeros("vec4(0.0)", layers));
    Replace(dec, "@L@", std::to_string(layers));
    code += dec;
  }
  code += SkipUniforms(key);
  if (key.Feedback)
    code += FeedbackPacking(key);
  return code;
}

// --- The segment of one lattice step: the mixed media of all volumes at its midpoint (post)
// or between the scalars at both ends (pre-integrated).
bool PreIntegrated(const Key& key)
{
  return key.Classification != C::PostClassification && CountIf(key, Medium) > 0;
}

std::string Segment(const Key& key)
{
  const int k = key.Volumes;
  if (key.Reduce || CountIf(key, Medium) == 0)
    return std::string();
  if (!PreIntegrated(key))
  {
    std::string volumes;
    for (int i = 0; i < k; ++i)
    {
      if (!Medium(key, i))
        continue;
      std::string v = ForVolume(
        HasComponents(key, i) ? vtkMultiVolumeSegmentComponents : vtkMultiVolumeSegmentVolume, i);
      Replace(v,
        "//STRATA::Shade::Impl",
        (GradientOpacity(key, i)
            ? ForVolume("tf.a = tf.a > 0.0 ? strataGradientTau@n@(p, tf.a) : 0.0;\n  ", i)
            : std::string()) +
          (Cropped(key, i) ? "tf.a = tf.a" + CropMask(key, i, "p") + ";\n  " : std::string()) +
          (key.Shaded[i]
              ? ForVolume("if (tf.a > 0.0)\n  {\n    tf.rgb = strataShade@n@(p, tf.rgb);\n  }", i)
              : ""));
      volumes += v;
    }
    std::string code = vtkMultiVolumeSegment;
    Replace(code, "//STRATA::SegmentVolumes::Impl", volumes);
    return code;
  }
  const std::string K = std::to_string(k);
  std::string code = "void strataSampleAll(vec3 p, out float s[" + K + "])\n{\n";
  // Every element written: an out array is copied back whole (the others are never read).
  for (int i = 0; i < k; ++i)
    code += ForVolume(Medium(key, i) ? "  s[@n@] = strataScalar@n@(p);\n" : "  s[@n@] = 0.0;\n", i);
  code += "}\n";
  if (k == 1)
  {
    code += "vec4 strataPair(float sf[1], float sb[1], float len, vec3 mid)\n{\n";
    code += "  vec4 ca = strataPre0(sf[0], sb[0], len)" + CropMask(key, 0, "mid") + ";\n";
    code +=
      key.Shaded[0]
        ? "  return ca.a > 0.0 ? vec4(strataShade0(mid, ca.rgb / ca.a) * ca.a, ca.a) : ca;\n}\n"
        : "  return ca;\n}\n";
    return code;
  }
  std::string volumes;
  for (int i = 0; i < k; ++i)
  {
    if (!Medium(key, i))
      continue;
    volumes += ForVolume(("ca = strataPre@n@(sf[@n@], sb[@n@], len)" + CropMask(key, i, "mid") +
                           ";\n  x = -log(max(1.0 - ca.a, 1.0e-30));\n  X += x;\n")
                           .c_str(),
      i);
    volumes +=
      key.Shaded[i]
        ? ForVolume(
            "  e += ca.a > 0.0 ? strataShade@n@(mid, ca.rgb / ca.a) * x : vec3(0.0);\n  ", i)
        : "  e += ca.a > 0.0 ? ca.rgb / ca.a * x : vec3(0.0);\n  ";
  }
  std::string pair = vtkMultiVolumePair;
  Replace(pair, "@K@", K);
  Replace(pair, "//STRATA::PairVolumes::Impl", volumes);
  return code + pair;
}

std::string Skipping(const Key& key)
{
  if (!key.Skipping)
    return std::string();
  std::string volumes;
  for (int i = 0; i < key.Volumes; ++i)
    if (Sampled(key, i))
      volumes += ForVolume(vtkMultiVolumeSkipVolume, i);
  std::string code = vtkMultiVolumeSkip;
  Replace(code, "//STRATA::SkipVolumes::Impl", volumes);
  return code;
}

// --- Termination (front to back): the fragment's share of the termination opacity.
void Termination(const Key& key, std::string& fs)
{
  if (!key.FrontToBack || key.Reduce)
  {
    Replace(fs, "//STRATA::Termination::Dec", "");
    Replace(fs, "//STRATA::Termination::Impl", "");
    return;
  }
  std::string dec = "uniform float uTerminationOpacity;\n";
  for (int r = 0; key.Barrier && r < key.Rays; ++r)
    dec += "uniform sampler2D uAccumulation" + std::to_string(r) + ";\n";
  Replace(fs, "//STRATA::Termination::Dec", dec);
  Replace(fs,
    "//STRATA::Termination::Impl",
    "if (prior >= uTerminationOpacity)\n  {\n    return vec4(0.0);\n  }\n"
    "  // This fragment's own opacity at which the whole ray reaches uTerminationOpacity.\n"
    "  float localStop = 1.0 - (1.0 - uTerminationOpacity) / (1.0 - prior);");
}

// --- Rays: the first (the coherence leader, the feedback ray), then the others at their
// sub-pixel offsets and lattice phases; then the fragment's feedback report.
// Before ray r: a reduction pass reads the ray's state so far, an integration pass the
// layers of its reduced volumes.
std::string RayPrologue(const Key& key, int r)
{
  const std::string R = std::to_string(r);
  if (key.Reduce)
    return "  gState = texelFetch(uAccumulation" + R + ", ivec2(gl_FragCoord.xy), 0);\n";
  std::string code;
  for (int i = 0, j = 0; i < key.Volumes; ++i)
  {
    if (!IsLayer(key, i))
      continue;
    const std::string J = std::to_string(j++);
    code += ForVolume(("  gLayerT[" + J + "] = strataLayer@n@(texelFetch(uLayer@n@_" + R +
                        ", ivec2(gl_FragCoord.xy), 0), gLayerC[" + J + "]);\n")
                        .c_str(),
      i);
  }
  return code;
}

// A reduction pass keeps the state of a ray that misses the fragment.
std::string RayStore(const Key& key, int r, const std::string& call)
{
  const std::string R = std::to_string(r);
  if (!key.Reduce)
    return "  gl_FragData[" + R + "] = " + call + ";\n";
  return "  {\n    vec4 state = " + call + ";\n    gl_FragData[" + R +
         "] = " + (r == 0 ? "inside0" : "inside") + " ? state : gState;\n  }\n";
}

// --- Surface layers (strata::VolumeSurfaceLayers): what ray r composited so far is 3 bits of the
// progress texel, at 8^r; the fragment adds what it took, in draw buffer `Rays`.
std::string SurfacePrologue(const Key& key, int r)
{
  if (key.Surfaces == 0)
    return std::string();
  const std::string scale = std::to_string(1 << (3 * r)) + ".0";
  return "  gSurfaceNext = int(mod(floor(surfaceProgress / " + scale +
         "), 8.0));\n"
         "  int surfaceStart" +
         std::to_string(r) + " = gSurfaceNext;\n";
}

std::string SurfaceEpilogue(const Key& key, int r)
{
  if (key.Surfaces == 0)
    return std::string();
  const std::string scale = std::to_string(1 << (3 * r)) + ".0";
  return "  surfacesTaken += float(gSurfaceNext - surfaceStart" + std::to_string(r) + ") * " +
         scale + ";\n";
}

std::string SurfaceRaysStart(const Key& key)
{
  if (key.Surfaces == 0)
    return std::string();
  return "  float surfaceProgress = texelFetch(uSurfaceProgress, ivec2(gl_FragCoord.xy), 0).r;\n"
         "  float surfacesTaken = 0.0;\n";
}

std::string SurfaceRaysEnd(const Key& key)
{
  if (key.Surfaces == 0)
    return std::string();
  return "  gl_FragData[" + std::to_string(key.Rays) + "] = vec4(surfacesTaken, 0.0, 0.0, 0.0);\n";
}

std::string Rays(const Key& key)
{
  const int rays = key.Rays;
  std::ostringstream code;
  code << "float tFirst0 = 0.0;\n  bool inside0 = false;\n" << SurfaceRaysStart(key);
  for (int r = 0; r < rays; ++r)
  {
    double offset[2];
    vtkMultiVolumeRayCastMapper::GetRayOffset(r, rays, offset);
    const std::string R = std::to_string(r);
    const std::string prior =
      key.Barrier ? "texelFetch(uAccumulation" + R + ", ivec2(gl_FragCoord.xy), 0).a" : "0.0";
    std::ostringstream pixel;
    pixel.precision(9);
    pixel << "gl_FragCoord.xy + vec2(" << offset[0] << ", " << offset[1] << ")";
    if (r == 0)
    {
      if (key.Feedback)
        code << "  gFeedbackRay = all(equal(ivec2(gl_FragCoord.xy) % uFeedbackScale, "
                "ivec2(uFeedbackScale / 2)));\n";
      code << RayPrologue(key, 0) << SurfacePrologue(key, 0)
           << RayStore(key,
                0,
                "strataCastRay(" + (rays > 1 ? pixel.str() : std::string("gl_FragCoord.xy")) +
                  ", 0.0, " + prior + ", 0.0, tFirst0, inside0)")
           << SurfaceEpilogue(key, 0);
      if (key.Feedback)
        code << "  gFeedbackRay = false;\n";
      if (rays > 1)
        code << "  float tFirst = 0.0;\n  bool inside = false;\n";
      if (rays > 1 && key.Coherent)
        code << "  // Coherence: the others start where the centre ray left empty space.\n"
             << "  float tStart = inside0 ? tFirst0 : 0.0;\n";
      continue;
    }
    std::ostringstream phase;
    phase.precision(9);
    phase << double(r) / rays;
    code << RayPrologue(key, r) << SurfacePrologue(key, r)
         << RayStore(key,
              r,
              "strataCastRay(" + pixel.str() + ", " + phase.str() + ", " + prior + ", " +
                (key.Coherent ? "tStart" : "0.0") + ", tFirst, inside)")
         << SurfaceEpilogue(key, r);
  }
  code << SurfaceRaysEnd(key);
  if (key.Feedback)
  {
    // The fragment's costliest lacking brick replaces the texel's if it costs more (fragments
    // are drawn one after another with a barrier between; on a tie the nearer one wins).
    code << "  if (gLackFound)\n  {\n"
         << "    ivec2 texel = ivec2(gl_FragCoord.xy) / uFeedbackScale;\n"
         << "    if (gLackScore " << (key.FrontToBack ? ">" : ">=")
         << " imageLoad(uFeedbackScore, texel).r)\n    {\n"
         << "      imageStore(uFeedbackScore, texel, vec4(gLackScore));\n"
         << "      imageStore(uFeedback, texel, uvec4(strataLackingPage(), 0u, 0u, 0u));\n    }\n  "
            "}\n";
  }
  return code.str();
}

// --- Compositing: the loop over lattice steps in the key's order, with exactly the skipping,
// feedback and classification code it uses.
std::string ReduceStep(const Key& key)
{
  switch (Mode(key, 0))
  {
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      return "if (state.w == 0.0 || s > state.x)\n      {\n        state = vec4(s, 0.0, t, 1.0);\n"
             "      }";
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      return "if (state.w == 0.0 || s < state.x)\n      {\n        state = vec4(s, 0.0, t, 1.0);\n"
             "      }";
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      return "if (s >= uAverageRange0.x && s <= uAverageRange0.y)\n      {\n"
             "        float len = (b - a) * segment;\n"
             "        state.x += strataOpacity0(s) * (s - uNormalize0.x) * uNormalize0.y * len;\n"
             "        state.y += len;\n      }";
    default: // additive
      return "state.x += strataOpacity0(s) * (s - uNormalize0.x) * uNormalize0.y * (b - a) * "
             "segment / uUnit0;";
  }
}

// --- A reduction pass: volume 0 alone, every step, the state carried across fragments. The
// depth of an average or additive layer is the midpoint of the ray's first step in the volume
// (strictly inside the fragment, so the integration pass finds it in the same fragment).
std::string Reduce(const Key& key)
{
  const int mode = Mode(key, 0);
  std::string start;
  if (mode == vtkVolumeMapper::AVERAGE_INTENSITY_BLEND || mode == vtkVolumeMapper::ADDITIVE_BLEND)
    start += "float tIn = 0.5 * (max((kk + phase) * dt, tEnter) + min((kk + 1.0 + phase) * dt, "
             "tExit));\n  state.z = state.w > 0.0 ? min(state.z, tIn) : tIn;\n  state.w = 1.0;\n  ";
  std::string skip;
  if (key.Skipping)
  {
    start += "bool probe = true;\n";
    skip = "float skip = probe ? strataEmptyUntil(o, d, a, 1.0) : a;\n    if (skip > b)\n    {\n"
           "      kk = max(kk + 1.0, floor(skip / dt - phase));\n      continue;\n    }";
  }
  std::string loop = vtkMultiVolumeReduce;
  Replace(loop, "//STRATA::Start::Impl", start);
  Replace(loop, "//STRATA::Skip::Impl", skip);
  Replace(loop,
    "//STRATA::Reduce::Impl",
    Cropped(key, 0)
      ? "if (strataCrop0(o + t * d) > 0.0)\n      {\n      " + ReduceStep(key) + "\n      }"
      : ReduceStep(key));
  return loop;
}

// Layers that lie in this fragment stay pending; the others are marked done.
std::string LayerStart(const Key& key)
{
  const int layers = CountIf(key, IsLayer);
  if (layers == 0)
    return std::string();
  return "for (int j = 0; j < " + std::to_string(layers) +
         "; ++j)\n  {\n    if (gLayerT[j] < tEnter || gLayerT[j] >= tExit)\n    {\n"
         "      gLayerT[j] = " +
         (key.FrontToBack ? "3.0e38" : "-3.0e38") + ";\n    }\n  }\n  ";
}

// The contour surfaces of the isosurface volumes in a step, in front of its medium.
std::string IsoStep(const Key& key)
{
  std::string code;
  for (int i = key.Volumes - 1; i >= 0; --i)
  {
    if (IsIso(key, i))
      code += ForVolume("\n      {\n        vec4 surface = strataIso@n@(o + a * d, o + b * d);\n"
                        "        c = surface + (1.0 - surface.a) * c;\n      }",
        i);
  }
  return code;
}

// The surface layers in the front-to-back loop: pending layers in front of the step go first
// (also after a skip: the space skipped was empty), the step ends at the next layer, and the
// same lattice step resumes behind it.
void SurfaceSteps(const Key& key, std::string& loop)
{
  const bool on = key.Surfaces > 0 && key.FrontToBack;
  Replace(loop, "//STRATA::Surfaces::Start", on ? "float surfaceFrom = tEnter;" : "");
  Replace(loop,
    "//STRATA::Surfaces::Split",
    on ? "a = max(a, surfaceFrom);\n    strataSurfacesBefore(a, acc);\n    float bStep = b;\n"
         "    b = min(b, strataSurfaceNext());"
       : "");
  Replace(loop,
    "//STRATA::Surfaces::Resume",
    on ? "if (b < bStep)\n    {\n      surfaceFrom = b;\n      continue;\n    }" : "");
}

// The surface layers' declarations and their load onto the ray, unrolled per layer (samplers).
void Surfaces(const Key& key, std::string& fs)
{
  if (key.Surfaces == 0)
  {
    Replace(fs, "//STRATA::Surfaces::Dec", "");
    Replace(fs, "//STRATA::Surfaces::Load", "");
    return;
  }
  std::string dec = vtkMultiVolumeSurfaces, samplers, load;
  for (int k = 0; k < key.Surfaces; ++k)
  {
    const std::string K = std::to_string(k);
    samplers +=
      "uniform sampler2D uSurfaceColor" + K + ";\nuniform sampler2D uSurfaceDepth" + K + ";\n";
    load += "\n  strataSurfaceSet(" + K + ", texelFetch(uSurfaceColor" + K +
            ", ivec2(gl_FragCoord.xy), 0), texelFetch(uSurfaceDepth" + K +
            ", ivec2(gl_FragCoord.xy), 0).r, ndc, o, d);";
  }
  Replace(dec, "//STRATA::SurfaceSamplers::Dec", samplers);
  Replace(dec, "@K0@", Zeros("0.0", key.Surfaces));
  Replace(dec, "@K0V@", Zeros("vec4(0.0)", key.Surfaces));
  Replace(dec, "@K@", std::to_string(key.Surfaces));
  Replace(fs, "//STRATA::Surfaces::Dec", dec);
  Replace(fs, "//STRATA::Surfaces::Load", load);
}

std::string Composite(const Key& key)
{
  if (key.Reduce)
    return Reduce(key);
  const bool ftb = key.FrontToBack;
  const bool layers = CountIf(key, IsLayer) > 0;
  const std::string layersBefore =
    ftb ? "strataLayersBefore(b, acc);" : "strataLayersBehind(b, acc);";
  const std::string layersAfter =
    ftb ? "strataLayersBefore(3.0e38, acc);" : "strataLayersBehind(-1.0e38, acc);";
  if (CountIf(key, Sampled) == 0) // nothing to sample: the layers alone
  {
    if (key.Surfaces == 0 || !ftb)
      return LayerStart(key) + layersAfter;
    // With surface layers (front to back only), the two kinds in the order of their depths:
    // before each pending surface (up to the fragment's exit), the layers in front of it.
    return LayerStart(key) + "for (int k = 0; k <= " + std::to_string(key.Surfaces) +
           "; ++k)\n  {\n    float ts = min(strataSurfaceNext(), tExit);\n"
           "    strataLayersBefore(ts, acc);\n    strataSurfacesBefore(ts, acc);\n  }\n  " +
           layersAfter;
  }
  const bool pre = PreIntegrated(key);
  const std::string K = std::to_string(key.Volumes);
  const char* end = ftb ? "tEnter" : "tExit";
  std::string start;
  if (key.Feedback && ftb)
    start += "gTransmittance = 1.0 - prior;\n  ";
  if (key.Skipping)
    start +=
      ftb
        ? "bool probe = true; // look for empty space: at the start and after transparent steps\n  "
        : "bool probe = true;\n  ";
  if (pre)
    start += "float sA[" + K + "] = float[" + K + "](" + Zeros("0.0", key.Volumes) +
             ");\n  float sB[" + K + "] = sA;\n  strataSampleAll(o + " + end + " * d, " +
             (ftb ? "sA" : "sB") + ");\n  ";
  std::string skip;
  if (key.Skipping)
  {
    skip =
      ftb ? "float skip = probe ? strataEmptyUntil(o, d, a, 1.0) : a;\n    if (skip > b)\n    {\n"
            "      kk = max(kk + 1.0, floor(skip / dt - phase));\n"
          : "float skip = probe ? strataEmptyUntil(o, d, b, -1.0) : b;\n    if (skip < a)\n    {\n"
            "      kb = min(kb - 1.0, ceil(skip / dt - phase));\n";
    if (pre)
      skip +=
        ftb ? "      strataSampleAll(o + min(max((kk + phase) * dt, tEnter), tExit) * d, sA);\n"
            : "      strataSampleAll(o + min(max((kb + phase) * dt, tEnter), tExit) * d, sB);\n";
    skip += "      continue;\n    }";
  }
  std::string step;
  if (key.Feedback && ftb)
    step += "gTransmittance = (1.0 - prior) * (1.0 - acc.a);\n      ";
  if (key.Footprint)
    step +=
      "gFootprint = uFeedbackFootprint.x + uFeedbackFootprint.y * distance(o + 0.5 * (a + b) * "
      "d, uFeedbackEye);\n      ";
  if (CountIf(key, Medium) == 0)
    step += "vec4 c = vec4(0.0);";
  else if (pre)
    step += ftb ? "strataSampleAll(o + b * d, sB);\n"
                  "      vec4 c = strataPair(sA, sB, (b - a) * segment, o + 0.5 * (a + b) * d);\n"
                  "      sA = sB;"
                : "strataSampleAll(o + a * d, sA);\n"
                  "      vec4 c = strataPair(sA, sB, (b - a) * segment, o + 0.5 * (a + b) * d);\n"
                  "      sB = sA;";
  else
    step += "vec4 c = strataSegment(o + 0.5 * (a + b) * d, (b - a) * segment);";
  step += IsoStep(key);
  std::string loop = ftb ? vtkMultiVolumeFrontToBack : vtkMultiVolumeBackToFront;
  Replace(loop, "//STRATA::Layers::Impl", layers ? layersBefore : "");
  Replace(loop, "//STRATA::LayersAfter::Impl", layers ? layersAfter : "");
  Replace(loop, "//STRATA::Start::Impl", start);
  Replace(loop, "//STRATA::Skip::Impl", skip);
  Replace(loop, "//STRATA::Step::Impl", step);
  Replace(loop, "//STRATA::Probe::Impl", key.Skipping ? "probe = c.a <= 0.0;" : "");
  SurfaceSteps(key, loop);
  return (AnyShaded(key) ? "gViewDirection = -normalize(d);\n  " : "") + LayerStart(key) + loop;
}
}

bool MultiVolumeShaderComposer::FragmentKey::operator<(const FragmentKey& o) const
{
  if (this->ComponentModes != o.ComponentModes)
    return this->ComponentModes < o.ComponentModes;
  if (this->SilentComponents != o.SilentComponents)
    return this->SilentComponents < o.SilentComponents;
  return std::tie(this->Volumes,
           this->Shaded,
           this->Classification,
           this->FrontToBack,
           this->Barrier,
           this->Rays,
           this->Coherent,
           this->Atlas,
           this->Skipping,
           this->Feedback,
           this->Footprint,
           this->Modes,
           this->Reduce,
           this->Cropped,
           this->GradientOpacity,
           this->Normalized,
           this->Surfaces) < std::tie(o.Volumes,
                               o.Shaded,
                               o.Classification,
                               o.FrontToBack,
                               o.Barrier,
                               o.Rays,
                               o.Coherent,
                               o.Atlas,
                               o.Skipping,
                               o.Feedback,
                               o.Footprint,
                               o.Modes,
                               o.Reduce,
                               o.Cropped,
                               o.GradientOpacity,
                               o.Normalized,
                               o.Surfaces);
}

std::string MultiVolumeShaderComposer::FragmentKey::ToString() const
{
  static const char* classifications[] = {
    "post-classification", "pre-integrated", "pre-integrated approximate"
  };
  std::ostringstream s;
  s << this->Volumes << (this->Volumes == 1 ? " volume" : " volumes") << " (";
  for (size_t i = 0; i < this->Shaded.size(); ++i)
    s << (i ? ", " : "") << (this->Shaded[i] ? "shaded" : "unshaded");
  s << ") " << classifications[static_cast<int>(this->Classification)] << ", "
    << (this->FrontToBack ? "front to back" : "back to front")
    << (this->Barrier ? " across fragments" : "") << ", " << this->Rays
    << (this->Rays == 1 ? " ray" : " rays") << (this->Coherent ? " coherent" : "")
    << (this->Atlas ? ", atlas" : ", plain textures") << (this->Skipping ? ", skipping" : "")
    << (this->Feedback ? (this->Footprint ? ", footprint feedback" : ", feedback") : "");
  static const char* modes[] = {
    "composite", "maximum", "minimum", "average", "additive", "isosurface", "slice"
  };
  bool any = false;
  for (int m : this->Modes)
    any = any || m != vtkVolumeMapper::COMPOSITE_BLEND;
  for (size_t i = 0; any && i < this->Modes.size(); ++i)
    s << (i ? " " : ", blend ") << modes[std::min(std::max(this->Modes[i], 0), 6)];
  s << (this->Reduce ? ", reduction pass" : "");
  for (size_t i = 0; i < this->Cropped.size(); ++i)
    s << (this->Cropped[i] ? ", cropped " + std::to_string(i) : std::string());
  for (size_t i = 0; i < this->GradientOpacity.size(); ++i)
    s << (this->GradientOpacity[i] ? ", gradient opacity " + std::to_string(i) : std::string());
  static const char* components[] = { "one component",
    "2 independent components",
    "3 independent components",
    "4 independent components",
    "colour and opacity components",
    "RGBA components" };
  for (size_t i = 0; i < this->ComponentModes.size(); ++i)
    s << (this->ComponentModes[i] != Components::One
            ? ", " + std::to_string(i) + " of " +
                components[static_cast<int>(this->ComponentModes[i])]
            : std::string());
  for (size_t i = 0; i < this->SilentComponents.size(); ++i)
    for (int c = 1; c < 4; ++c)
      s << (this->SilentComponents[i] & (1 << c)
              ? ", " + std::to_string(i) + " component " + std::to_string(c) + " of weight 0"
              : std::string());
  for (size_t i = 0; i < this->Normalized.size(); ++i)
    s << (this->Normalized[i] ? ", normalised " + std::to_string(i) : std::string());
  if (this->Surfaces > 0)
    s << ", " << this->Surfaces << " surface layers";
  return s.str();
}

int MultiVolumeShaderComposer::GetNumberOfComponents(Components mode)
{
  switch (mode)
  {
    case Components::One:
      return 1;
    case Components::Independent2:
    case Components::ColorOpacity:
      return 2;
    case Components::Independent3:
      return 3;
    default:
      return 4;
  }
}

std::string MultiVolumeShaderComposer::BuildFragmentShader(const FragmentKey& key)
{
  std::string fs = vtkMultiVolumeFragmentFS;
  Replace(fs,
    "//STRATA::Extensions::Dec",
    key.Feedback ? "#extension GL_ARB_shader_image_load_store : require\n" : "");
  Replace(fs, "//STRATA::Volumes::Dec", Volumes(key));
  Replace(fs, "//STRATA::Segment::Dec", Segment(key) + Skipping(key));
  Termination(key, fs);
  Surfaces(key, fs);
  Replace(fs, "//STRATA::Rays::Impl", Rays(key));
  Replace(fs, "//STRATA::Composite::Impl", Composite(key));
  return fs;
}

namespace
{
// Behind each ray's colour, the surface layers no fragment composited (in front of the scene's
// opaque depth, behind every volume the ray crossed, or where it crossed none).
std::string CompositeSurfaces(int rays, int surfaces, std::string& dec)
{
  dec += "uniform sampler2D uSurfaceProgress;\n";
  std::string code = "float progress = texelFetch(uSurfaceProgress, pixel, 0).r;\n  vec4 sum = "
                     "vec4(0.0);\n";
  for (int k = 0; k < surfaces; ++k)
  {
    const std::string K = std::to_string(k);
    dec += "uniform sampler2D uSurfaceColor" + K + ";\nuniform sampler2D uSurfaceDepth" + K + ";\n";
    code += "  vec4 surface" + K + " = texelFetch(uSurfaceDepth" + K +
            ", pixel, 0).r < 1.0 ? texelFetch(uSurfaceColor" + K +
            ", pixel, 0) : vec4(0.0);\n  surface" + K + ".rgb *= surface" + K + ".a;\n";
  }
  for (int r = 0; r < rays; ++r)
  {
    const std::string R = std::to_string(r);
    code += "  {\n    vec4 acc = texelFetch(uAccumulation" + R +
            ", pixel, 0);\n    int done = " + "int(mod(floor(progress / " +
            std::to_string(1 << (3 * r)) + ".0), 8.0));\n";
    for (int k = 0; k < surfaces; ++k)
      code += "    acc += " + std::to_string(k) + " >= done ? (1.0 - acc.a) * surface" +
              std::to_string(k) + " : vec4(0.0);\n";
    code += "    sum += acc;\n  }\n";
  }
  return code + "  fragOutput0 = sum / " + std::to_string(rays) + ".0;";
}
}

std::string MultiVolumeShaderComposer::BuildCompositeShader(int rays, int surfaces)
{
  // The pixel is the mean of its rays' composites.
  std::string fs = vtkMultiVolumeCompositeFS;
  std::ostringstream dec, impl;
  for (int r = 0; r < rays; ++r)
  {
    dec << "uniform sampler2D uAccumulation" << r << ";\n";
    impl << (r ? " + " : "") << "texelFetch(uAccumulation" << r << ", pixel, 0)";
  }
  if (surfaces > 0)
  {
    std::string surfaceDec = dec.str();
    const std::string code = CompositeSurfaces(rays, surfaces, surfaceDec);
    Replace(fs, "//STRATA::Accumulation::Dec", surfaceDec);
    Replace(fs, "//STRATA::Accumulation::Impl", code);
    return fs;
  }
  Replace(fs, "//STRATA::Accumulation::Dec", dec.str());
  Replace(fs,
    "//STRATA::Accumulation::Impl",
    "fragOutput0 = (" + impl.str() + ") / " + std::to_string(rays) + ".0;");
  return fs;
}

class MultiVolumeShaderComposer::vtkInternals
{
public:
  strata::ShaderCache<FragmentKey> Fragments;
  strata::ShaderCache<int> Composites;
};

MultiVolumeShaderComposer::MultiVolumeShaderComposer()
  : Internals(new vtkInternals)
{
}

MultiVolumeShaderComposer::~MultiVolumeShaderComposer() = default;

vtkShaderProgram* MultiVolumeShaderComposer::ReadyFragmentProgram(vtkOpenGLRenderWindow* window,
  const FragmentKey& key)
{
  return this->Internals->Fragments.Ready(window,
    key,
    [](const FragmentKey& k, std::string& vs, std::string& fs)
    {
      vs = vtkMultiVolumeFragmentVS;
      fs = BuildFragmentShader(k);
    });
}

vtkShaderProgram* MultiVolumeShaderComposer::ReadyCompositeProgram(vtkOpenGLRenderWindow* window,
  int rays,
  int surfaces)
{
  // Keyed by rays (1-8) and surface layers (0-7) in one int.
  return this->Internals->Composites.Ready(window,
    rays + 16 * surfaces,
    [](int k, std::string& vs, std::string& fs)
    {
      vs = vtkMultiVolumeCompositeVS;
      fs = BuildCompositeShader(k % 16, k / 16);
    });
}

vtkShaderProgram* MultiVolumeShaderComposer::ReadyComputeProgram(vtkOpenGLRenderWindow* window,
  const FragmentKey& key,
  std::string& error)
{
  return this->Internals->Fragments.ReadyCompute(
    window,
    key,
    [](const FragmentKey& k, std::string& cs, std::string& reason) {
      cs = strata::ComputeStage::FromFragment(BuildFragmentShader(k), GetComputeOutputs(k), reason);
    },
    error);
}

strata::ComputeStage::Outputs MultiVolumeShaderComposer::GetComputeOutputs(const FragmentKey& key)
{
  strata::ComputeStage::Outputs outputs;
  outputs.Count = key.Rays + (key.Surfaces > 0 ? 1 : 0);
  outputs.Blending = key.Reduce        ? strata::ComputeStage::Blend::None
                     : key.FrontToBack ? strata::ComputeStage::Blend::FrontToBack
                                       : strata::ComputeStage::Blend::Over;
  return outputs;
}

std::string MultiVolumeShaderComposer::BuildComputeShader(const FragmentKey& key)
{
  std::string error;
  return strata::ComputeStage::FromFragment(
    BuildFragmentShader(key), GetComputeOutputs(key), error);
}

std::string MultiVolumeShaderComposer::GetComputeSource(const FragmentKey& key) const
{
  const auto* entry = this->Internals->Fragments.FindCompute(key);
  return entry ? entry->Source : std::string();
}

std::string MultiVolumeShaderComposer::GetFragmentSource(const FragmentKey& key) const
{
  const auto* entry = this->Internals->Fragments.Find(key);
  return entry ? entry->Fragment : std::string();
}

int MultiVolumeShaderComposer::GetNumberOfSourcesBuilt() const
{
  return this->Internals->Fragments.GetSourcesBuilt() +
         this->Internals->Composites.GetSourcesBuilt();
}

int MultiVolumeShaderComposer::GetNumberOfCompilations() const
{
  return this->Internals->Fragments.GetCompilations() +
         this->Internals->Composites.GetCompilations();
}

void MultiVolumeShaderComposer::ReleaseGraphicsResources()
{
  this->Internals->Fragments.ReleaseGraphicsResources();
  this->Internals->Composites.ReleaseGraphicsResources();
}
}
