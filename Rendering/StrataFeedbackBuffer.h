// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::FeedbackBuffer
 * @brief   The GPU half of level-of-detail feedback, shared by both paging mappers: the
 *          feedback images the rays write, the pixel buffer they are read through, and the
 *          reduction of what was read.
 *
 * One R32UI texel of packed page ids (strata::FeedbackReduction) per Scale x Scale pixels of the
 * viewport, and with Scored an R32F texel beside it (the volume rays keep the costliest
 * lacking brick per texel and compare costs through it). The rays write them by image
 * load/store on image units 0 (ids) and 1 (scores) within one pass, so no frame needs an
 * extra pass or a viewport-sized target. After the draw Queue() copies the ids into a
 * pixel-pack buffer and returns at once; Read() maps it and reduces it to (page, coverage)
 * with OpenCL or the CPU (both give the same list). A caller that reads at its next frame
 * never waits for the GPU; one that reads at once waits only for its own draw.
 *
 * The owner calls ReleaseGraphicsResources() from its own, with the context current.
 *
 * @sa strata::FeedbackReduction vtkStackedHeightFieldMapper vtkMultiVolumeRayCastMapper
 */
#ifndef StrataFeedbackBuffer_h
#define StrataFeedbackBuffer_h

#include "StrataFeedbackReduction.h" // For strata::FeedbackReduction::Entry
#include "StrataGLObject.h"          // For strata::GLObject
#include "StrataRenderingModule.h"   // For export macro

#include <vector> // For std::vector

class vtkOpenGLRenderWindow;

namespace strata
{
class STRATARENDERING_EXPORT FeedbackBuffer
{
public:
  /// `scored`: with the R32F cost image on unit 1.
  explicit FeedbackBuffer(bool scored);
  FeedbackBuffer(const FeedbackBuffer&) = delete;
  FeedbackBuffer& operator=(const FeedbackBuffer&) = delete;

  /**
   * Sizes the images for a viewport of width x height pixels at one texel per scale x scale
   * pixels. Returns true when they were (re)allocated, which drops a queued copy (it was
   * written at another size).
   */
  bool Allocate(vtkOpenGLRenderWindow* window, int width, int height, int scale);
  int GetWidth() const { return this->Size[0]; }
  int GetHeight() const { return this->Size[1]; }

  /// Zeroes the ids (0: no page) and the scores.
  void Clear(vtkOpenGLRenderWindow* window);
  /// The images on units 0 and 1, for writing only or (the scored rays) reading too.
  void BindImages(bool readWrite);
  void UnbindImages();

  /// Queues the copy of the ids into the pixel buffer (after a barrier for the rays' stores).
  void Queue(vtkOpenGLRenderWindow* window);
  /// A copy was queued and not read yet.
  bool IsPending() const { return this->Pending; }
  /// Forgets a queued copy (it was written for a cut or view that is gone).
  void Drop() { this->Pending = false; }

  /**
   * Maps the queued copy and reduces it into `list` (sorted by page id, coverage > 0).
   * Returns false, with `list` empty, when nothing was queued or the map failed.
   */
  bool Read(std::vector<strata::FeedbackReduction::Entry>& list);

  ///@{
  /// Reduce with OpenCL when a device is found (default on), else on the CPU.
  void SetUseOpenCL(bool use) { this->UseOpenCL = use; }
  /// Whether the last Read() reduced with OpenCL.
  bool GetLastReadUsedOpenCL() const { return this->LastOpenCL; }
  ///@}

  void ReleaseGraphicsResources();

private:
  bool Scored;
  bool UseOpenCL = true;
  bool LastOpenCL = false;
  bool Pending = false;
  int Size[2] = { 0, 0 };
  strata::GLObject Ids{ strata::GLObject::Kinds::Texture };
  strata::GLObject Scores{ strata::GLObject::Kinds::Texture };
  strata::GLObject PixelBuffer{ strata::GLObject::Kinds::Buffer };
  strata::FeedbackReduction Reduction;
};
}

#endif
