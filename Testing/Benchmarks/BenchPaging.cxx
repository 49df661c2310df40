// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Benchmark of out-of-core volume rendering: vtkPagePoolReader + vtkMultiVolumeRayCastMapper
// paging bricks from page pools through a RAM cache into the GPU atlas. scripts/bench paging
// runs it. Usage:
//   BenchPaging generate <dir>     -> nine 1024^3 uint8 volumes (9.7 GB of voxels), one 512^3
//                                     accuracy volume and eight 256^3 series steps as page
//                                     pools in <dir>, each made
//                                     once (streamed slab by slab from vtkRTAnalyticSource)
//   BenchPaging header             -> the CSV header of `flythrough`
//   BenchPaging flythrough <dir> <cache MB> <atlas MB> [no-feedback] [prefetch]
//                                  -> one row: the nine volumes in a 3 x 3 grid, opened (the
//                                     readers' pipeline update: header, page table, coarsest
//                                     level), then a scripted fly-through (48 moving frames),
//                                     then still until converged; peak RSS, frames to converge,
//                                     ms per frame, MB read and uploaded per frame, frames in
//                                     which the render thread read pages (the mapper itself or
//                                     a reader's pipeline update); level-of-detail feedback at
//                                     1/4 unless no-feedback
//   BenchPaging feedback           -> the feedback reduction (strata::FeedbackReduction) on buffers
//                                     of 1/2, 1/4 and 1/8 of a 1920 x 1080 viewport: CPU and
//                                     OpenCL times and whether their lists are identical
//   BenchPaging accuracy-header    -> the CSV header of `accuracy`
//   BenchPaging accuracy <dir>     -> rows of the converged accuracy view at atlas budgets of
//                                     16 to 128 MB, without feedback and with feedback buffers
//                                     of 1/2, 1/4 and 1/8 of the viewport, against the in-core
//                                     rendering at full resolution: RMS error, ms per frame,
//                                     MB uploaded
//   BenchPaging report <csv> <png> -> the accuracy rows (any case in the CSV, e.g. horizons)
//                                     as RMS error against atlas budget
//   BenchPaging series-header      -> the CSV header of `series`
//   BenchPaging series <dir> <cache MB> <atlas MB> [no-prefetch]
//                                  -> one row: a 4-D series (eight 256^3 time steps, one pool
//                                     each, made by `generate`) played twice through at four
//                                     steps a second: I/O-wait frames, ms per step switch, MB
//                                     read per step, with the next step prefetched or not
//                                     (the steps are made first if `generate` has not)
// Rendering at 256 x 256 on whatever OpenGL the EGL window finds (llvmpipe here).
#include "StrataBenchChart.h"
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataTestHelpers.h"
#include "StrataVolumeScenes.h"

#include "StrataFeedbackReduction.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkChart.h"
#include "vtkColorTransferFunction.h"
#include "vtkImageCast.h"
#include "vtkImageData.h"
#include "vtkImageShiftScale.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkInformation.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPen.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlotLine.h"
#include "vtkPlotPoints.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using strata_test::FileExists;
using strata_test::PeakRssMB;
using strata_test::Percentile;

namespace
{
const int Size = 256;
const int Edge = 1024; // voxels per axis of the fly-through volumes
const int Small = 512; // of the accuracy volume

std::string PoolPath(const std::string& dir, int i)
{
  return dir + "/paging-volume-" + std::to_string(i) + ".spp";
}

// Volume i: the analytic wavelet with its own centre and frequencies, scaled to uint8.
bool Generate(const std::string& path, int edge, int i)
{
  if (FileExists(path))
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
  std::cerr << path << ": " << (ok ? "written" : "FAILED") << ", "
            << writer->GetFileSize() / 1048576.0 << " MB, "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
            << " s\n";
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

// Pages the readers read in their pipeline updates: the pages of each RequestData (0 when it
// answered from its last output), summed at its EndEvent.
struct PageReads
{
  long long Pages = 0;
  static void Count(vtkObject* caller, unsigned long, void* self, void*)
  {
    static_cast<PageReads*>(self)->Pages +=
      static_cast<vtkPagePoolReader*>(caller)->GetNumberOfPagesRead();
  }
};

int FlyThrough(const std::string& dir, double cacheMB, double atlasMB, bool feedback, bool prefetch)
{
  const std::string name =
    std::string(feedback ? "flythrough-9x1024" : "flythrough-9x1024-no-feedback") +
    (prefetch ? "-prefetch" : "");
  for (int i = 0; i < 9; ++i)
  {
    if (!FileExists(PoolPath(dir, i)))
    {
      std::printf("%s,%g,,,,,,,,missing %s: run BenchPaging generate first\n",
        name.c_str(),
        cacheMB + atlasMB,
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
  mapper->SetLevelOfDetailFeedback(feedback);
  mapper->SetPrefetch(prefetch);
  vtkNew<vtkMultiVolume> multi;
  multi->SetMapper(mapper);
  std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
  std::vector<vtkSmartPointer<vtkVolume>> volumes;
  auto property = Property();
  PageReads pipelineReads;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetCallback(&PageReads::Count);
  counter->SetClientData(&pipelineReads);
  for (int i = 0; i < 9; ++i)
  {
    auto reader = vtkSmartPointer<vtkPagePoolReader>::New();
    reader->SetFileName(PoolPath(dir, i).c_str());
    reader->AddObserver(vtkCommand::EndEvent, counter);
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
  // Opening the data, as an application does when it loads a scene: the readers' pipeline
  // update reads the page tables and the coarsest level (the roots the mapper draws first).
  const auto open0 = std::chrono::steady_clock::now();
  mapper->Update();
  const double openMs =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - open0).count();
  const long long openPages = pipelineReads.Pages;
  vtkCamera* cam = ren->GetActiveCamera();
  cam->SetViewAngle(35);
  cam->SetViewUp(0, 0, 1);
  const double centre[3] = { 1.6 * Edge, 1.6 * Edge, 0.5 * Edge };
  // The path: a low pass across the grid, turning, then still at the last pose.
  auto pose = [&](double s)
  {
    const double a = -2.2 + 1.6 * s;
    const double r = (3.6 - 1.2 * s) * Edge;
    cam->SetFocalPoint(centre[0] + 0.4 * Edge * std::cos(3 * s), centre[1], centre[2]);
    cam->SetPosition(
      centre[0] + r * std::cos(a), centre[1] + r * std::sin(a), centre[2] + (1.5 - 0.5 * s) * Edge);
    ren->ResetCameraClippingRange(0, 3.3 * Edge, 0, 3.3 * Edge, 0, Edge);
  };
  const int moving = 48;
  std::vector<double> ms, feedbackMs;
  std::vector<double> uploaded;
  int waits = 0, converged = -1, frames = 0;
  long long lastRoots = 0, lastPipeline = pipelineReads.Pages;
  double lastRead = 0.0;
  const auto start = std::chrono::steady_clock::now();
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
    if (feedback && st.FeedbackPages + st.FeedbackPixels > 0)
      feedbackMs.push_back(st.FeedbackMilliseconds);
    // A frame waited on I/O if the render thread read a page: the mapper itself (a root it
    // could not take from its input) or a reader in a pipeline update.
    waits += st.RootPagesRead > lastRoots || pipelineReads.Pages > lastPipeline ? 1 : 0;
    lastRoots = st.RootPagesRead;
    lastPipeline = pipelineReads.Pages;
    lastRead = st.BytesRead / 1048576.0;
    ++frames;
    if (f >= moving && st.Converged)
      converged = f - moving + 1;
    if (f % 16 == 0)
      std::cerr << "  frame " << f << ": " << ms.back() << " ms, "
                << mapper->GetNumberOfResidentBricks() << " bricks, " << st.PendingPages
                << " pending, " << lastRead << " MB read, RSS " << PeakRssMB() << " MB\n";
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double upTotal = 0.0;
  for (double u : uploaded)
    upTotal += u;
  const auto st = mapper->GetPagingStatistics();
  std::ostringstream fb;
  if (feedback)
    fb << "level-of-detail feedback at 1/4 (64x64 ids), read back and reduced in "
       << Percentile(feedbackMs, 0.5) << " ms median (" << (st.FeedbackOpenCL ? "OpenCL" : "CPU")
       << ")";
  else
    fb << "no feedback (screen-space cut)";
  fb << "; prefetch " << (prefetch ? "on" : "off");
  std::printf("%s,%g,%.0f,%d,%d,%.1f,%.1f,%.2f,%.2f,cache %g MB + atlas %g MB; 9 uint8 volumes of "
              "1024^3 (9.66 GB of voxels) in 32^3 bricks; %s; opened in %.0f ms (%lld root pages "
              "from the readers' pipeline update%s); %d frames (%d moving) in %.0f s; "
              "io_wait_frames counts frames in which the render thread read a page (%d roots read "
              "by the mapper itself); %d failed pages; sample distance 2 voxels; %dx%d\n",
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
    fb.str().c_str(),
    openMs,
    openPages,
    st.RootPagesFromPipeline == 9 ? ", taken as the volumes' roots" : ", NOT all used as roots",
    frames,
    moving,
    seconds,
    st.RootPagesRead,
    st.Failures,
    Size,
    Size);
  return 0;
}

const int SeriesEdge = 256; // voxels per axis of each time step
const int SeriesSteps = 8;

std::string SeriesPath(const std::string& dir, int step)
{
  return dir + "/paging-series-" + std::to_string(step) + ".spp";
}

const char* const SeriesHeader =
  "case,steps,switches,cache_mb,atlas_mb,io_wait_frames,pipeline_read_switches,step_pages_read,"
  "ms_per_switch_median,ms_per_switch_max,ms_per_frame_median,frames_per_step,mb_read_per_step,"
  "prefetched_fraction,note";

/// What one playback measured.
struct Playback
{
  std::vector<double> SwitchMs, FrameMs, Prefetched;
  int PipelineSwitches = 0; ///< switches whose pipeline update read a page (the new root)
  int Frames = 0;
};

/// Shows the step of `time` for `frames` frames, as an animation holding each step for a few
/// frames does; the switch frame is timed apart.
void ShowStep(vtkRenderWindow* win,
  vtkMultiVolumeRayCastMapper* mapper,
  const PageReads& reads,
  double time,
  int frames,
  Playback& play)
{
  using Clock = std::chrono::steady_clock;
  const long long pipelineBefore = reads.Pages;
  mapper->GetInputInformation(0, 0)->Set(
    vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), time);
  for (int f = 0; f < frames; ++f)
  {
    const auto t0 = Clock::now();
    win->Render();
    win->WaitForCompletion();
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    (f == 0 ? play.SwitchMs : play.FrameMs).push_back(ms);
    ++play.Frames;
  }
  const auto st = mapper->GetPagingStatistics();
  play.Prefetched.push_back(
    st.NextStepPagesWanted ? double(st.NextStepPagesResident) / st.NextStepPagesWanted : 0.0);
  play.PipelineSwitches += reads.Pages > pipelineBefore ? 1 : 0;
}

// A 4-D playback: eight time steps of a 256^3 volume (one pool each, vtkPagePoolReader::
// AddTimeStep), converged on step 0, then played twice through (16 step switches), each step
// shown for 3 frames, with or without the next step prefetched. No waits: what the loaders
// read while the render thread draws is what the switch finds.
int Series(const std::string& dir, double cacheMB, double atlasMB, bool prefetch)
{
  const std::string name = prefetch ? "series-8x256" : "series-8x256-no-prefetch";
  for (int k = 0; k < SeriesSteps; ++k)
    if (!FileExists(SeriesPath(dir, k)) && !Generate(SeriesPath(dir, k), SeriesEdge, k))
    {
      std::printf("%s,,,,,,,,,,,,,,cannot write %s\n", name.c_str(), SeriesPath(dir, k).c_str());
      return 1;
    }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  strata_test::MakeWindow(win, ren, Size, Size);
  vtkNew<vtkPagePoolReader> reader;
  for (int k = 0; k < SeriesSteps; ++k)
    reader->AddTimeStep(SeriesPath(dir, k).c_str(), k);
  PageReads reads;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetCallback(&PageReads::Count);
  counter->SetClientData(&reads);
  reader->AddObserver(vtkCommand::EndEvent, counter);
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  mapper->SetSampleDistance(2.0);
  mapper->SetAtlasBudget(atlasMB);
  mapper->SetPageCacheBudget(cacheMB);
  mapper->SetPagesPerFrame(64);
  mapper->SetPrefetchTimeSteps(prefetch);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(Property());
  ren->AddVolume(volume);
  vtkCamera* cam = ren->GetActiveCamera();
  const double c = 0.5 * (SeriesEdge - 1);
  cam->SetFocalPoint(c, c, c);
  cam->SetPosition(c + 1.6 * SeriesEdge, c - 1.9 * SeriesEdge, c + 1.2 * SeriesEdge);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(30);
  ren->ResetCameraClippingRange(0, SeriesEdge, 0, SeriesEdge, 0, SeriesEdge);
  // Step 0 settled first (the loaders waited on: set-up, not measured).
  mapper->GetInputInformation(0, 0)->Set(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), 0.0);
  int settle = 0;
  for (; settle < 200 && !mapper->GetPagingStatistics().Converged; ++settle)
  {
    win->Render();
    mapper->WaitForPages(60.0);
  }
  const auto before = mapper->GetPagingStatistics();
  Playback play;
  const int switches = 2 * SeriesSteps;
  for (int s = 1; s <= switches; ++s)
    ShowStep(win, mapper, reads, s % SeriesSteps, 3, play);
  const auto after = mapper->GetPagingStatistics();
  const double mbPerStep = (after.BytesRead - before.BytesRead) / 1048576.0 / switches;
  std::printf(
    "%s,%d,%d,%g,%g,%d,%d,%d,%.1f,%.1f,%.1f,%.1f,%.2f,%.3f,%d uint8 steps of %d^3 in "
    "32^3 bricks (one pool each); settled on step 0 in %d frames (%d bricks resident); "
    "played twice through, 3 frames a step; io_wait_frames: frames in "
    "which the mapper read a page on the render thread (StepPagesRead: a new step's "
    "held brick not prefetched in time; roots); pipeline_read_switches: switches whose "
    "reader update read the new step's coarsest page (the pipeline's own stand-in); "
    "prefetched_fraction: the least share of the next step's pages in RAM when a step ended; "
    "sample distance 2 voxels; %dx%d\n",
    name.c_str(),
    SeriesSteps,
    switches,
    cacheMB,
    atlasMB,
    after.IoWaitFrames - before.IoWaitFrames,
    play.PipelineSwitches,
    after.StepPagesRead - before.StepPagesRead,
    Percentile(play.SwitchMs, 0.5),
    Percentile(play.SwitchMs, 1.0),
    play.FrameMs.empty() ? 0.0 : Percentile(play.FrameMs, 0.5),
    double(play.Frames) / switches,
    mbPerStep,
    Percentile(play.Prefetched, 0.0),
    SeriesSteps,
    SeriesEdge,
    settle,
    mapper->GetNumberOfResidentBricks(),
    Size,
    Size);
  return 0;
}

const char* const AccuracyHeader =
  "case,atlas_mb,rms_error,max_error,ms_per_frame,frames_to_converge,mb_uploaded_per_frame,note";

// One accuracy row: the accuracy volume paged under `atlasMB`, rendered until converged, then
// timed and compared with `reference`. feedbackScale 0: no feedback (the screen-space cut).
void AccuracyRow(vtkRenderWindow* win,
  vtkVolume* volume,
  const std::string& path,
  double atlasMB,
  int feedbackScale,
  const std::vector<double>& reference)
{
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(path.c_str());
  vtkNew<vtkMultiVolumeRayCastMapper> paged;
  paged->SetInputConnection(reader->GetOutputPort());
  paged->SetSampleDistance(1.0);
  paged->SetAtlasBudget(atlasMB);
  paged->SetPageCacheBudget(256);
  paged->SetPagesPerFrame(256);
  paged->SetLevelOfDetailFeedback(feedbackScale > 0);
  paged->SetFeedbackScale(std::max(feedbackScale, 1));
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
    ms.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  const auto err = strata_test::ImageError(strata_test::ReadRGB(win), reference);
  const auto st = paged->GetPagingStatistics();
  const auto levels = paged->GetResidentBricksPerLevel(0);
  std::ostringstream note;
  note << paged->GetNumberOfResidentBricks() << " bricks resident (per level";
  for (int c : levels)
    note << " " << c;
  note << "); converged after " << frames << " frames; " << up << " MB uploaded in all; ";
  if (feedbackScale > 0)
    note << "feedback buffer 1/" << feedbackScale << " of the viewport ("
         << (Size + feedbackScale - 1) / feedbackScale << "^2 ids), its read-back and reduction "
         << st.FeedbackMilliseconds << " ms (" << (st.FeedbackOpenCL ? "OpenCL" : "CPU")
         << ") in the last frame";
  else
    note << "no feedback: screen-space cut";
  note << "; reference: in-core, every brick (" << Size << "x" << Size
       << "; sample distance 1 voxel)";
  const std::string name = feedbackScale > 0
                             ? "accuracy-512-feedback-1/" + std::to_string(feedbackScale)
                             : std::string("accuracy-512-no-feedback");
  std::printf("%s,%g,%.4f,%.1f,%.1f,%d,%.2f,%s\n",
    name.c_str(),
    atlasMB,
    err.Rms,
    err.Max,
    Percentile(ms, 0.5),
    frames,
    up / frames,
    note.str().c_str());
  std::fflush(stdout);
}

int Accuracy(const std::string& dir)
{
  const std::string path = PoolPath(dir, 9);
  if (!FileExists(path))
  {
    std::printf("accuracy-512,,,,,,,missing %s: run BenchPaging generate first\n", path.c_str());
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
  // Atlas budgets without feedback and with feedback buffers of 1/2, 1/4 and 1/8.
  for (int scale : { 0, 2, 4, 8 })
    for (double atlasMB : { 16.0, 32.0, 64.0, 128.0 })
      AccuracyRow(win, volume, path, atlasMB, scale, ref);
  return 0;
}

// --- Report -----------------------------------------------------------------------------------

std::vector<std::map<std::string, std::string>> ReadCsv(const std::string& path)
{
  std::vector<std::map<std::string, std::string>> rows;
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> keys;
  while (std::getline(in, line))
  {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ','))
      cells.push_back(cell);
    if (keys.empty())
    {
      keys = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < keys.size() && i < cells.size(); ++i)
      row[keys[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

// RMS error against atlas budget, one line per case of the accuracy CSV (the volume with and
// without feedback at each buffer scale, and whatever other cases the CSV holds).
int Report(const std::string& csv, const std::string& png)
{
  const auto rows = ReadCsv(csv);
  std::vector<std::string> cases;
  for (const auto& r : rows)
  {
    const auto c = r.find("case");
    if (c != r.end() && r.count("atlas_mb") && !r.at("atlas_mb").empty() &&
        std::find(cases.begin(), cases.end(), c->second) == cases.end())
      cases.push_back(c->second);
  }
  strata_bench::Chart chart(
    "Paging on llvmpipe: converged RMS error against the in-core rendering vs atlas budget "
    "(legend: ms per frame; RMS 0 drawn at 0.001)",
    15,
    "atlas budget, MB (log)",
    true,
    "RMS error, 8-bit units (log)",
    true,
    true);
  // Okabe-Ito: eight colours told apart also with colour-blind eyes.
  const unsigned char colours[8][3] = { { 0, 0, 0 },
    { 230, 159, 0 },
    { 86, 180, 233 },
    { 0, 158, 115 },
    { 240, 228, 66 },
    { 0, 114, 178 },
    { 213, 94, 0 },
    { 204, 121, 167 } };
  std::printf("%-34s %8s %10s %10s %12s\n", "case", "atlas MB", "RMS", "ms/frame", "MB up/frame");
  for (size_t c = 0; c < cases.size(); ++c)
  {
    std::vector<std::pair<double, double>> pts;
    double msLo = 1e300, msHi = 0.0;
    for (const auto& r : rows)
    {
      if (r.at("case") != cases[c] || !r.count("rms_error") || r.at("rms_error").empty())
        continue;
      pts.emplace_back(
        std::atof(r.at("atlas_mb").c_str()), std::max(std::atof(r.at("rms_error").c_str()), 1e-3));
      const double ms = r.count("ms_per_frame") ? std::atof(r.at("ms_per_frame").c_str()) : 0.0;
      msLo = std::min(msLo, ms);
      msHi = std::max(msHi, ms);
      std::printf("%-34s %8s %10s %10s %12s\n",
        cases[c].c_str(),
        r.at("atlas_mb").c_str(),
        r.at("rms_error").c_str(),
        r.count("ms_per_frame") ? r.at("ms_per_frame").c_str() : "",
        r.count("mb_uploaded_per_frame") ? r.at("mb_uploaded_per_frame").c_str() : "");
    }
    if (pts.empty())
      continue;
    std::sort(pts.begin(), pts.end());
    std::ostringstream label;
    label << cases[c] << " (" << std::lround(msLo) << "-" << std::lround(msHi) << " ms)";
    vtkPlot* plot = chart.Add(vtkChart::LINE, label.str(), pts, colours[c % 8]);
    plot->SetWidth(2.0);
    if (cases[c].find("horizon") != std::string::npos)
      plot->GetPen()->SetLineType(vtkPen::DASH_LINE);
    if (auto* line = vtkPlotLine::SafeDownCast(plot))
      line->SetMarkerStyle(cases[c].find("horizon") != std::string::npos ? vtkPlotPoints::CIRCLE
                                                                         : vtkPlotPoints::SQUARE);
  }
  chart.Write(png);
  return 0;
}
}
// A feedback buffer like a ray caster writes: blocks of pixels needing the same brick of a
// screen-space-error cut over nine volumes, 10 % empty (background).
int Feedback()
{
  std::printf("case,scale,pixels,entries,cpu_ms,opencl_ms,identical,device\n");
  strata::FeedbackReduction reduction;
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
        ids[size_t(y) * w + x] =
          empty ? 0u
                : strata::FeedbackReduction::PackPage((bx / 16 + 3 * (by / 16)) % 9,
                    level,
                    static_cast<uint32_t>((bx * 131 + by * 71) % 32768));
      }
    std::vector<strata::FeedbackReduction::Entry> cpu, gpu;
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
    std::printf("feedback,1/%d,%d,%zu,%.3f,%s,%s,%s\n",
      scale,
      w * h,
      cpu.size(),
      Percentile(cpuMs, 0.5),
      clMs.empty() ? "" : std::to_string(Percentile(clMs, 0.5)).c_str(),
      cl ? (same ? "yes" : "no") : "",
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
    for (int k = 0; k < SeriesSteps; ++k)
      ok = Generate(SeriesPath(argv[2], k), SeriesEdge, k) && ok;
    return ok ? 0 : 1;
  }
  if (mode == "header")
  {
    std::printf("case,budget_mb,peak_rss_mb,io_wait_frames,frames_to_converge,ms_per_frame_median,"
                "ms_per_frame_p99,mb_read_per_frame,mb_uploaded_per_frame,note\n");
    return 0;
  }
  if (mode == "flythrough" && argc > 4)
  {
    bool feedback = true, prefetch = false;
    for (int a = 5; a < argc; ++a)
    {
      feedback = feedback && std::string(argv[a]) != "no-feedback";
      prefetch = prefetch || std::string(argv[a]) == "prefetch";
    }
    return FlyThrough(argv[2], std::atof(argv[3]), std::atof(argv[4]), feedback, prefetch);
  }
  if (mode == "feedback")
    return Feedback();
  if (mode == "series-header")
  {
    std::printf("%s\n", SeriesHeader);
    return 0;
  }
  if (mode == "series" && argc > 4)
    return Series(argv[2],
      std::atof(argv[3]),
      std::atof(argv[4]),
      argc <= 5 || std::string(argv[5]) != "no-prefetch");
  if (mode == "accuracy-header")
  {
    std::printf("%s\n", AccuracyHeader);
    return 0;
  }
  if (mode == "accuracy" && argc > 2)
    return Accuracy(argv[2]);
  if (mode == "report" && argc > 3)
    return Report(argv[2], argv[3]);
  std::cerr << "usage: BenchPaging generate <dir> | header | flythrough <dir> <cache MB> <atlas "
               "MB> [no-feedback] [prefetch] | "
               "feedback | accuracy-header | accuracy <dir> | report <csv> <png> | series-header | "
               "series <dir> <cache MB> <atlas MB> [no-prefetch]\n";
  return 2;
}
