// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata_bench::FrameTimer
 * @brief   Where one frame's time goes: wall clock, the GPU (GL_TIME_ELAPSED) and the render
 *          thread's CPU (CLOCK_THREAD_CPUTIME_ID), measured around the same Render.
 *
 * Wall: a steady clock around Render and WaitForCompletion (glFinish), right on every driver.
 * GPU: a GL_TIME_ELAPSED query around Render, read after WaitForCompletion; -1 where the
 * context has no timer queries (ARB_timer_query). On llvmpipe the fragment work runs on its own
 * threads and the query undercounts it: there compare by wall clock. CPU: the calling thread's
 * CPU time around Render (VTK's traversal, the mappers' CPU work, driver calls), which must stay
 * small beside the GPU time on a real GPU.
 */
#ifndef StrataFrameTimer_h
#define StrataFrameTimer_h

#include <vector> // For std::vector

class vtkRenderWindow;

namespace strata_bench
{
struct FrameTime
{
  double WallMs = 0.0;
  double GpuMs = -1.0; ///< -1: no timer query on this context
  double CpuMs = 0.0;
};

class FrameTimer
{
public:
  /// One timed frame of `window` (made current first).
  static FrameTime Time(vtkRenderWindow* window);
  /// Medians (the upper of two middles) of each field over `frames`; GpuMs -1 when any frame
  /// had no query.
  static FrameTime Median(const std::vector<FrameTime>& frames);
};
}

#endif
