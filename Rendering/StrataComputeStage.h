// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::ComputeStage
 * @brief   The ray casters' compute stage: a composed fragment program rewritten as a compute
 *          program, the screen rectangle it is dispatched over, and the per-device choice
 *          between the two stages.
 *
 * Both ray casters compose one fragment source per scene from their feature snippets
 * (strata::MultiVolumeShaderComposer, strata::HeightFieldShaderComposer). FromFragment() turns that
 * same source into a compute program, so that the snippets and the typed feature key stay the
 * single source of what a frame simulates: one invocation per pixel of a screen rectangle
 * (LocalSize x LocalSize groups), gl_FragCoord from the invocation's pixel, the fragment's main
 * called as a function, `discard` a return that stores nothing, and the outputs either
 * - blended into the targets (Blend::FrontToBack or Blend::Over, as the fragment stage's fixed
 *   blending would, or stored with Blend::None): imageLoad and imageStore of float RGBA images on
 *   units FirstImageUnit + i, at the pixel less the rectangle's origin; the multi-volume caster's
 *   integration buffers, one dispatch per BSP fragment with a glMemoryBarrier between; or
 * - staged (Staged): the colours into float images and the depth with a written flag into an RG
 *   image, which a fragment pass over the same rectangle (Resolve) writes into the frame buffer
 *   under the depth test and blending the fragment stage used; the height-field caster's one
 *   dispatch.
 *
 * Auto chooses per device: Probe() times the same arithmetic kernel as a fragment and as a
 * compute shader (the wall clock around glFinish, right on every driver, a few milliseconds at the
 * first render) once per renderer string in the process.
 *
 * @sa vtkStrataComputeProgram vtkMultiVolumeRayCastMapper vtkStackedHeightFieldMapper
 */
#ifndef StrataComputeStage_h
#define StrataComputeStage_h

#include "StrataRenderingModule.h" // For export macro

#include <string> // For std::string

class vtkMatrix4x4;
class vtkObject;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;

namespace strata
{
class STRATARENDERING_EXPORT ComputeStage
{
public:
  /// The stages a mapper can ray cast in (its SetStage): the values of both mappers' Stages.
  enum Stages
  {
    Auto = 0,     ///< the probe's faster stage on this device
    Fragment = 1, ///< fragment shaders, rasterising the proxy geometry
    Compute = 2,  ///< compute shaders over the proxy's screen rectangle
  };

  /// How a rewritten program's outputs reach their targets.
  enum class Blend
  {
    None,        ///< stored as computed (blending off)
    FrontToBack, ///< (1 - destination alpha, 1): front-to-back compositing
    Over,        ///< (1, 1 - source alpha): back-to-front compositing
  };

  struct Outputs
  {
    int Count = 1; ///< gl_FragData[0 .. Count - 1]
    Blend Blending = Blend::None;
    bool Staged = false; ///< colours and depth to staging images, for Resolve
  };

  /// Invocations per work group along x and y.
  static constexpr int LocalSize = 8;
  /// The first image unit of the outputs (0 and 1 hold the level-of-detail feedback).
  static constexpr int FirstImageUnit = 2;
  /// The staging depth image's unit (after the colours).
  static int DepthImageUnit(const Outputs& outputs) { return FirstImageUnit + outputs.Count; }

  /**
   * `fragment` (a composed fragment source, before VTK's replacements) as a compute source;
   * empty, with the reason in `error`, if it cannot be rewritten (a `discard` outside main, an
   * input varying).
   */
  static std::string FromFragment(const std::string& fragment,
    const Outputs& outputs,
    std::string& error);

  /**
   * The pixels (x, y, width, height within a viewport of `size`, origin at its corner) that
   * `count` points (x, y, z triples) cover once through `toClip`, widened by `dilate` pixels and
   * one for rounding; the whole viewport when a point lies at or behind the eye. False when the
   * rectangle is empty.
   */
  static bool ScreenRect(vtkMatrix4x4* toClip,
    const double* points,
    int count,
    const int size[2],
    double dilate,
    int rect[4]);

  /**
   * Dispatches the bound compute program over `rect` (pixels of its targets, whose pixel (0, 0)
   * is window position `origin`): the uniforms the rewritten main reads, then the groups.
   */
  static void Dispatch(vtkShaderProgram* program, const int rect[4], const int origin[2]);

  /// The images units a compute program may use in this context, 0 without compute shaders.
  static int GetMaxImageUnits(vtkOpenGLRenderWindow* window);

  /// One device's probe: GPU time of the same kernel in both stages.
  struct ProbeResult
  {
    bool Measured = false; ///< false: no compute shaders here (Auto is Fragment)
    double FragmentMs = 0.0;
    double ComputeMs = 0.0;
    std::string Renderer; ///< GL_RENDERER
    /// compute / fragment (0 when not measured).
    double Ratio() const
    {
      return this->FragmentMs > 0.0 ? this->ComputeMs / this->FragmentMs : 0.0;
    }
  };

  /**
   * The probe of this window's device, run on the first call for its renderer string and
   * cached for the process (the context current). Leaves GL state as VTK's cache believes it.
   */
  static ProbeResult Probe(vtkOpenGLRenderWindow* window);
  /// Probes run in this process (each renderer string once).
  static int GetNumberOfProbes();

  /**
   * The stage to ray cast in: `requested` unless Auto (the probe's faster) or unless compute
   * programs cannot run here or would need more than the device's image units (`images`).
   */
  static int Choose(vtkOpenGLRenderWindow* window, int requested, int images);
  /// The same with the device's image units already known (`units`, GetMaxImageUnits).
  static int Choose(vtkOpenGLRenderWindow* window, int requested, int images, int units);

  /**
   * A mapper's choice of stage, frame by frame: the stage its last frame used, Auto's probe
   * ratio, and the warning (once) when Compute was asked for where it cannot run. The
   * device's image units are asked once per window, not every frame.
   */
  class STRATARENDERING_EXPORT Choice
  {
  public:
    /// The frame's stage for `requested` with `images` image units; warns through `mapper`.
    int Choose(vtkObject* mapper, vtkOpenGLRenderWindow* window, int requested, int images);
    int GetStageInUse() const { return this->InUse; }
    double GetProbeRatio() const { return this->ProbeRatio; }

  private:
    int InUse = Auto;
    double ProbeRatio = 0.0;
    bool Warned = false;
    vtkOpenGLRenderWindow* Window = nullptr; ///< whose units Units holds
    int Units = 0;
  };

  /// The stage named in STRATA_RAY_CASTING_STAGE (Auto, Fragment or Compute), else Auto.
  static int DefaultStage();
  /// "Auto", "Fragment" or "Compute".
  static const char* StageName(int stage);
};
}

#endif
