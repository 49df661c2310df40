// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::MultiVolumeShaderComposer
 * @brief   The multi-volume ray caster's shaders: sources generated for exactly the features a
 *          BSP fragment uses, programs cached by those features.
 *
 * A fragment's program depends on FragmentKey alone: how many volumes cover it, which of them
 * are shaded, their blend modes (composite volumes are media; isosurface volumes add their
 * contour surfaces; MIP, MinIP, average and additive volumes are read as layers that their own
 * reduction pass, a program of its own, wrote), the classification, the compositing order, rays per
 * pixel and coherence, brick atlas, empty-space skipping, level-of-detail feedback and each
 * volume's components (independent, colour + opacity, RGBA: one medium per volume). The fragment
 * template (vtkMultiVolumeFragmentFS.glsl) is a skeleton of tags; each feature has one builder
 * below that fills its tags from .glsl snippets (per volume, `@n@` standing for the volume's place
 * in the fragment), so a feature the scene does not use leaves no code behind. The lookup that
 * knows where voxels live is the brick atlas's (strata::BrickAtlasTexture) or a plain texture's.
 *
 * Programs are kept by key (strata::ShaderCache): a frame that draws the same fragments as
 * the last builds no source and hashes nothing; GetNumberOfSourcesBuilt() and
 * GetNumberOfCompilations() count what was built, for tests.
 *
 * @sa vtkMultiVolumeRayCastMapper strata::ShaderCache
 */
#ifndef StrataMultiVolumeShaderComposer_h
#define StrataMultiVolumeShaderComposer_h

#include "StrataComputeStage.h"          // For strata::ComputeStage::Outputs
#include "StrataRenderingModule.h"       // For export macro
#include "vtkMultiVolumeRayCastMapper.h" // For Classifications

#include <memory> // For std::unique_ptr
#include <string> // For std::string
#include <vector> // For std::vector

class vtkOpenGLRenderWindow;
class vtkShaderProgram;

namespace strata
{
class STRATARENDERING_EXPORT MultiVolumeShaderComposer
{
public:
  using Classifications = vtkMultiVolumeRayCastMapper::Classifications;

  /// How a volume's point components are classified (vtkVolumeProperty's IndependentComponents):
  /// one scalar; 2-4 independent components, each with its own functions and weight; two
  /// dependent (colour of the first, opacity of the second); four dependent (RGB and opacity).
  enum class Components
  {
    One,
    Independent2,
    Independent3,
    Independent4,
    ColorOpacity,
    RGBA
  };
  /// The number of components of a mode.
  static int GetNumberOfComponents(Components mode);

  /// Everything a fragment's program depends on.
  struct FragmentKey
  {
    int Volumes = 1;          ///< volumes covering the fragment
    std::vector<bool> Shaded; ///< per volume: gradient shading
    Classifications Classification = Classifications::PostClassification;
    bool FrontToBack = true;
    bool Barrier = false;   ///< early termination across fragments (texture barrier)
    int Rays = 1;           ///< rays per pixel
    bool Coherent = false;  ///< rays after the first start where it left empty space
    bool Atlas = true;      ///< bricks in the shared atlas (else one texture per volume)
    bool Skipping = true;   ///< empty-space skipping
    bool Feedback = false;  ///< level-of-detail feedback (paged scenes, with the atlas)
    bool Footprint = false; ///< feedback asks for the level of the pixel footprint
    /// Per volume: its vtkVolumeMapper blend mode (missing entries: COMPOSITE).
    std::vector<int> Modes;
    /// The reduction pass of volume 0 (MIP, MinIP, average, additive by Modes[0]) into its
    /// layer buffers, instead of the integration of all the fragment's volumes.
    bool Reduce = false;
    /// Per volume: cropped by vtkVolumeMapper's regions (missing entries: not cropped).
    std::vector<bool> Cropped;
    /// Per volume: opacity scaled by the gradient opacity function (composite volumes,
    /// post-classification; missing entries: none).
    std::vector<bool> GradientOpacity;
    /// Per volume: its components (missing entries: One). A volume of several is read from its
    /// own texture, never the atlas, as a composite medium (post-classified, unshaded).
    std::vector<Components> ComponentModes;
    /// Per volume: bit c (c > 0) set for an independent component of weight 0, which shows
    /// nothing: it has no lookup and no table (its value reads 0; missing entries: none).
    std::vector<int> SilentComponents;
    /// Per volume: texels normalised, decoded by uDecode<n> (R8 or R16 storage,
    /// strata::BrickAtlasFormat; missing entries: float).
    std::vector<bool> Normalized;
    /// Translucent surface layers (strata::VolumeSurfaceLayers) the rays composite where they cross
    /// them (front to back across fragments, with Barrier); 0: none, no surface code.
    int Surfaces = 0;

    bool operator<(const FragmentKey& other) const;
    /// A printable form, e.g. "2 volumes (shaded, -) post-classification front-to-back ...".
    std::string ToString() const;
  };

  MultiVolumeShaderComposer();
  ~MultiVolumeShaderComposer();
  MultiVolumeShaderComposer(const MultiVolumeShaderComposer&) = delete;
  MultiVolumeShaderComposer& operator=(const MultiVolumeShaderComposer&) = delete;

  /// Binds the program of `key` (built and compiled the first time); null if it fails.
  vtkShaderProgram* ReadyFragmentProgram(vtkOpenGLRenderWindow* window, const FragmentKey& key);
  /**
   * Binds the compute stage's program of `key` (strata::ComputeStage: the fragment source
   * rewritten, its outputs blended into the images of GetComputeOutputs); null, with the log
   * in `error`, if it fails.
   */
  vtkShaderProgram* ReadyComputeProgram(vtkOpenGLRenderWindow* window,
    const FragmentKey& key,
    std::string& error);
  /// Binds the program that blends the integration buffers of `rays` rays over the scene,
  /// with the `surfaces` surface layers no fragment composited behind each ray's colour.
  vtkShaderProgram* ReadyCompositeProgram(vtkOpenGLRenderWindow* window,
    int rays,
    int surfaces = 0);

  /// The fragment source of `key`, empty if it was never built.
  std::string GetFragmentSource(const FragmentKey& key) const;

  /// The compute source of `key`, empty if it was never built.
  std::string GetComputeSource(const FragmentKey& key) const;

  /// The fragment shader source for `key` (what ReadyFragmentProgram compiles).
  static std::string BuildFragmentShader(const FragmentKey& key);
  /// The compute shader source for `key` (what ReadyComputeProgram compiles).
  static std::string BuildComputeShader(const FragmentKey& key);
  /**
   * What a compute program of `key` writes: ray r's integration buffer as output r and the
   * surface progress after them, blended as the fragment stage blends them (front to back,
   * back to front, or stored by a reduction).
   */
  static strata::ComputeStage::Outputs GetComputeOutputs(const FragmentKey& key);
  /// The composite shader source for `rays` rays and `surfaces` surface layers.
  static std::string BuildCompositeShader(int rays, int surfaces = 0);

  /// Sources built and programs compiled since construction (fragment and composite).
  int GetNumberOfSourcesBuilt() const;
  int GetNumberOfCompilations() const;

  /// Forgets the programs (the window's shader cache owns them) and deletes the compute ones.
  void ReleaseGraphicsResources();

private:
  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};
}

#endif
