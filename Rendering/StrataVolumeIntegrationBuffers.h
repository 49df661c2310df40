// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::VolumeIntegrationBuffers
 * @brief   Where the multi-volume ray caster integrates: one float RGBA buffer per ray of a
 *          pixel, the scene's depth, and the final blend of the buffers over the scene.
 *
 * Fragments composite into the integration buffers (premultiplied colour and opacity, 32-bit
 * float so that many fragments add up without banding), ray r of a pixel into buffer r. Rays
 * stop at the depth of the opaque geometry drawn before the volumes, copied from the frame
 * buffer (SceneDepth). Composite() then blends the mean of the buffers over the scene in the
 * renderer's viewport.
 *
 * The owner calls ReleaseGraphicsResources() from its own, with the context current.
 */
#ifndef StrataVolumeIntegrationBuffers_h
#define StrataVolumeIntegrationBuffers_h

#include "StrataGLObject.h"        // For strata::GLObject
#include "StrataRenderingModule.h" // For export macro
#include "vtkSmartPointer.h"       // For vtkSmartPointer

#include <vector> // For std::vector

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

namespace strata
{
class STRATARENDERING_EXPORT VolumeIntegrationBuffers
{
public:
  VolumeIntegrationBuffers();
  ~VolumeIntegrationBuffers();
  VolumeIntegrationBuffers(const VolumeIntegrationBuffers&) = delete;
  VolumeIntegrationBuffers& operator=(const VolumeIntegrationBuffers&) = delete;

  /**
   * Sizes `rays` buffers for the viewport (x, y, width, height in the window) and copies the
   * scene's depth there.
   */
  void Prepare(vtkOpenGLRenderWindow* window, const int viewport[4], int rays);
  /// Binds the framebuffer with the buffers of `rays` rays as draw buffers (pushes bindings),
  /// and `extra` after them when given (the surface layers' progress, strata::VolumeSurfaceLayers).
  void Bind(vtkOpenGLRenderWindow* window, int rays, vtkTextureObject* extra = nullptr);
  /// Pops the framebuffer bindings Bind() pushed.
  void Unbind(vtkOpenGLRenderWindow* window);

  vtkTextureObject* GetAccumulation(int ray) const;
  vtkTextureObject* GetSceneDepth() const;

  /// Blends the mean of the rays' buffers over the viewport with `program` (its sampler
  /// uniforms set here); blending set to (1, 1 - source alpha) by the caller.
  void Composite(vtkShaderProgram* program, const int viewport[4], int rays);

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  std::vector<vtkSmartPointer<vtkTextureObject>> Accumulation;
  vtkSmartPointer<vtkTextureObject> SceneDepth;
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  int Attached = 0; ///< colour attachments of the last Bind
  strata::GLObject EmptyArray{ strata::GLObject::Kinds::VertexArray };
};
}

#endif
