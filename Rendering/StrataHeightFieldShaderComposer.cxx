// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataHeightFieldShaderComposer.h"

#include "StrataFeedbackReduction.h"
#include "StrataHeightFieldTileAtlas.h"
#include "StrataShaderCache.h"

#include "vtkStackedHeightFieldAttribute.h"
#include "vtkStackedHeightFieldBlend.h"
#include "vtkStackedHeightFieldFS.h"
#include "vtkStackedHeightFieldFeedback.h"
#include "vtkStackedHeightFieldFeedbackWrite.h"
#include "vtkStackedHeightFieldHeadlight.h"
#include "vtkStackedHeightFieldHoles.h"
#include "vtkStackedHeightFieldHorizonColor.h"
#include "vtkStackedHeightFieldLayerDec.h"
#include "vtkStackedHeightFieldLayerMerge.h"
#include "vtkStackedHeightFieldLayerStart.h"
#include "vtkStackedHeightFieldLight.h"
#include "vtkStackedHeightFieldPositionalLight.h"
#include "vtkStackedHeightFieldShading.h"
#include "vtkStackedHeightFieldShadingDec.h"
#include "vtkStackedHeightFieldVS.h"

#include <sstream>
#include <tuple>

namespace strata
{

namespace
{
using Key = HeightFieldShaderComposer::Key;
using Translucency = HeightFieldShaderComposer::Translucency;

void Replace(std::string& source, const std::string& tag, const std::string& code)
{
  strata::ShaderCache<int>::Replace(source, tag, code);
}

// --- Where heights live: the tile atlas's page table (paged) or one array texture in core.
void Heights(const Key& key, std::string& fs)
{
  if (key.Paged)
  {
    Replace(
      fs, "//STRATA::HeightLookup::Dec", strata::HeightFieldTileAtlas::GetLookupDeclarations());
    Replace(
      fs, "//STRATA::CellCorners::Dec", strata::HeightFieldTileAtlas::GetCellCornersFunction());
    Replace(fs, "//STRATA::SearchLevel::Impl", strata::HeightFieldTileAtlas::GetSearchLevelCode());
  }
  else
  {
    Replace(fs,
      "//STRATA::HeightLookup::Dec",
      "uniform sampler2DArray uHeights;\n"
      "float strataHeight(int layer, ivec2 p) { return texelFetch(uHeights, ivec3(p, layer), 0).r; "
      "}");
    Replace(fs,
      "//STRATA::CellCorners::Dec",
      "vec4 strataCellCorners(int layer, ivec2 c) { return strataCorners(layer, c); }");
    Replace(fs, "//STRATA::SearchLevel::Impl", "");
  }
}

// --- Holes: NaN in core and BIG where a paged tile is missing, tested on the bits and by
// magnitude (strataHoles; never isnan, which fast math may fold away). The layer merge tests
// holes too, attribute grids their NaN (strataIsNaN).
bool UsesBits(const Key& key)
{
  const bool merged =
    key.Translucent == Translucency::Layer || key.Translucent == Translucency::Blend;
  return key.Holes || merged || (key.Shaded && key.PerHorizon && key.Attributes);
}

void Holes(const Key& key, std::string& fs)
{
  Replace(fs, "//STRATA::Holes::Dec", UsesBits(key) ? vtkStackedHeightFieldHoles : "");
  Replace(fs, "//STRATA::Hole::Impl", key.Holes ? "valid = !any(strataHoles(h));" : "");
}

// --- Extensions: floatBitsToUint (core in GLSL 3.30; VTK declares 1.50), image load/store.
void Extensions(const Key& key, std::string& fs)
{
  Replace(fs,
    "//STRATA::Extensions::Dec",
    std::string(UsesBits(key) ? "#extension GL_ARB_shader_bit_encoding : require\n" : "") +
      (key.Feedback ? "#extension GL_ARB_shader_image_load_store : require" : ""));
}

// --- Feedback (image load/store): the tile each sampled ray hit, at the level it wants.
void Feedback(const Key& key, std::string& fs)
{
  Replace(fs,
    "//STRATA::Feedback::Dec",
    key.Feedback ? std::string(vtkStackedHeightFieldFeedback) +
                     strata::FeedbackReduction::GetGLSLPackFunction()
                 : "");
  Replace(fs, "//STRATA::Feedback::Impl", key.Feedback ? vtkStackedHeightFieldFeedbackWrite : "");
}

// --- Colour: horizon ids (tests, picking), one colour per horizon, or a table over depth.
void Color(const Key& key, std::string& fs)
{
  if (!key.Shaded)
  {
    Replace(fs, "//STRATA::Color::Dec", "float strataHorizonOpacity(int layer) { return 1.0; }");
    Replace(fs, "//STRATA::Color::Impl", "");
    return;
  }
  if (key.PerHorizon)
  {
    std::string colors = vtkStackedHeightFieldHorizonColor;
    Replace(
      colors, "//STRATA::Attribute::Dec", key.Attributes ? vtkStackedHeightFieldAttribute : "");
    Replace(colors,
      "//STRATA::Attribute::Impl",
      key.Attributes ? "if (d.y >= 0.0 && !strataAttribute(int(d.y), pGrid.xy, value))\n"
                       "  {\n"
                       "    return texelFetch(uColors, table + 1024).rgb;\n"
                       "  }"
                     : "");
    colors += "float strataHorizonOpacity(int layer) { return texelFetch(uColors, 2 * layer + "
              "1).a; }\n"
              "vec3 strataLayerColor(int layer, vec3 pGrid) { return strataHorizonColor(layer, "
              "pGrid); }\n";
    Replace(fs, "//STRATA::Color::Dec", colors);
    Replace(fs, "//STRATA::Color::Impl", "vec3 baseColor = strataHorizonColor(hitLayer, pGrid);");
    return;
  }
  if (key.LookupTable)
  {
    Replace(fs,
      "//STRATA::Color::Dec",
      "uniform samplerBuffer uColors; // 1024 entries from uLutRange.x, uLutRange.y a unit\n"
      "uniform vec2 uLutRange;\n"
      "float strataHorizonOpacity(int layer) { return 1.0; } // translucency makes it per horizon");
    Replace(fs,
      "//STRATA::Color::Impl",
      "float lutS = (pGrid.z - uLutRange.x) * uLutRange.y;\n"
      "  vec3 baseColor = texelFetch(uColors, int(clamp(lutS, 0.0, 1023.0))).rgb;");
    return;
  }
  Replace(fs,
    "//STRATA::Color::Dec",
    "uniform samplerBuffer uColors; // one per horizon, its opacity in alpha\n"
    "float strataHorizonOpacity(int layer) { return texelFetch(uColors, layer).a; }\n"
    "vec3 strataLayerColor(int layer, vec3 pGrid) { return texelFetch(uColors, layer).rgb; }");
  Replace(fs, "//STRATA::Color::Impl", "vec3 baseColor = texelFetch(uColors, hitLayer).rgb;");
}

/// The renderer's lights unrolled as VTK's mappers do: a headlight, or each light in turn,
/// positional ones (complexity 3) with attenuation and cones.
std::string Lights(const Key& key)
{
  if (key.LightingComplexity == 1)
    return vtkStackedHeightFieldHeadlight;
  std::string code;
  for (int l = 0; l < key.LightCount; ++l)
  {
    std::string light = vtkStackedHeightFieldLight;
    Replace(light,
      "//STRATA::Positional::Impl",
      key.LightingComplexity == 3 ? vtkStackedHeightFieldPositionalLight : "");
    Replace(light, "@l@", std::to_string(l));
    code += light;
  }
  return code;
}

// --- Shading and output: lit colour, flat colour, or the horizon id packed in 24-bit RGB.
void Shading(const Key& key, const std::string& lightingUniforms, std::string& fs)
{
  const bool merged =
    key.Translucent == Translucency::Layer || key.Translucent == Translucency::Blend;
  const std::string alpha = merged ? "layerAlpha" : "1.0";
  if (!key.Shaded)
  {
    Replace(fs, "//STRATA::Shading::Dec", "");
    Replace(fs, "//STRATA::Shading::Impl", "");
    Replace(fs,
      "//STRATA::Output::Impl",
      "int id = hitLayer + 1;\n"
      "  return vec4(float(id & 255), float((id >> 8) & 255), float((id >> 16) & 255), "
      "255.0) / 255.0;");
    return;
  }
  if (!key.Lit)
  {
    Replace(fs, "//STRATA::Shading::Dec", "");
    Replace(fs, "//STRATA::Shading::Impl", "");
    Replace(fs, "//STRATA::Output::Impl", "return vec4(baseColor, " + alpha + ");");
    return;
  }
  std::string dec = vtkStackedHeightFieldShadingDec;
  Replace(dec, "//STRATA::LightingUniforms::Dec", lightingUniforms);
  std::string impl = vtkStackedHeightFieldShading;
  Replace(impl, "//STRATA::Lights::Impl", Lights(key));
  Replace(fs, "//STRATA::Shading::Dec", dec);
  Replace(fs, "//STRATA::Shading::Impl", impl);
  Replace(
    fs, "//STRATA::Output::Impl", "return vec4(clamp(shadedColor, 0.0, 1.0), " + alpha + ");");
}

// --- Translucent horizons: passed through by the opaque pass; or one peel layer, the first
// translucent hit behind the previous layer's depth and in front of the scene, merged with the
// translucent horizons coincident with it there (index order, as the references composite
// them).
void Translucent(const Key& key, std::string& fs)
{
  const bool layer = key.Translucent == Translucency::Layer;
  const bool blend = key.Translucent == Translucency::Blend;
  Replace(fs,
    "//STRATA::Translucency::Skip",
    key.Translucent == Translucency::Skip
      ? "if (strataHorizonOpacity(layer) < 1.0)\n          {\n            continue;\n          }"
      : "");
  Replace(fs,
    "//STRATA::Translucency::Dec",
    std::string(layer ? vtkStackedHeightFieldLayerDec : "") +
      (layer || blend ? "uniform int uNumHorizons;\n" : ""));
  Replace(fs, "//STRATA::Translucency::Start", layer ? vtkStackedHeightFieldLayerStart : "");
  Replace(fs,
    "//STRATA::Translucency::Depth",
    layer   ? "if (gl_FragDepth >= peelScene || strataHorizonOpacity(hitLayer) >= 1.0)\n"
              "  {\n    discard;\n  }"
    : blend ? "if (strataHorizonOpacity(hitLayer) >= 1.0)\n  {\n    discard;\n  }"
            : "");
  Replace(
    fs, "//STRATA::Translucency::Merge", layer || blend ? vtkStackedHeightFieldLayerMerge : "");
  Replace(fs,
    "//STRATA::Translucency::Output",
    blend ? vtkStackedHeightFieldBlend : "gl_FragData[0] = strataShade(hitLayer, hitCell, pGrid);");
}
}

bool HeightFieldShaderComposer::Key::operator<(const Key& o) const
{
  return std::tie(this->Paged,
           this->Feedback,
           this->Holes,
           this->Shaded,
           this->LookupTable,
           this->PerHorizon,
           this->Attributes,
           this->Lit,
           this->LightingComplexity,
           this->LightCount,
           this->Translucent) < std::tie(o.Paged,
                                  o.Feedback,
                                  o.Holes,
                                  o.Shaded,
                                  o.LookupTable,
                                  o.PerHorizon,
                                  o.Attributes,
                                  o.Lit,
                                  o.LightingComplexity,
                                  o.LightCount,
                                  o.Translucent);
}

std::string HeightFieldShaderComposer::Key::ToString() const
{
  std::ostringstream s;
  s << (this->Paged ? "paged" : "in core") << (this->Feedback ? ", feedback" : "")
    << (this->Holes ? ", holes" : "")
    << (!this->Shaded       ? ", horizon ids"
         : this->PerHorizon ? (this->Attributes ? ", per horizon with attributes" : ", per horizon")
         : this->LookupTable ? ", lookup table"
                             : ", solid colours");
  if (this->Lit)
    s << ", lit (complexity " << this->LightingComplexity << ", " << this->LightCount
      << (this->LightCount == 1 ? " light)" : " lights)");
  if (this->Translucent == Translucency::Skip)
    s << ", translucent skipped";
  else if (this->Translucent == Translucency::Layer)
    s << ", translucent layer";
  else if (this->Translucent == Translucency::Blend)
    s << ", translucent blended";
  return s.str();
}

std::string HeightFieldShaderComposer::BuildFragmentShader(const Key& key,
  const std::string& lightingUniforms)
{
  std::string fs = vtkStackedHeightFieldFS;
  Heights(key, fs);
  Holes(key, fs);
  Extensions(key, fs);
  Feedback(key, fs);
  Color(key, fs);
  Shading(key, lightingUniforms, fs);
  Translucent(key, fs);
  return fs;
}

class HeightFieldShaderComposer::vtkInternals
{
public:
  strata::ShaderCache<Key> Programs;
};

HeightFieldShaderComposer::HeightFieldShaderComposer()
  : Internals(new vtkInternals)
{
}

HeightFieldShaderComposer::~HeightFieldShaderComposer() = default;

vtkShaderProgram* HeightFieldShaderComposer::ReadyProgram(vtkOpenGLRenderWindow* window,
  const Key& key,
  const std::function<std::string()>& lightingUniforms)
{
  return this->Internals->Programs.Ready(window,
    key,
    [&lightingUniforms](const Key& k, std::string& vs, std::string& fs)
    {
      vs = vtkStackedHeightFieldVS;
      fs = BuildFragmentShader(k, k.Lit ? lightingUniforms() : std::string());
    });
}

vtkShaderProgram* HeightFieldShaderComposer::ReadyComputeProgram(vtkOpenGLRenderWindow* window,
  const Key& key,
  const std::function<std::string()>& lightingUniforms,
  std::string& error)
{
  return this->Internals->Programs.ReadyCompute(
    window,
    key,
    [&lightingUniforms](const Key& k, std::string& cs, std::string& reason)
    {
      cs = strata::ComputeStage::FromFragment(
        BuildFragmentShader(k, k.Lit ? lightingUniforms() : std::string()),
        GetComputeOutputs(k),
        reason);
    },
    error);
}

strata::ComputeStage::Outputs HeightFieldShaderComposer::GetComputeOutputs(const Key& key)
{
  strata::ComputeStage::Outputs outputs;
  outputs.Count = key.Translucent == Translucency::Blend ? 2 : 1;
  outputs.Staged = true;
  return outputs;
}

std::string HeightFieldShaderComposer::GetComputeSource(const Key& key) const
{
  const auto* entry = this->Internals->Programs.FindCompute(key);
  return entry ? entry->Source : std::string();
}

std::string HeightFieldShaderComposer::GetFragmentSource(const Key& key) const
{
  const auto* entry = this->Internals->Programs.Find(key);
  return entry ? entry->Fragment : std::string();
}

int HeightFieldShaderComposer::GetNumberOfSourcesBuilt() const
{
  return this->Internals->Programs.GetSourcesBuilt();
}

int HeightFieldShaderComposer::GetNumberOfCompilations() const
{
  return this->Internals->Programs.GetCompilations();
}

void HeightFieldShaderComposer::ReleaseGraphicsResources()
{
  this->Internals->Programs.ReleaseGraphicsResources();
}
}
