// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkFeedbackReadBack
 * @brief   The OpenGL half of level-of-detail feedback: a frame's R32UI feedback texture copied
 *          into a pixel buffer object, and that buffer mapped for vtkFeedbackReduction.
 *
 * Shared by the paging mappers (vtkMultiVolumeRayCastMapper, vtkStackedHeightFieldMapper). The
 * copy is queued after the draw (after a barrier that makes the rays' image stores visible) and
 * returns at once; the map waits only if the GPU has not finished that frame yet, so a caller
 * that maps at its next frame never waits for the GPU.
 */
#ifndef vtkFeedbackReadBack_h
#define vtkFeedbackReadBack_h

#include "StrataRenderingModule.h" // For export macro

#include <cstddef>    // For size_t
#include <cstdint>    // For uint32_t
#include <functional> // For std::function

class vtkOpenGLRenderWindow;

class STRATARENDERING_EXPORT vtkFeedbackReadBack
{
public:
  /// Creates `buffer` if 0 and sizes it (stream read) for `count` ids, contents undefined.
  static void Allocate(unsigned int& buffer, size_t count);
  /// Queues the copy of `texture` (R32UI, the whole level 0) into `buffer` (a pixel pack
  /// buffer at least as large), on a texture unit of `renWin`'s manager.
  static void Queue(vtkOpenGLRenderWindow* renWin, unsigned int texture, unsigned int buffer);
  /// Maps the first `count` ids of `buffer` and hands them to `use`; false if the map failed.
  static bool Map(unsigned int buffer,
    size_t count,
    const std::function<void(const uint32_t* ids)>& use);
};

#endif
