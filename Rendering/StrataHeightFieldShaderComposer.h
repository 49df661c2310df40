// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::HeightFieldShaderComposer
 * @brief   The stacked height-field ray caster's shaders: a source generated for exactly the
 *          features the scene uses, programs cached by those features.
 *
 * The fragment template (vtkStackedHeightFieldFS.glsl) is a skeleton of tags; each feature of
 * Key fills its own: where heights live (in core, or paged: the tile atlas's lookup,
 * strata::HeightFieldTileAtlas), holes, level-of-detail feedback, colours (per horizon or a lookup
 * table over depth, or horizon ids; or each horizon its own source: its solid colour, its table
 * over its depth or over an attribute grid, with the attribute sampling compiled only when a
 * horizon is coloured by one), lighting with the renderer's lights (its complexity and
 * number of lights, as VTK's own mappers unroll them), translucent horizons (skipped by the
 * opaque pass; one peel layer per pass for strata::VolumeSurfaceLayers, coincident translucent
 * horizons merged). A feature the scene does not use
 * leaves no code behind. Programs are kept by key (strata::ShaderCache), so an unchanged frame
 * builds no source and hashes nothing.
 *
 * @sa vtkStackedHeightFieldMapper strata::ShaderCache
 */
#ifndef StrataHeightFieldShaderComposer_h
#define StrataHeightFieldShaderComposer_h

#include "StrataComputeStage.h"    // For strata::ComputeStage::Outputs
#include "StrataRenderingModule.h" // For export macro

#include <functional> // For std::function
#include <memory>     // For std::unique_ptr
#include <string>     // For std::string

class vtkOpenGLRenderWindow;
class vtkShaderProgram;

namespace strata
{
class STRATARENDERING_EXPORT HeightFieldShaderComposer
{
public:
  /// What a pass does with translucent horizons (opacity below 1).
  enum class Translucency
  {
    None,  ///< every horizon opaque: no translucency code at all
    Skip,  ///< the opaque pass of a stack with translucent horizons: rays pass through them
    Layer, ///< one peel of strata::VolumeSurfaceLayers: the first translucent hit behind the last
    Blend, ///< VTK's order-independent translucent pass: the stack's translucent hits in order
  };

  /// Everything the program depends on.
  struct Key
  {
    bool Paged = false;         ///< heights through the tile atlas's page table
    bool Feedback = false;      ///< paged, with level-of-detail feedback
    bool Holes = false;         ///< some sample can be a hole
    bool Shaded = true;         ///< colours (else horizon ids)
    bool LookupTable = false;   ///< colour by depth through a table (else one per horizon)
    bool PerHorizon = false;    ///< each horizon its own colour source (solid, table, attribute)
    bool Attributes = false;    ///< some horizon is coloured by an attribute grid
    bool Lit = false;           ///< lighting
    int LightingComplexity = 0; ///< vtkOpenGLRenderer's, when lit
    int LightCount = 0;         ///< vtkOpenGLRenderer's, when lit
    Translucency Translucent = Translucency::None;

    bool operator<(const Key& other) const;
    /// A printable form, e.g. "paged, feedback, holes, lookup table, lit (complexity 2, 1 light)".
    std::string ToString() const;
  };

  HeightFieldShaderComposer();
  ~HeightFieldShaderComposer();
  HeightFieldShaderComposer(const HeightFieldShaderComposer&) = delete;
  HeightFieldShaderComposer& operator=(const HeightFieldShaderComposer&) = delete;

  /**
   * Binds the program of `key` (built and compiled the first time); `lightingUniforms` gives
   * the renderer's declaration of its lights (vtkOpenGLRenderer::GetLightingUniforms, which the
   * key's complexity and light count determine), asked for only when a source is built. Null
   * if it does not compile.
   */
  vtkShaderProgram* ReadyProgram(vtkOpenGLRenderWindow* window,
    const Key& key,
    const std::function<std::string()>& lightingUniforms);
  /**
   * Binds the compute stage's program of `key` (strata::ComputeStage: the fragment source
   * rewritten, its colours and depth staged for strata::ComputeStaging); null, with the log in
   * `error`, if it fails.
   */
  vtkShaderProgram* ReadyComputeProgram(vtkOpenGLRenderWindow* window,
    const Key& key,
    const std::function<std::string()>& lightingUniforms,
    std::string& error);
  /// The fragment source of `key`, empty if it was never built.
  std::string GetFragmentSource(const Key& key) const;
  /// The compute source of `key`, empty if it was never built.
  std::string GetComputeSource(const Key& key) const;

  /// The fragment shader source for `key`.
  static std::string BuildFragmentShader(const Key& key, const std::string& lightingUniforms);
  /// What a compute program of `key` stages: one colour (two for VTK's translucent pass).
  static strata::ComputeStage::Outputs GetComputeOutputs(const Key& key);

  /// Sources built and programs compiled since construction.
  int GetNumberOfSourcesBuilt() const;
  int GetNumberOfCompilations() const;

  /// Forgets the programs (the window's shader cache owns them).
  void ReleaseGraphicsResources();

private:
  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};
}

#endif
