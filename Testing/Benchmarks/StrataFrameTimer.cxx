// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataFrameTimer.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderWindow.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <ctime>

namespace
{
double ThreadCpuMs()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1000.0 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

double MedianOf(std::vector<double> v)
{
  if (v.empty())
    return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2]; // the upper of two middles, as the frame benchmarks always took it
}
}

namespace strata_bench
{
FrameTime FrameTimer::Time(vtkRenderWindow* window)
{
  FrameTime time;
  window->MakeCurrent();
  // Timer queries need GL 3.3 or ARB_timer_query; GLEW is initialised by the first render.
  const bool timer = vtkOpenGLRenderWindow::SafeDownCast(window) && glGenQueries &&
                     (GLEW_VERSION_3_3 || GLEW_ARB_timer_query);
  GLuint query = 0;
  if (timer)
  {
    glGenQueries(1, &query);
    glBeginQuery(GL_TIME_ELAPSED, query);
  }
  const auto wall = std::chrono::steady_clock::now();
  const double cpu = ThreadCpuMs();
  window->Render();
  time.CpuMs = ThreadCpuMs() - cpu;
  window->MakeCurrent();
  if (timer)
    glEndQuery(GL_TIME_ELAPSED);
  window->WaitForCompletion();
  time.WallMs =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall).count();
  if (timer)
  {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    glDeleteQueries(1, &query);
    time.GpuMs = 1e-6 * static_cast<double>(ns);
  }
  return time;
}

FrameTime FrameTimer::Median(const std::vector<FrameTime>& frames)
{
  std::vector<double> wall, gpu, cpu;
  bool allGpu = !frames.empty();
  for (const FrameTime& f : frames)
  {
    wall.push_back(f.WallMs);
    cpu.push_back(f.CpuMs);
    gpu.push_back(f.GpuMs);
    allGpu = allGpu && f.GpuMs >= 0.0;
  }
  FrameTime median;
  median.WallMs = MedianOf(wall);
  median.CpuMs = MedianOf(cpu);
  median.GpuMs = allGpu ? MedianOf(gpu) : -1.0;
  return median;
}
}
