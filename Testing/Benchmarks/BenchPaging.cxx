// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Benchmark of out-of-core volume rendering: vtkPagePoolReader + vtkMultiVolumeRayCastMapper
// paging bricks from page pools through a RAM cache into the GPU atlas. scripts/bench paging
// runs it. Usage:
//   BenchPaging generate <dir>     -> nine 1024^3 uint8 volumes (9.7 GB of voxels) and one
//                                     512^3 accuracy volume as page pools in <dir>, each made
//                                     once (streamed slab by slab from vtkRTAnalyticSource)
//   BenchPaging header             -> the CSV header of `flythrough`
//   BenchPaging flythrough <dir> <cache MB> <atlas MB>
//                                  -> one row: the nine volumes in a 3 x 3 grid, a scripted
//                                     fly-through (48 moving frames), then still until
//                                     converged; peak RSS, frames to converge, ms per frame,
//                                     MB read and uploaded per frame, frames that read on the
//                                     render thread
//   BenchPaging feedback           -> the feedback reduction (vtkFeedbackReduction) on buffers
//                                     of 1/2, 1/4 and 1/8 of a 1920 x 1080 viewport: CPU and
//                                     OpenCL times and whether their lists are identical
//   BenchPaging accuracy <dir>     -> rows of the converged accuracy view at atlas budgets of
//                                     16 to 128 MB against the in-core rendering at full
//                                     resolution: RMS error, ms per frame, MB uploaded
// Rendering at 256 x 256 on whatever OpenGL the EGL window finds (llvmpipe here).
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataTestHelpers.h"
#include "StrataVolumeScenes.h"

#include "vtkCamera.h"
#include "vtkFeedbackReduction.h"
#include "vtkColorTransferFunction.h"
#include "vtkImageCast.h"
#include "vtkImageData.h"
#include "vtkImageShiftScale.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

namespace
{
const int Size = 256;
const int Edge = 1024; // voxels per axis of the fly-through volumes
const int Small = 512; // of the accuracy volume

double PeakRssMB()
{
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0; // kilobytes on Linux
}

bool Exists(const std::string& path)
{
  return static_cast<bool>(std::ifstream(path));
}

std::string PoolPath(const std::string& dir, int i)
{
  return dir + "/paging-volume-" + std::to_string(i) + ".spp";
}

// Volume i: the analytic wavelet with its own centre and frequencies, scaled to uint8.
bool Generate(const std::string& path, int edge, int i)
{
  if (Exists(path))
  {
    std::cerr << path << " exists\n";
    return true;
  }
  vtkNew<vtkRTAnalyticSource> source;
  source->SetWholeExtent(0, edge - 1, 0, edge - 1, 0, edge - 1);
  source->SetCenter(edge * (0.3 + 0.05 * i), edge * (0.6 - 0.04 * i), edge * 0.5);
  source->SetStandardDeviation(0.5);
  source->SetMaximum(255);
  source->SetXFreq(60.0 * 128 / edge * (1 + 0.1 * i));
  source->SetYFreq(30.0 * 128 / edge);
  source->SetZFreq(40.0 * 128 / edge * (1 + 0.05 * i));
  source->SetXMag(10);
  source->SetYMag(18);
  source->SetZMag(5);
  source->SetSubsampleRate(1);
  vtkNew<vtkImageShiftScale> scale; // about [37, 277] -> [0, 255]
  scale->SetInputConnection(source->GetOutputPort());
  scale->SetShift(-37.0);
  scale->SetScale(255.0 / 240.0);
  scale->SetOutputScalarTypeToUnsignedChar();
  scale->ClampOverflowOn();
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputConnection(scale->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->SetPageSize(32);
  writer->SetMemoryLimit(256);
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = writer->Write();
  std::cerr << path << ": " << (ok ? "written" : "FAILED") << ", " << writer->GetFileSize() / 1048576.0 << " MB, "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s\n";
  return ok;
}

vtkSmartPointer<vtkVolumeProperty> Property()
{
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0, 0.1, 0.2, 0.6);
  color->AddRGBPoint(120, 0.3, 0.7, 0.9);
  color->AddRGBPoint(170, 0.95, 0.8, 0.4);
  color->AddRGBPoint(255, 1.0, 0.3, 0.2);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(140, 0.0);
  opacity->AddPoint(170, 0.02);
  opacity->AddPoint(210, 0.08);
  opacity->AddPoint(255, 0.3);
  auto p = vtkSmartPointer<vtkVolumeProperty>::New();
  p->SetColor(color);
  p->SetScalarOpacity(opacity);
  p->SetInterpolationTypeToLinear();
  return p;
}

double Percentile(std::vector<double> v, double q)
{
  if (v.empty())
    return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1) + 0.5))];
}

int FlyThrough(const std::string& dir, double cacheMB, double atlasMB)
{
  for (int i = 0; i < 9; ++i)
  {
    if (!Exists(PoolPath(dir, i)))
    {
      std::printf("flythrough-9x1024,%g,,,,,,,,missing %s: run BenchPaging generate first\n", cacheMB + atlasMB,
        PoolPath(dir, i).c_str());
      return 1;
    }
  }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  strata_test::MakeWindow(win, ren, Size, Size);
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetSampleDistance(2.0);
  mapper->SetAtlasBudget(atlasMB);
  mapper->SetPageCacheBudget(cacheMB);
  mapper->SetPagesPerFrame(64);
  vtkNew<vtkMultiVolume> multi;
  multi->SetMapper(mapper);
  std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
  std::vector<vtkSmartPointer<vtkVolume>> volumes;
  auto property = Property();
  for (int i = 0; i < 9; ++i)
  {
    auto reader = vtkSmartPointer<vtkPagePoolReader>::New();
    reader->SetFileName(PoolPath(dir, i).c_str());
    mapper->SetInputConnection(i, reader->GetOutputPort());
    auto v = vtkSmartPointer<vtkVolume>::New();
    v->SetProperty(property);
    vtkNew<vtkTransform> t;
    t->Translate((i % 3) * 1.1 * Edge, (i / 3) * 1.1 * Edge, 0);
    v->SetUserTransform(t);
    multi->SetVolume(v, i);
    readers.push_back(reader);
    volumes.push_back(v);
  }
  ren->AddVolume(multi);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetViewAngle(35);
  cam->SetViewUp(0, 0, 1);
  const double centre[3] = { 1.6 * Edge, 1.6 * Edge, 0.5 * Edge };
  // The path: a low pass across the grid, turning, then still at the last pose.
  auto pose = [&](double s) {
    const double a = -2.2 + 1.6 * s;
    const double r = (3.6 - 1.2 * s) * Edge;
    cam->SetFocalPoint(centre[0] + 0.4 * Edge * std::cos(3 * s), centre[1], centre[2]);
    cam->SetPosition(centre[0] + r * std::cos(a), centre[1] + r * std::sin(a), centre[2] + (1.5 - 0.5 * s) * Edge);
    ren->ResetCameraClippingRange(0, 3.3 * Edge, 0, 3.3 * Edge, 0, Edge);
  };
  const int moving = 48;
  std::vector<double> ms;
  std::vector<double> uploaded;
  int waits = 0, converged = -1, frames = 0;
  long long lastRoots = 0;
  double lastRead = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (int f = 0; f < moving + 400 && converged < 0; ++f)
  {
    pose(std::min(1.0, double(f) / (moving - 1)));
    const auto t0 = std::chrono::steady_clock::now();
    win->Render();
    win->WaitForCompletion();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    const auto st = mapper->GetPagingStatistics();
    uploaded.push_back(st.BytesUploaded / 1048576.0);
    waits += st.RootPagesRead > lastRoots ? 1 : 0;
    lastRoots = st.RootPagesRead;
    lastRead = st.BytesRead / 1048576.0;
    ++frames;
    if (f >= moving && st.Converged)
      converged = f - moving + 1;
    if (f % 16 == 0)
      std::cerr << "  frame " << f << ": " << ms.back() << " ms, " << mapper->GetNumberOfResidentBricks() << " bricks, "
                << st.PendingPages << " pending, " << lastRead << " MB read, RSS " << PeakRssMB() << " MB\n";
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double upTotal = 0.0;
  for (double u : uploaded)
    upTotal += u;
  const auto st = mapper->GetPagingStatistics();
  std::printf("flythrough-9x1024,%g,%.0f,%d,%d,%.1f,%.1f,%.2f,%.2f,cache %g MB + atlas %g MB; 9 uint8 volumes of 1024^3 "
              "(9.66 GB of voxels) in 32^3 bricks; %d frames (%d moving) in %.0f s; io_wait_frames counts frames in "
              "which the render thread read pages itself (the 9 root pages when the pools were opened); %d failed pages; "
              "sample distance 2 voxels; %dx%d\n",
    cacheMB + atlasMB, PeakRssMB(), waits, converged, Percentile(ms, 0.5), Percentile(ms, 0.99), lastRead / frames,
    upTotal / frames, cacheMB, atlasMB, frames, moving, seconds, st.Failures, Size, Size);
  return 0;
}

int Accuracy(const std::string& dir)
{
  const std::string path = PoolPath(dir, 9);
  if (!Exists(path))
  {
    std::printf("accuracy-512,,,,,,missing %s: run BenchPaging generate first\n", path.c_str());
    return 1;
  }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  strata_test::MakeWindow(win, ren, Size, Size);
  vtkNew<vtkVolume> volume;
  volume->SetProperty(Property());
  ren->AddVolume(volume);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetFocalPoint(Small / 2.0, Small / 2.0, Small / 2.0);
  cam->SetPosition(-0.6 * Small, -0.9 * Small, 1.3 * Small);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(35);
  ren->ResetCameraClippingRange(0, Small, 0, Small, 0, Small);
  // The reference: the same pool read whole through the pipeline, rendered in core with room
  // for every brick.
  vtkNew<vtkPagePoolReader> whole;
  whole->SetFileName(path.c_str());
  whole->Update();
  vtkNew<vtkMultiVolumeRayCastMapper> incore;
  incore->SetInputData(whole->GetOutput());
  incore->SetSampleDistance(1.0);
  incore->SetAtlasBudget(4096);
  volume->SetMapper(incore);
  for (int i = 0; i < 3; ++i)
    win->Render();
  const auto reference = strata_test::ReadRGB(win);
  const std::vector<double> ref(reference.begin(), reference.end());
  for (double atlasMB : { 16.0, 32.0, 64.0, 128.0 })
  {
    vtkNew<vtkPagePoolReader> reader;
    reader->SetFileName(path.c_str());
    vtkNew<vtkMultiVolumeRayCastMapper> paged;
    paged->SetInputConnection(reader->GetOutputPort());
    paged->SetSampleDistance(1.0);
    paged->SetAtlasBudget(atlasMB);
    paged->SetPageCacheBudget(256);
    paged->SetPagesPerFrame(256);
    volume->SetMapper(paged);
    int frames = 0;
    double up = 0.0;
    while (frames < 400)
    {
      win->Render();
      ++frames;
      up += paged->GetPagingStatistics().BytesUploaded / 1048576.0;
      if (paged->GetPagingStatistics().Converged)
        break;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    std::vector<double> ms;
    for (int i = 0; i < 3; ++i)
    {
      const auto t0 = std::chrono::steady_clock::now();
      win->Render();
      win->WaitForCompletion();
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    const auto err = strata_test::ImageError(strata_test::ReadRGB(win), ref);
    std::printf("accuracy-512,%g,%.4f,%.1f,%.1f,%d,%.2f,%d bricks resident; converged after %d frames; %.1f MB uploaded "
                "in all; reference: in-core with every brick (%dx%d; sample distance 1 voxel)\n",
      atlasMB, err.Rms, err.Max, Percentile(ms, 0.5), frames, up / frames, paged->GetNumberOfResidentBricks(), frames, up,
      Size, Size);
    std::fflush(stdout);
  }
  return 0;
}
}
// A feedback buffer like a ray caster writes: blocks of pixels needing the same brick of a
// screen-space-error cut over nine volumes, 10 % empty (background).
int Feedback()
{
  std::printf("case,scale,pixels,entries,cpu_ms,opencl_ms,identical,device\n");
  vtkFeedbackReduction reduction;
  const bool cl = reduction.IsOpenCLAvailable();
  for (int scale : { 2, 4, 8 })
  {
    const int w = 1920 / scale, h = 1080 / scale;
    std::vector<uint32_t> ids(size_t(w) * h);
    unsigned state = 7u;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
      {
        const int bx = x * scale / 24, by = y * scale / 24; // a brick covers ~24 pixels
        state = state * 1664525u + 1013904223u;
        const bool empty = (state >> 24) < 26;
        const int level = std::min(5, (bx + by) / 16);
        ids[size_t(y) * w + x] = empty ? 0u
                                       : vtkFeedbackReduction::PackPage((bx / 16 + 3 * (by / 16)) % 9, level,
                                           static_cast<uint32_t>((bx * 131 + by * 71) % 32768));
      }
    std::vector<vtkFeedbackReduction::Entry> cpu, gpu;
    std::vector<double> cpuMs, clMs;
    for (int r = 0; r < 5; ++r)
    {
      reduction.ReduceCPU(ids.data(), ids.size(), cpu);
      cpuMs.push_back(1000.0 * reduction.GetLastCPUSeconds());
      if (cl && reduction.ReduceOpenCL(ids.data(), ids.size(), gpu))
        clMs.push_back(1000.0 * reduction.GetLastOpenCLSeconds());
    }
    bool same = cl && cpu.size() == gpu.size();
    for (size_t i = 0; same && i < cpu.size(); ++i)
      same = cpu[i].Page == gpu[i].Page && cpu[i].Coverage == gpu[i].Coverage;
    std::printf("feedback,1/%d,%d,%zu,%.3f,%s,%s,%s\n", scale, w * h, cpu.size(), Percentile(cpuMs, 0.5),
      clMs.empty() ? "" : std::to_string(Percentile(clMs, 0.5)).c_str(), cl ? (same ? "yes" : "no") : "",
      cl ? reduction.GetOpenCLDeviceName().c_str() : reduction.GetOpenCLMessage().c_str());
  }
  return 0;
}

int main(int argc, char* argv[])
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "generate" && argc > 2)
  {
    bool ok = true;
    for (int i = 0; i < 9; ++i)
      ok = Generate(PoolPath(argv[2], i), Edge, i) && ok;
    ok = Generate(PoolPath(argv[2], 9), Small, 9) && ok;
    return ok ? 0 : 1;
  }
  if (mode == "header")
  {
    std::printf("case,budget_mb,peak_rss_mb,io_wait_frames,frames_to_converge,ms_per_frame_median,ms_per_frame_p99,"
                "mb_read_per_frame,mb_uploaded_per_frame,note\n");
    return 0;
  }
  if (mode == "flythrough" && argc > 4)
    return FlyThrough(argv[2], std::atof(argv[3]), std::atof(argv[4]));
  if (mode == "feedback")
    return Feedback();
  if (mode == "accuracy" && argc > 2)
    return Accuracy(argv[2]);
  std::cerr << "usage: BenchPaging generate <dir> | header | flythrough <dir> <cache MB> <atlas MB> | accuracy <dir>\n";
  return 2;
}
