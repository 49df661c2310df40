// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Soak (issue 14): a fly-through of Frames frames (one path flown twice) at a Size x Size
// viewport over a paged volume and a paged horizon stack in one renderer, both with
// level-of-detail feedback, small atlases and page caches of 1 and 2 MB, so that the cuts
// refine and coarsen, the atlases evict and the caches turn over all the way. Asserted:
// - memory stays flat over the second pass (the caches are full and every pose, page and
//   shader variant of the path was met in the first): the least-squares slope of the bytes
//   the allocator has handed out (mallinfo2, all arenas) is below HeapSlopeBoundKiB per frame
//   (measured 0.003-0.017; one volume brick kept per frame would be 2 KB, one horizon tile
//   4.3 KB), and that of the resident set (VmRSS) below RssSlopeBoundKiB, which only a gross
//   leak exceeds. The resident set's slope is measured 0-0.13 KB a frame, but now and then it
//   takes a step of 1-3 MB that the bytes in use do not (up to 2.8 KB a frame over the pass):
//   /proc/self/smaps shows the main heap's break and a page-cache worker's arena moving up,
//   free lists of pages freed on one thread and allocated on another.
// - GL objects do not grow: the window's live GL names (StrataGLNames) after the last frame
//   equal those after the first Warm frames, and with the props and mappers gone they are
//   those of the empty window before.
// Under AddressSanitizer (scripts/asan) the heap is ASan's allocator, counted by ASan with the
// same bound (measured 0.0037 KB a frame); the resident set is not asserted there: ASan's
// quarantine fills over the whole run (StrataMemory.h), 8.3-10.7 KB a frame without a leak.
#include "StrataGLNames.h"
#include "StrataHeightFieldScenes.h" // For MakeWindow, MakeHorizon, FractalNoise
#include "StrataMemory.h"            // For ResidentKiB, HeapInUseKiB, UnderAddressSanitizer
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h" // For MakeBlobVolume, MakeVolumeProperty

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

using namespace strata_test;

namespace
{
const int Frames = 2000;
const int Warm = 100;
const int Size = 64;
const double HeapSlopeBoundKiB = 0.1;
const double RssSlopeBoundKiB = 8.0;

std::string WritePool(vtkImageData* image, const std::string& name, int page)
{
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(name.c_str());
  writer->SetPageSize(page);
  Check(writer->Write(), "pool " + name + " written");
  return name;
}

// A fractal horizon of n x n points over [0, 64]^2, around `height`.
vtkSmartPointer<vtkImageData> Horizon(int n, double height, int seed)
{
  std::vector<float> z(size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      z[size_t(j) * n + i] = static_cast<float>(
        height + 6.0 * FractalNoise(6.0 * i / (n - 1), 6.0 * j / (n - 1), seed, 5));
  const double s = 64.0 / (n - 1);
  return MakeHorizon(n, n, 0.0, 0.0, s, s, 0.0, z);
}

/// Least-squares slope of y over x = 0, 1, ...
double Slope(const std::vector<double>& y)
{
  const double n = static_cast<double>(y.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < y.size(); ++i)
  {
    sx += i;
    sy += y[i];
    sxx += double(i) * i;
    sxy += i * y[i];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}
}

int TestPagingSoak(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  // 6 MB of volume bricks and 2 x 4 MB of horizon tiles at level 0: several times the caches.
  const double spacing[3] = { 0.5, 0.5, 0.5 }, origin[3] = { 0.0, 0.0, 8.0 };
  const std::string volumePool =
    WritePool(MakeBlobVolume(128, 128, 96, spacing, origin, 4), paths.Output + "/soak-v.spp", 8);
  const std::vector<std::string> horizonPools = {
    WritePool(Horizon(1025, -4.0, 3), paths.Output + "/soak-h0.spp", 33),
    WritePool(Horizon(1025, -14.0, 5), paths.Output + "/soak-h1.spp", 33)
  };

  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  MakeWindow(win, ren, Size, Size);
  win->Render();
  const GLNames empty = CountGLNames(win);

  std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
  auto reader = [&readers](const std::string& pool)
  {
    auto r = vtkSmartPointer<vtkPagePoolReader>::New();
    r->SetFileName(pool.c_str());
    readers.push_back(r);
    return r;
  };
  auto volumes = vtkSmartPointer<vtkMultiVolumeRayCastMapper>::New();
  volumes->SetInputConnection(0, reader(volumePool)->GetOutputPort());
  volumes->SetSampleDistance(1.0);
  volumes->SetPageCacheBudget(1.0);
  volumes->SetAtlasBudget(0.25); // 128 bricks of 8^3 floats, of 3072 at level 0
  auto multi = vtkSmartPointer<vtkMultiVolume>::New();
  multi->SetMapper(volumes);
  vtkNew<vtkVolume> member;
  member->SetProperty(MakeVolumeProperty(1));
  multi->SetVolume(member, 0);
  ren->AddVolume(multi);

  auto horizons = vtkSmartPointer<vtkStackedHeightFieldMapper>::New();
  for (const std::string& pool : horizonPools)
    horizons->AddInputConnection(reader(pool)->GetOutputPort());
  horizons->SetColorMode(vtkStackedHeightFieldMapper::ColorModes::LookupTable);
  horizons->SetPageCacheBudget(2.0);
  horizons->SetAtlasBudget(0.5); // 120 tiles of 33^2, of 2048 at level 0
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(horizons);
  ren->AddActor(actor);

  // Twice the same path: two orbits around the scene while dollying in and out every 250
  // frames. The first pass meets every pose, page and shader variant the path has, so the
  // second's allocations can only be what a frame leaks.
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(32, 32, 8);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(40);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<double> rss, heap;
  GLNames warm;
  double uploadedMB = 0.0;
  int finestHorizons = 0;
  long long readVolume = 0, readHorizons = 0;
  for (int f = 0; f < Frames; ++f)
  {
    const int p = f % (Frames / 2);
    const double a = 2.0 * std::acos(-1.0) * 4.0 * p / Frames;
    const double d = 70.0 + 50.0 * std::cos(2.0 * std::acos(-1.0) * p / 250.0);
    cam->SetPosition(32 + d * std::cos(a), 32 + d * std::sin(a), 8 + 0.6 * d);
    ren->ResetCameraClippingRange(-10, 80, -10, 80, -30, 60);
    win->Render();
    const auto sv = volumes->GetPagingStatistics();
    const auto sh = horizons->GetPagingStatistics();
    uploadedMB += (sv.BytesUploaded + sh.BytesUploaded) / 1048576.0;
    readVolume = sv.BytesRead;
    readHorizons = sh.BytesRead;
    finestHorizons = std::max(finestHorizons, sh.FinestTiles);
    if (f == Warm - 1)
      warm = CountGLNames(win);
    if (f >= Frames / 2)
    {
      rss.push_back(static_cast<double>(ResidentKiB()));
      heap.push_back(HeapInUseKiB());
    }
    if (f % 250 == 0 || f == Frames - 1)
      std::cout << "soak: frame " << f << ": resident " << ResidentKiB() / 1024.0
                << " MB, heap in use " << HeapInUseKiB() / 1024.0 << " MB, page caches "
                << sv.CacheBytes / 1048576.0 << " and " << sh.CacheBytes / 1048576.0 << " MB\n";
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const GLNames last = CountGLNames(win);
  ren->RemoveAllViewProps();
  actor = nullptr;
  multi = nullptr;
  volumes = nullptr;
  horizons = nullptr;
  readers.clear();
  const GLNames gone = CountGLNames(win);

  const double slope = Slope(rss);
  const double heapSlope = Slope(heap);
  std::cout << "soak: " << Frames << " frames at " << Size << "^2 in " << seconds << " s; "
            << uploadedMB << " MB uploaded to the atlases, " << readVolume / 1048576.0 << " and "
            << readHorizons / 1048576.0 << " MB read into the 1 and 2 MB page caches; up to "
            << finestHorizons << " level-0 tiles at once\n"
            << "soak: resident " << rss.front() / 1024.0 << " MB at frame " << Frames / 2 << ", "
            << rss.back() / 1024.0 << " MB at the end; slope over the second pass " << slope
            << " KB per frame (bound " << RssSlopeBoundKiB << "); heap in use "
            << heap.front() / 1024.0 << " MB, then " << heap.back() / 1024.0 << " MB, slope "
            << heapSlope << " KB per frame (bound " << HeapSlopeBoundKiB << ")\n"
            << "soak: GL names: " << empty.Text() << " empty; " << warm.Text() << " after " << Warm
            << " frames; " << last.Text() << " after " << Frames << "; " << gone.Text()
            << " with the scene gone\n";
  Check(heapSlope < HeapSlopeBoundKiB, "the heap stays flat");
  if (UnderAddressSanitizer())
    std::cout << "soak: the resident set is not asserted under AddressSanitizer (its quarantine "
                 "fills over the run)\n";
  else
    Check(slope < RssSlopeBoundKiB, "resident memory stays flat");
  Check(warm.Total() > empty.Total() && last == warm, "no GL object is leaked while flying");
  Check(gone == empty, "every GL object of the scene is released");
  Check(uploadedMB > 20.0 && readVolume > 2 * 1048576 && readHorizons > 4 * 1048576,
    "the atlases and the caches turned over many times");
  if (output->Errors || output->Warnings)
  {
    std::cerr << "FAILED: VTK printed " << output->Errors << " errors and " << output->Warnings
              << " warnings\n";
    return EXIT_FAILURE;
  }
  return Failures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
