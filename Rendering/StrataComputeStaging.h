// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::ComputeStaging
 * @brief   Where a compute-stage pass that draws into VTK's frame buffer leaves its pixels, and
 *          the fragment pass that writes them there.
 *
 * A compute program cannot write the window's frame buffer, its depth test or its blending. A
 * program rewritten with Outputs::Staged (strata::ComputeStage) stores each pixel's colours and
 * its depth with a written flag in these images; Resolve() then draws the dispatched rectangle
 * with a fragment program that discards the pixels no ray hit and writes the others' colours
 * and gl_FragDepth, under the caller's depth test, depth mask and blending: the fragment stage's
 * result, at one fetch per pixel.
 *
 * The owner calls ReleaseGraphicsResources() from its own, with the context current.
 */
#ifndef StrataComputeStaging_h
#define StrataComputeStaging_h

#include "StrataComputeStage.h"    // For strata::ComputeStage::Outputs
#include "StrataGLObject.h"        // For strata::GLObject
#include "StrataRenderingModule.h" // For export macro
#include "vtkSmartPointer.h"       // For vtkSmartPointer

#include <array> // For std::array

class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

namespace strata
{
class STRATARENDERING_EXPORT ComputeStaging
{
public:
  ComputeStaging();
  ~ComputeStaging();
  ComputeStaging(const ComputeStaging&) = delete;
  ComputeStaging& operator=(const ComputeStaging&) = delete;

  /// Images of `width` x `height` for `outputs`, bound on their image units.
  void Bind(vtkOpenGLRenderWindow* window,
    int width,
    int height,
    const ComputeStage::Outputs& outputs);
  /// Unbinds the image units Bind() bound.
  void Unbind();

  /**
   * Writes the staged pixels of `rect` (image pixels; image pixel (0, 0) is window position
   * `origin`) into the bound frame buffer. The caller's depth test, depth mask and blending
   * apply. False if the program does not compile.
   */
  bool Resolve(vtkOpenGLRenderWindow* window, const int rect[4], const int origin[2]);

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  std::array<vtkSmartPointer<vtkTextureObject>, 2> Colors;
  vtkSmartPointer<vtkTextureObject> Depth;
  ComputeStage::Outputs Bound;
  strata::GLObject EmptyArray{ strata::GLObject::Kinds::VertexArray };
};
}

#endif
