// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::VolumeSurfaceLayers
 * @brief   Translucent surfaces for the multi-volume ray caster: the first K surface layers of
 *          each pixel, front to back, as colour and window depth, blended by the rays where
 *          they cross them.
 *
 * Why the ray caster needs them: a translucent surface inside a volume is neither in front of
 * nor behind the volume, so no blend of two images is right; each ray must composite the
 * surface at the depth where it crosses it, between the samples in front and behind.
 *
 * What a layer is: per pixel of the renderer's viewport, the k-th nearest translucent surface
 * in front of the opaque scene: its straight (not premultiplied) RGBA in a float texture and its
 * window depth in a depth texture (1: none). Layers are ordered (layer k + 1 lies behind layer k
 * wherever both exist) and a pixel without a k-th surface has none after it either. That is all
 * the ray caster reads: how a producer found them does not matter. Peel() makes them from
 * vtkActors by depth peeling (Everitt, interactive order-independent transparency): pass k
 * draws the actors with a depth test, keeping only fragments behind layer k - 1 and in front of
 * the scene's depth, through a vtkOpenGLRenderPass on each actor's property keys (VTK's own hook
 * into vtkOpenGLPolyDataMapper's shader: //VTK::DepthPeeling::Dec and ::PreColor).
 *
 * A second producer: vtkStackedHeightFieldMapper. An actor of that mapper given to the ray
 * caster (vtkMultiVolumeRayCastMapper::AddTranslucentActor) sees this peel on its keys
 * (vtkVolumeSurfacePeelPass::Find) while Peel draws it, and its ray caster then writes, for
 * pass k, the first translucent horizon hit behind layer k - 1 and in front of the scene, as
 * the same colour and gl_FragDepth; coincident translucent horizons are merged into one layer
 * there. The depth test merges its hits with the actors' per pixel, so the K layers are the
 * first K surfaces of both. Its opaque horizons stay in the renderer's opaque pass and its
 * translucent ones are left out of the renderer's translucent pass while a peel is attached.
 *
 * Progress: a ray crosses the volumes' BSP fragments in several passes, and layers between
 * fragments must still come in order. The progress texture counts, per pixel and ray, the
 * layers already composited (3 bits a ray, ray r at 8^r, exact in a float for up to 8 rays and
 * 7 layers). A fragment composites the pending layers in front of its exit and adds what it
 * took (the integration blend is additive where destination alpha is 0, which it stays here);
 * the final blend composites what no fragment took behind the integrated colour.
 *
 * The owner calls ReleaseGraphicsResources() from its own, with the context current.
 *
 * @sa vtkMultiVolumeRayCastMapper strata::VolumeIntegrationBuffers
 */
#ifndef StrataVolumeSurfaceLayers_h
#define StrataVolumeSurfaceLayers_h

#include "StrataRenderingModule.h"    // For export macro
#include "vtkSmartPointer.h"          // For vtkSmartPointer
#include "vtkVolumeSurfacePeelPass.h" // For the peel the layers own

#include <vector> // For std::vector

class vtkActor;
class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

namespace strata
{
class STRATARENDERING_EXPORT VolumeSurfaceLayers
{
public:
  /// Most layers a frame can hold (3 bits of progress per ray).
  static constexpr int MaximumLayers = 7;

  VolumeSurfaceLayers();
  ~VolumeSurfaceLayers();
  VolumeSurfaceLayers(const VolumeSurfaceLayers&) = delete;
  VolumeSurfaceLayers& operator=(const VolumeSurfaceLayers&) = delete;

  ///@{
  /// The actors peeled (kept until RemoveAllActors, which takes the peel off their keys).
  void AddActor(vtkActor* actor);
  void RemoveAllActors();
  int GetNumberOfActors() const { return static_cast<int>(this->Actors.size()); }
  bool HasVisibleActors() const;
  ///@}

  /**
   * Peels `layers` layers of the visible actors for the viewport (x, y, width, height in the
   * window), in front of `sceneDepth` (the opaque scene's window depth, viewport-sized), with
   * the camera and lights of `ren`. Leaves the GL state as it found it. Returns the layers of
   * this frame: `layers`, or 0 when no actor is visible. `acrossFragments`: the ray caster
   * composites front to back with texture barriers, which the progress needs; without, and
   * with 8 rays per pixel (the progress would be a ninth draw buffer), nothing is peeled and a
   * warning says so once.
   */
  int Peel(vtkRenderer* ren,
    vtkOpenGLRenderWindow* window,
    vtkTextureObject* sceneDepth,
    const int viewport[4],
    int layers,
    int rays,
    bool acrossFragments);

  /// Layers of the last Peel (0: none this frame).
  int GetNumberOfLayers() const { return this->Layers; }
  vtkTextureObject* GetColor(int layer) const;
  vtkTextureObject* GetDepth(int layer) const;
  /// The composited-layer counts (viewport-sized, float), cleared with the integration
  /// buffers; null when the last Peel made no layers.
  vtkTextureObject* GetProgress() const;

  /// Activates the textures and sets uSurfaceColor<k>, uSurfaceDepth<k>, uSurfaceProgress
  /// (nothing when the last Peel made no layers).
  void SetUniforms(vtkShaderProgram* program) const;
  void Deactivate() const;

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  void Allocate(vtkOpenGLRenderWindow* window, int width, int height, int layers);
  void Attach(vtkActor* actor) const;

  int Layers = 0;
  bool UnsupportedWarned = false;
  std::vector<vtkSmartPointer<vtkActor>> Actors;
  std::vector<vtkSmartPointer<vtkTextureObject>> Colors;
  std::vector<vtkSmartPointer<vtkTextureObject>> Depths;
  vtkSmartPointer<vtkTextureObject> Progress;
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  vtkSmartPointer<vtkVolumeSurfacePeelPass> Pass;
};
}

#endif
