// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Out-of-core horizons: the stack of the paper's size (3 horizons of 6870 x 14300 points,
// 16-bit) as tile pools generated once (streamed row slab by row slab through
// vtkImageToPagePoolWriter, never held whole), then a scripted fly-through with the
// vtkStackedHeightFieldMapper paging them under a page cache and an atlas budget. Prints one
// row of bench-results/paging.csv.
//
//   BenchPagingHorizons generate <dir>      (also a 3 x 2049^2 stack for the accuracy rows)
//   BenchPagingHorizons flythrough <dir> <cache MB> <atlas MB> [prefetch] [no-morph]
//   BenchPagingHorizons accuracy <dir>      (rows of bench-results/paging-accuracy.csv)
#include "StrataHeightFieldScenes.h" // For MakeWindow, FractalNoise
#include "StrataImageHelpers.h"      // For ReadRGB
#include "StrataTestHelpers.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPNGWriter.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedShortArray.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

using strata_test::FileExists;
using strata_test::PeakRssMB;
using strata_test::Percentile;

namespace
{
const int NX = 6870;
const int NY = 14300;
const double Spacing = 12.5;
const int Size = 256;

/// Horizon k of the stack, computed for exactly the rows asked for: uint16 depths in
/// decimetres, a regional dip plus fractal relief, the three horizons 300-900 m apart.
class HorizonSource : public vtkImageAlgorithm
{
public:
  static HorizonSource* New();
  vtkTypeMacro(HorizonSource, vtkImageAlgorithm);
  int Horizon = 0;
  int Nx = NX, Ny = NY; ///< the same horizons sampled on a coarser grid when smaller

protected:
  HorizonSource() { this->SetNumberOfInputPorts(0); }
  int RequestInformation(vtkInformation*,
    vtkInformationVector**,
    vtkInformationVector* out) override
  {
    vtkInformation* info = out->GetInformationObject(0);
    const int extent[6] = { 0, this->Nx - 1, 0, this->Ny - 1, 0, 0 };
    info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    const double spacing[3] = {
      Spacing * (NX - 1) / (this->Nx - 1), Spacing * (NY - 1) / (this->Ny - 1), 1.0
    };
    const double origin[3] = { 420000.0, 6500000.0, 0.0 };
    info->Set(vtkDataObject::SPACING(), spacing, 3);
    info->Set(vtkDataObject::ORIGIN(), origin, 3);
    info->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
    vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_UNSIGNED_SHORT, 1);
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    vtkInformation* info = out->GetInformationObject(0);
    auto* image = vtkImageData::GetData(info);
    int extent[6];
    info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent);
    image->SetExtent(extent);
    image->AllocateScalars(VTK_UNSIGNED_SHORT, 1);
    auto* values = static_cast<unsigned short*>(image->GetScalarPointer());
    const int k = this->Horizon;
    size_t n = 0;
    for (int j = extent[2]; j <= extent[3]; ++j)
    {
      for (int i = extent[0]; i <= extent[1]; ++i)
      {
        const double u = double(i) / (this->Nx - 1), v = double(j) / (this->Ny - 1);
        const double metres = 1200.0 + 600.0 * k + 900.0 * u + 500.0 * v +
                              (180.0 + 40.0 * k) * strata_test::FractalNoise(
                                                     12 * u + 3.1 * k, 25 * v + 1.7 * k, 31 + k, 7);
        values[n++] =
          static_cast<unsigned short>(std::min(65535.0, std::max(0.0, std::round(metres * 10.0))));
      }
    }
    return 1;
  }
};
vtkStandardNewMacro(HorizonSource);

std::string PoolPath(const std::string& dir, int k, bool small = false)
{
  return dir + (small ? "/paging-horizon-small-" : "/paging-horizon-") + std::to_string(k) + ".spp";
}

const int SmallN = 2049;   // points per axis of the accuracy stack
const int SmallPage = 129; // its tile size

int Generate(const std::string& dir)
{
  for (int k = 0; k < 6; ++k)
  {
    const bool small = k >= 3;
    const std::string path = PoolPath(dir, k % 3, small);
    if (FileExists(path))
    {
      std::cerr << path << " exists\n";
      continue;
    }
    vtkNew<HorizonSource> source;
    source->Horizon = k % 3;
    if (small)
      source->Nx = source->Ny = SmallN;
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputConnection(source->GetOutputPort());
    writer->SetFileName(path.c_str());
    writer->SetPageSize(small ? SmallPage : 257);
    writer->SetMemoryLimit(256);
    const auto t0 = std::chrono::steady_clock::now();
    const bool ok = writer->Write();
    std::cerr << path << ": " << (ok ? "written" : "FAILED") << ", "
              << writer->GetFileSize() / 1048576.0 << " MB, "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
              << " s, peak RSS " << PeakRssMB() << " MB\n";
    if (!ok)
      return 1;
  }
  return 0;
}

int FlyThrough(const std::string& dir, double cacheMB, double atlasMB, bool prefetch, bool morph)
{
  const std::string name = std::string("flythrough-horizons-3x6870x14300") +
                           (prefetch ? "-prefetch" : "") + (morph ? "" : "-no-morph");
  for (int k = 0; k < 3; ++k)
  {
    if (!FileExists(PoolPath(dir, k)))
    {
      std::printf("%s,%g,,,,,,,,missing %s: run BenchPagingHorizons generate first\n",
        name.c_str(),
        cacheMB + atlasMB,
        PoolPath(dir, k).c_str());
      return 1;
    }
  }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  strata_test::MakeWindow(win, ren, Size, Size);
  vtkNew<vtkStackedHeightFieldMapper> mapper;
  mapper->SetHeightScale(-0.1); // decimetres, depth downwards
  mapper->SetPageCacheBudget(cacheMB);
  mapper->SetPrefetch(prefetch);
  if (!morph)
    mapper->SetMorphFrames(0);
  mapper->SetAtlasBudget(atlasMB);
  mapper->SetPagesPerFrame(32);
  mapper->SetLevelOfDetailThreshold(1.0); // about a cell per pixel: no I/O for sub-pixel detail
  mapper->SetColorMode(vtkStackedHeightFieldMapper::ColorModes::LookupTable);
  std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
  for (int k = 0; k < 3; ++k)
  {
    auto reader = vtkSmartPointer<vtkPagePoolReader>::New();
    reader->SetFileName(PoolPath(dir, k).c_str());
    mapper->AddInputConnection(reader->GetOutputPort());
    readers.push_back(reader);
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->SetScale(1, 1, 8); // relief of a few hundred metres over 170 km, exaggerated
  ren->AddActor(actor);
  // Opening the data, as any VTK application does before its first frame: the readers'
  // pipeline update reads the coarsest level (the three root tiles). Frames never read.
  mapper->GetBounds();
  double b[6];
  actor->GetBounds(b);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetViewAngle(40);
  cam->SetViewUp(0, 0, 1);
  const double cx = 0.5 * (b[0] + b[1]), lx = b[1] - b[0], ly = b[3] - b[2];
  // The path: a low oblique pass from the south end to two thirds up the survey, turning.
  auto pose = [&](double s)
  {
    const double y = b[2] + (0.05 + 0.6 * s) * ly;
    const double x = cx + 0.25 * lx * std::sin(3.0 * s);
    cam->SetFocalPoint(x, y + 0.3 * ly, b[4]);
    cam->SetPosition(x - 0.1 * lx, y - 0.05 * ly, b[5] + 0.04 * ly);
    ren->ResetCameraClippingRange(b);
  };
  const int moving = 48;
  std::vector<double> ms, uploaded;
  int waits = 0, converged = -1, frames = 0, lastRoots = 0;
  const auto start = std::chrono::steady_clock::now();
  double lastRead = 0.0;
  for (int f = 0; f < moving + 400 && converged < 0; ++f)
  {
    pose(std::min(1.0, double(f) / (moving - 1)));
    const auto t0 = std::chrono::steady_clock::now();
    win->Render();
    win->WaitForCompletion();
    ms.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    const auto st = mapper->GetPagingStatistics();
    uploaded.push_back(st.BytesUploaded / 1048576.0);
    waits +=
      st.RootPagesRead > lastRoots ? 1 : 0; // tiles read on this thread (roots without a reader)
    lastRoots = st.RootPagesRead;
    lastRead = st.BytesRead / 1048576.0;
    ++frames;
    if (f >= moving && st.Converged)
      converged = f - moving + 1;
    if (f % 16 == 0)
      std::cerr << "  frame " << f << ": " << ms.back() << " ms, " << st.CutTiles << " tiles ("
                << st.FinestTiles << " level 0), " << st.PendingPages << " pending, " << lastRead
                << " MB read, RSS " << PeakRssMB() << " MB\n";
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double upTotal = 0.0;
  for (double u : uploaded)
    upTotal += u;
  const auto st = mapper->GetPagingStatistics();
  std::printf(
    "%s,%g,%.0f,%d,%d,%.1f,%.1f,%.2f,%.2f,cache %g MB + atlas %g MB (%d tiles); 3 uint16 horizons "
    "of 6870 x 14300 (589 MB of heights) in 257^2 tiles; %d frames (%d moving) in %.0f s; feedback "
    "1/4, level of detail 1 cell per pixel, prefetch %s, refinements blended over %d frames; the "
    "readers read the 3 root tiles before the first frame; io_wait_frames counts frames in which "
    "the render thread read tiles itself; %d failed tiles; %dx%d\n",
    name.c_str(),
    cacheMB + atlasMB,
    PeakRssMB(),
    waits,
    converged,
    Percentile(ms, 0.5),
    Percentile(ms, 0.99),
    lastRead / frames,
    upTotal / frames,
    cacheMB,
    atlasMB,
    st.AtlasSlots,
    frames,
    moving,
    seconds,
    prefetch ? "on" : "off",
    mapper->GetMorphFrames(),
    st.Failures,
    Size,
    Size);
  if (const char* png = std::getenv("STRATA_BENCH_PNG"))
  {
    // The converged last pose, for a look.
    win->Render();
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(win);
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputConnection(grab->GetOutputPort());
    writer->SetFileName(png);
    writer->Write();
  }
  return 0;
}
}

// The converged view at several atlas budgets against the in-core rendering of the full data.
int Accuracy(const std::string& dir)
{
  std::vector<vtkSmartPointer<vtkImageData>> full;
  for (int k = 0; k < 3; ++k)
  {
    if (!FileExists(PoolPath(dir, k, true)))
    {
      std::printf("accuracy-horizons-%d,,,,,,,missing %s: run BenchPagingHorizons generate first\n",
        SmallN,
        PoolPath(dir, k, true).c_str());
      return 1;
    }
    vtkNew<vtkPagePoolReader> reader; // resolution 1: the finest level, read whole
    reader->SetFileName(PoolPath(dir, k, true).c_str());
    reader->Update();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(reader->GetOutput());
    full.push_back(image);
  }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  strata_test::MakeWindow(win, ren, Size, Size);
  vtkNew<vtkActor> actor;
  actor->SetScale(1, 1, 8);
  ren->AddActor(actor);
  auto setUp = [&](vtkStackedHeightFieldMapper* m)
  {
    m->SetHeightScale(-0.1);
    m->SetColorMode(vtkStackedHeightFieldMapper::ColorModes::LookupTable);
    actor->SetMapper(m);
  };
  vtkNew<vtkStackedHeightFieldMapper> incore;
  setUp(incore);
  for (auto& image : full)
    incore->AddInputDataObject(image);
  double b[6];
  actor->GetBounds(b);
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetViewAngle(40);
  cam->SetViewUp(0, 0, 1);
  const double lx = b[1] - b[0], ly = b[3] - b[2];
  cam->SetFocalPoint(b[0] + 0.5 * lx, b[2] + 0.6 * ly, b[4]);
  cam->SetPosition(b[0] + 0.4 * lx, b[2] - 0.1 * ly, b[5] + 0.15 * ly);
  ren->ResetCameraClippingRange(b);
  win->Render();
  const auto reference = strata_test::ReadRGB(win);
  for (int feedbackScale : { 0, 2, 4, 8 })
    for (double atlasMB : { 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0 })
    {
      vtkNew<vtkStackedHeightFieldMapper> paged;
      setUp(paged);
      paged->SetAtlasBudget(atlasMB);
      paged->SetLevelOfDetailFeedback(feedbackScale > 0);
      paged->SetFeedbackScale(std::max(1, feedbackScale));
      paged->SetPagesPerFrame(32);
      std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
      for (int k = 0; k < 3; ++k)
      {
        auto reader = vtkSmartPointer<vtkPagePoolReader>::New();
        reader->SetFileName(PoolPath(dir, k, true).c_str());
        paged->AddInputConnection(reader->GetOutputPort());
        readers.push_back(reader);
      }
      int frames = 0;
      double uploaded = 0.0;
      for (; frames < 400; ++frames)
      {
        win->Render();
        const auto st = paged->GetPagingStatistics();
        uploaded += st.BytesUploaded / 1048576.0;
        if (st.Converged)
          break;
        paged->WaitForPages(1.0);
      }
      std::vector<double> ms;
      for (int f = 0; f < 5; ++f)
      {
        const auto t0 = std::chrono::steady_clock::now();
        win->Render();
        win->WaitForCompletion();
        ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      }
      const auto image = strata_test::ReadRGB(win);
      double sum = 0.0;
      int worst = 0;
      long differing = 0;
      for (size_t p = 0; p < image.size(); ++p)
      {
        const int e = std::abs(int(image[p]) - int(reference[p]));
        sum += double(e) * e;
        worst = std::max(worst, e);
      }
      for (size_t p = 0; p + 2 < image.size(); p += 3)
        differing += (image[p] != reference[p] || image[p + 1] != reference[p + 1] ||
                       image[p + 2] != reference[p + 2])
                       ? 1
                       : 0;
      const auto st = paged->GetPagingStatistics();
      const std::string name = "accuracy-horizons-" + std::to_string(SmallN) +
                               (feedbackScale > 0 ? "-feedback-1/" + std::to_string(feedbackScale)
                                                  : std::string("-no-feedback"));
      std::printf(
        "%s,%g,%.4f,%d,%.1f,%d,%.2f,%d tiles of %dx%d resident (%d at level 0); %.1f %% of "
        "pixels differ; %.1f MB uploaded in all; %s; reference: in-core, every point (%dx%d)\n",
        name.c_str(),
        atlasMB,
        std::sqrt(sum / image.size()),
        worst,
        Percentile(ms, 0.5),
        frames + 1,
        uploaded / (frames + 1),
        st.CutTiles,
        SmallPage,
        SmallPage,
        st.FinestTiles,
        100.0 * differing / (image.size() / 3),
        uploaded,
        feedbackScale > 0
          ? ("feedback reduction " + std::to_string(st.FeedbackMilliseconds) + " ms").c_str()
          : "screen-space cut",
        Size,
        Size);
      std::fflush(stdout);
    }
  return 0;
}

int main(int argc, char* argv[])
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "generate" && argc > 2)
    return Generate(argv[2]);
  if (mode == "accuracy" && argc > 2)
    return Accuracy(argv[2]);
  if (mode == "flythrough" && argc > 4)
  {
    bool prefetch = false, morph = true;
    for (int a = 5; a < argc; ++a)
    {
      prefetch = prefetch || std::string(argv[a]) == "prefetch";
      morph = morph && std::string(argv[a]) != "no-morph";
    }
    return FlyThrough(argv[2], std::atof(argv[3]), std::atof(argv[4]), prefetch, morph);
  }
  std::cerr << "usage: BenchPagingHorizons generate <dir> | flythrough <dir> <cache MB> <atlas MB> "
               "[prefetch] [no-morph]\n";
  return 2;
}
