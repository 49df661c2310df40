// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// A paged time series: four pools of the blob volume with different blobs (seeds 3-6) at
// times 0, 0.5, 2 and 3.5 given to one vtkPagePoolReader (AddTimeStep).
// - The reader reports TIME_STEPS and TIME_RANGE exactly, and UPDATE_TIME_STEP t reads the step
//   at or below t (before the first: the first; after the last: the last), its values exactly.
// - The multi-volume mapper follows UPDATE_TIME_STEP: each step's converged paged image equals
//   the in-core rendering of the same step through a time-aware pipeline (the reader behind an
//   identity vtkImageShiftScale, re-executed per step, which the in-core mapper must upload
//   again), and differs clearly from the step before (so a mapper stuck on a step fails).
// - Prefetch: once the loaders are idle (WaitForPages, no sleeps), the next step's pages of
//   every brick held are in RAM; the switch to it reads 0 pages on the render thread, counts 0
//   I/O-wait frames and draws the converged image of that step at once. Each mapper starts
//   with its own empty cache, so every step switched to is new to it: forward 1 -> 2 -> 3 -> 0
//   (wrapping around), and backward 3 -> 2 -> 1 -> 0, where the first change was not foreseen
//   and reads all 135 held pages itself in one I/O-wait frame (exact counts: the counter can
//   fail) and after it the steps below are prefetched.
// - Hidden bricks: with values below 30 transparent, bricks the cut keeps as empty leaves (no
//   page) show data in the next step: the prefetch and the switch load them too (0 pages read
//   on the render thread, no "entered the cut without its page" error: measured before the
//   fix), and every step converges to its in-core image.
// - Components: a series of two independent components (each step a set of two component
//   pools) switches forward like one component: both components' held pages prefetched, 0
//   pages read on the render thread, 0 I/O-wait frames, each first frame the step's image.
// - Bad series: a step of other dimensions, a missing step, and times not increasing give a
//   VTK error naming the step, and no crash (reader and mapper).
//
// Bounds. Every brick fits the atlas and the cache, so the converged paged cut is the whole
// cut the in-core mapper draws: the same floats, by another program (paged vs in core; the
// two-component series also against plain textures in core), measured RMS 0-0.0045 and max
// 1/255 (one channel of one pixel, steps 1 and 3; max 1 on an H200 too); the bound, max 1/255
// (ImagePolicy::TwoProgramsMax, StrataImagePolicy.h rule 2) and RMS 0.05, leaves room for that
// rounding only. Neighbouring steps were measured RMS 20.6-25.8 apart; the
// bound 3 fails a mapper stuck on a step or an in-core input not uploaded again.
#include "StrataErrorCounter.h"
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "StrataPagePoolFormat.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkImageShiftScale.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkInformation.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

using namespace strata_test;

namespace
{
using SDDP = vtkStreamingDemandDrivenPipeline;
const int Size = 128;
const int Page = 16;
const int Steps = 4;
const double Times[Steps] = { 0.0, 0.5, 2.0, 3.5 };
/// The pages a converged cut holds: its bricks and their ancestors, 135 of the tree's 143 nodes
/// (6 x 5 x 4, 3 x 3 x 2, 2 x 2 x 1 and 1 bricks), measured; the same for every step.
const int HeldPages = 135;
const double BrickMB = double(Page) * Page * Page * 4 / (1024.0 * 1024.0);

/// Every value visible (opacity 0.02 at 0): no brick is empty in any step, so every step's
/// cut is the same and a switch needs exactly the pages the last step held.
vtkSmartPointer<vtkVolumeProperty> MakeProperty()
{
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.02);
  opacity->AddPoint(100.0, 0.4);
  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(0.0, 0.1, 0.2, 0.9);
  colour->AddRGBPoint(50.0, 0.9, 0.9, 0.2);
  colour->AddRGBPoint(100.0, 0.9, 0.1, 0.1);
  property->SetScalarOpacity(opacity);
  property->SetColor(colour);
  property->SetInterpolationTypeToLinear();
  return property;
}

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  vtkNew<vtkVolume> Volume;
  explicit Scene(vtkVolumeProperty* property)
  {
    MakeWindow(this->Win, this->Ren, Size, Size);
    this->Volume->SetProperty(property);
    this->Ren->AddVolume(this->Volume);
    vtkCamera* cam = this->Ren->GetActiveCamera();
    cam->SetFocalPoint(40, 35, 30);
    cam->SetPosition(40 + 120 * std::cos(0.6), 35 + 120 * std::sin(0.6), 90);
    cam->SetViewUp(0, 0, 1);
    cam->SetViewAngle(30);
    this->Ren->ResetCameraClippingRange(0, 80, 0, 70, 0, 60);
  }
  std::vector<unsigned char> Render(vtkMultiVolumeRayCastMapper* mapper)
  {
    this->Volume->SetMapper(mapper);
    this->Win->Render();
    return ReadRGB(this->Win);
  }
};

void Configure(vtkMultiVolumeRayCastMapper* m)
{
  m->SetSampleDistance(0.5);
  m->SetBrickSize(Page);
  m->SetAtlasBudget(160 * BrickMB); // all 143 bricks
  m->SetPageCacheBudget(64);        // two cuts and more
}

struct Fixture
{
  explicit Fixture(const std::string& dir)
    : Dir(dir)
    , Property(MakeProperty())
  {
    const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
    for (int k = 0; k < Steps; ++k)
    {
      this->Images.push_back(MakeBlobVolume(81, 71, 61, spacing, origin, 3 + k));
      this->Pools.push_back(dir + "/series-" + std::to_string(k) + ".spp");
      Check(
        Write(this->Images.back(), this->Pools.back()), "step " + std::to_string(k) + " written");
    }
  }
  ~Fixture()
  {
    for (const std::string& pool : this->Pools)
      std::remove(pool.c_str());
  }
  static bool Write(vtkImageData* image, const std::string& pool)
  {
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(pool.c_str());
    writer->SetPageSize(Page);
    return writer->Write();
  }
  vtkSmartPointer<vtkPagePoolReader> MakeReader() const
  {
    auto reader = vtkSmartPointer<vtkPagePoolReader>::New();
    for (int k = 0; k < Steps; ++k)
      reader->AddTimeStep(this->Pools[k].c_str(), Times[k]);
    return reader;
  }
  std::string Dir;
  std::vector<vtkSmartPointer<vtkImageData>> Images;
  std::vector<std::string> Pools;
  vtkSmartPointer<vtkVolumeProperty> Property;
};

/// Sets the time the mapper's input on port 0 asks for, as a VTK pipeline (ParaView's
/// animation, a reader's UpdateTimeStep) does.
void SetTime(vtkMultiVolumeRayCastMapper* m, double t)
{
  m->GetInputInformation(0, 0)->Set(SDDP::UPDATE_TIME_STEP(), t);
}

/// Renders until converged, the loaders waited on between frames; returns the last image.
std::vector<unsigned char> Converge(Scene& s, vtkMultiVolumeRayCastMapper* m, int& frames)
{
  std::vector<unsigned char> image;
  for (frames = 1; frames <= 60; ++frames)
  {
    image = s.Render(m);
    if (m->GetPagingStatistics().Converged)
      return image;
    m->WaitForPages(30.0);
  }
  frames = -1;
  return image;
}

void ReaderSteps(Fixture& fx)
{
  vtkSmartPointer<vtkPagePoolReader> reader = fx.MakeReader();
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  const int n = info->Length(SDDP::TIME_STEPS());
  bool exact = n == Steps;
  for (int k = 0; exact && k < n; ++k)
    exact = info->Get(SDDP::TIME_STEPS())[k] == Times[k];
  const double* range = info->Has(SDDP::TIME_RANGE()) ? info->Get(SDDP::TIME_RANGE()) : nullptr;
  Check(exact, "TIME_STEPS are the 4 times given, exactly");
  Check(range && range[0] == 0.0 && range[1] == 3.5, "TIME_RANGE is [0, 3.5]");
  // The step at or below t; before the first the first, after the last the last.
  const std::vector<std::pair<double, int>> cases = { { -1.0, 0 },
    { 0.0, 0 },
    { 0.25, 0 },
    { 0.5, 1 },
    { 1.99, 1 },
    { 2.0, 2 },
    { 3.49, 2 },
    { 3.5, 3 },
    { 100.0, 3 } };
  for (const auto& [t, step] : cases)
  {
    reader->UpdateTimeStep(t);
    vtkImageData* out = reader->GetOutput();
    const std::string at = "t = " + std::to_string(t);
    Check(reader->GetTimeStepRead() == step, at + " reads step " + std::to_string(step));
    Check(out->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()) == Times[step],
      at + ": DATA_TIME_STEP is the step's time");
    vtkDataArray* got = out->GetPointData()->GetScalars();
    vtkDataArray* want = fx.Images[step]->GetPointData()->GetScalars();
    double worst = got && got->GetNumberOfTuples() == want->GetNumberOfTuples() ? 0.0 : 1e30;
    for (vtkIdType i = 0; worst == 0.0 && i < want->GetNumberOfTuples(); ++i)
      worst = std::max(worst, std::abs(got->GetTuple1(i) - want->GetTuple1(i)));
    Check(worst == 0.0, at + ": the output holds that step's values exactly");
  }
  std::cout << "Reader: " << n << " time steps, " << cases.size() << " times chosen\n";
}

void ImagesPerStep(Fixture& fx)
{
  Scene s(fx.Property);
  vtkSmartPointer<vtkPagePoolReader> pagedReader = fx.MakeReader();
  vtkNew<vtkMultiVolumeRayCastMapper> paged;
  paged->SetInputConnection(pagedReader->GetOutputPort());
  Configure(paged);
  // In core, through the pipeline: the identity filter is no pool's reader, so the mapper
  // takes its (full-resolution) output as data and must upload it again for every step.
  vtkSmartPointer<vtkPagePoolReader> incoreReader = fx.MakeReader();
  vtkNew<vtkImageShiftScale> identity;
  identity->SetInputConnection(incoreReader->GetOutputPort());
  identity->SetOutputScalarTypeToFloat();
  vtkNew<vtkMultiVolumeRayCastMapper> incore;
  incore->SetInputConnection(identity->GetOutputPort());
  Configure(incore);
  std::vector<unsigned char> last;
  for (int k = 0; k < Steps; ++k)
  {
    const std::string step = "step " + std::to_string(k);
    SetTime(paged, Times[k] + 0.1); // between steps: the step below
    SetTime(incore, Times[k]);
    int frames = 0;
    const auto image = Converge(s, paged, frames);
    const auto reference = s.Render(incore);
    const ChannelError e = ImageError(image, reference);
    const double apart = last.empty() ? 0.0 : ImageError(reference, last).Rms;
    std::cout << "Series " << step << ": converged after " << frames << " frames, paged vs in "
              << "core RMS " << e.Rms << ", max " << e.Max << "; RMS " << apart
              << " from the step before; in-core reader read step "
              << incoreReader->GetTimeStepRead() << "\n";
    Check(frames > 0, step + ": the paged view converges");
    Check(pagedReader->GetTimeStepRead() == k && incoreReader->GetTimeStepRead() == k,
      step + ": both pipelines read the step of their time");
    Check(e.Max <= ImagePolicy::TwoProgramsMax && e.Rms <= 0.05,
      step + ": paged equals in core (max 1/255, RMS 0.05)");
    if (k > 0)
      Check(apart > 3.0, step + ": differs from the step before (RMS > 3)");
    last = reference;
  }
}

/// What one step switch did: pages of the next step resident before it, pages read on the
/// render thread and I/O-wait frames by it, and its first image against the step's in-core one.
struct Switch
{
  int Resident = 0, Wanted = 0, Read = 0, Waits = 0, Switches = 0;
  ChannelError Error;
};

/// Lets the loaders finish (no sleeps), then switches `paged` to step `next` and renders once.
Switch SwitchTo(Scene& s,
  vtkMultiVolumeRayCastMapper* paged,
  int next,
  const std::vector<unsigned char>& reference)
{
  paged->WaitForPages(30.0);
  s.Render(paged); // the prefetch's pages are counted resident by a frame
  const auto before = paged->GetPagingStatistics();
  SetTime(paged, Times[next]);
  const auto image = s.Render(paged);
  const auto after = paged->GetPagingStatistics();
  Switch w;
  w.Resident = before.NextStepPagesResident;
  w.Wanted = before.NextStepPagesWanted;
  w.Read = after.StepPagesRead - before.StepPagesRead;
  w.Waits = after.IoWaitFrames - before.IoWaitFrames;
  w.Switches = after.StepSwitches - before.StepSwitches;
  w.Error = ImageError(image, reference);
  std::cout << "  switch to step " << next << ": " << w.Resident << " of " << w.Wanted
            << " next-step pages resident before; " << w.Read << " pages read on the render "
            << "thread, " << w.Waits << " I/O-wait frames; first frame vs in core RMS "
            << w.Error.Rms << ", max " << w.Error.Max << "\n";
  return w;
}

/// A fresh paged mapper (its own cache: no step loaded yet) settled on step `first`.
struct Player
{
  Player(Fixture& fx, Scene& s, int first)
    : Reader(fx.MakeReader())
  {
    this->Mapper->SetInputConnection(this->Reader->GetOutputPort());
    Configure(this->Mapper);
    // VTK drops an UPDATE_TIME_STEP set before the output exists (ResetPipelineInformation
    // when the first data object is made): the information pass makes it first.
    this->Reader->UpdateInformation();
    SetTime(this->Mapper, Times[first]);
    int frames = 0;
    Converge(s, this->Mapper, frames);
    Check(frames > 0 && this->Reader->GetTimeStepRead() == first,
      "step " + std::to_string(first) + " shown and converged");
  }
  vtkSmartPointer<vtkPagePoolReader> Reader;
  vtkNew<vtkMultiVolumeRayCastMapper> Mapper;
};

void Prefetch(Fixture& fx)
{
  Scene s(fx.Property);
  // The converged in-core images of every step, for the switch frames.
  std::vector<std::vector<unsigned char>> reference;
  for (int k = 0; k < Steps; ++k)
  {
    vtkNew<vtkMultiVolumeRayCastMapper> incore;
    incore->SetInputData(fx.Images[k]);
    Configure(incore);
    reference.push_back(s.Render(incore));
  }
  // Forward from step 1: 2, 3, then 0 (wrapping around). Each step is new to this mapper's
  // cache, so only the prefetch can have put its pages there.
  std::cout << "Prefetch, forward from step 1:\n";
  Player forward(fx, s, 1);
  for (int next : { 2, 3, 0 })
  {
    const Switch w = SwitchTo(s, forward.Mapper, next, reference[next]);
    const std::string at = "forward, switch to step " + std::to_string(next);
    Check(w.Wanted == HeldPages && w.Resident == HeldPages,
      at + ": all " + std::to_string(HeldPages) + " held pages of the next step prefetched");
    Check(w.Read == 0, at + ": 0 pages read synchronously");
    Check(w.Waits == 0, at + ": 0 I/O-wait frames");
    Check(w.Switches == 1, at + ": the cut was kept");
    Check(w.Error.Max <= ImagePolicy::TwoProgramsMax && w.Error.Rms <= 0.05,
      at + ": its first frame is the step's image");
  }
  // Backward from step 3: the first change (to 2) was not foreseen (forward from 3 is 0), so
  // every held page is read on the render thread in one I/O-wait frame; after it playback
  // runs backward and 1 and 0, new to this cache, are prefetched.
  std::cout << "Prefetch, backward from step 3:\n";
  Player backward(fx, s, 3);
  const Switch jump = SwitchTo(s, backward.Mapper, 2, reference[2]);
  Check(jump.Read == HeldPages && jump.Waits == 1,
    "backward, switch to step 2 (not prefetched): all " + std::to_string(HeldPages) +
      " held pages read here, in one I/O-wait frame");
  Check(jump.Error.Max <= ImagePolicy::TwoProgramsMax,
    "backward, switch to step 2: its first frame is the step's image");
  for (int next : { 1, 0 })
  {
    const Switch w = SwitchTo(s, backward.Mapper, next, reference[next]);
    const std::string at = "backward, switch to step " + std::to_string(next);
    Check(w.Read == 0 && w.Waits == 0 && w.Resident == HeldPages,
      at + ": prefetched (0 pages read synchronously, 0 I/O-wait frames)");
    Check(w.Error.Max <= ImagePolicy::TwoProgramsMax && w.Error.Rms <= 0.05,
      at + ": its first frame is the step's image");
  }
}

/// Values below 30 transparent: blobs of other steps cover bricks the cut keeps as empty
/// leaves without a page, which a switch must load (the new step's ranges show them).
void HiddenBricks(Fixture& fx)
{
  auto property = MakeProperty();
  property->GetScalarOpacity()->RemoveAllPoints();
  property->GetScalarOpacity()->AddPoint(0.0, 0.0);
  property->GetScalarOpacity()->AddPoint(30.0, 0.0);
  property->GetScalarOpacity()->AddPoint(100.0, 0.4);
  Scene s(property);
  vtkSmartPointer<vtkPagePoolReader> reader = fx.MakeReader();
  vtkNew<vtkMultiVolumeRayCastMapper> paged;
  paged->SetInputConnection(reader->GetOutputPort());
  Configure(paged);
  SetTime(paged, Times[0]);
  int frames = 0;
  Converge(s, paged, frames);
  for (int next = 1; next < Steps; ++next)
  {
    paged->WaitForPages(30.0);
    s.Render(paged);
    const auto before = paged->GetPagingStatistics();
    SetTime(paged, Times[next]);
    const auto first = s.Render(paged);
    const auto after = paged->GetPagingStatistics();
    const auto image = Converge(s, paged, frames);
    vtkNew<vtkMultiVolumeRayCastMapper> incore;
    incore->SetInputData(fx.Images[next]);
    Configure(incore);
    const auto reference = s.Render(incore);
    const ChannelError e = ImageError(image, reference);
    const std::string at = "hidden bricks, switch to step " + std::to_string(next);
    std::cout << "Hidden bricks, switch to step " << next << ": " << before.NextStepPagesResident
              << " of " << before.NextStepPagesWanted << " next-step pages resident, "
              << after.StepPagesRead - before.StepPagesRead << " read on the render thread; "
              << "first frame RMS " << ImageError(first, reference).Rms << ", converged after "
              << frames << " more frames: RMS " << e.Rms << ", max " << e.Max << "\n";
    Check(
      before.NextStepPagesWanted > 0 && before.NextStepPagesResident == before.NextStepPagesWanted,
      at + ": every page of the next step prefetched");
    Check(after.StepPagesRead == before.StepPagesRead, at + ": 0 pages read synchronously");
    Check(frames > 0 && e.Max <= ImagePolicy::TwoProgramsMax && e.Rms <= 0.05,
      at + ": converges to the in-core image");
  }
}

/// One bad series: the reader's information fails with an error naming `expect` (the first
/// error of the update), and a mapper on it renders without crashing. Returns that error.
std::string BadSeries(const std::string& what,
  vtkPagePoolReader* reader,
  const std::string& expect,
  vtkVolumeProperty* property)
{
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->UpdateInformation();
  const std::string first = errors->First;
  std::cout << "Bad series (" << what << "): " << errors->Errors << " error(s): \"" << first
            << "\"\n";
  Check(errors->Errors >= 1 && first.find(expect) != std::string::npos,
    what + ": a VTK error saying \"" + expect + "\"");
  Scene s(property);
  vtkNew<vtkMultiVolumeRayCastMapper> m;
  m->SetInputConnection(reader->GetOutputPort());
  Configure(m);
  errors->Watch(m);
  s.Render(m);
  Check(errors->Errors >= 2, what + ": the render fails with errors and without a crash");
  return first;
}

void BadInput(Fixture& fx)
{
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  const std::string narrow = fx.Dir + "/series-narrow.spp";
  Check(Fixture::Write(MakeBlobVolume(41, 71, 61, spacing, origin, 9), narrow), "narrow written");
  {
    vtkNew<vtkPagePoolReader> r;
    r->AddTimeStep(fx.Pools[0].c_str(), 0.0);
    r->AddTimeStep(narrow.c_str(), 1.0);
    const std::string error = BadSeries("other dimensions", r, "time step 1", fx.Property);
    Check(error.find("41 x 71 x 61") != std::string::npos, "the error gives the step's dimensions");
  }
  {
    vtkNew<vtkPagePoolReader> r;
    r->AddTimeStep(fx.Pools[0].c_str(), 0.0);
    r->AddTimeStep(fx.Pools[1].c_str(), 1.0);
    r->AddTimeStep((fx.Dir + "/series-missing.spp").c_str(), 2.0);
    BadSeries(
      "missing file", r, "time step 2 (\"" + fx.Dir + "/series-missing.spp\")", fx.Property);
  }
  {
    vtkNew<vtkPagePoolReader> r;
    r->AddTimeStep(fx.Pools[0].c_str(), 1.0);
    r->AddTimeStep(fx.Pools[1].c_str(), 1.0);
    BadSeries("times not increasing", r, "times must increase", fx.Property);
  }
  std::remove(narrow.c_str());
}
}

/// A series of two independent components: each step a set of two component pools, each
/// component paged (and prefetched) as its own volume; the switches of Prefetch, forward.
void Components(Fixture& fx)
{
  auto property = MakeProperty();
  property->SetScalarOpacity(1, property->GetScalarOpacity(0));
  property->SetColor(1, property->GetRGBTransferFunction(0));
  property->SetComponentWeight(1, 0.5);
  Scene s(property);
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  std::vector<vtkSmartPointer<vtkImageData>> images;
  std::vector<std::vector<unsigned char>> reference;
  vtkNew<vtkPagePoolReader> reader;
  std::vector<std::string> pools;
  for (int k = 0; k < Steps; ++k)
  {
    auto image = MakeBlobVolume(81, 71, 61, spacing, origin, 3 + k);
    auto other = MakeBlobVolume(81, 71, 61, spacing, origin, 11 + k);
    vtkDataArray* a = image->GetPointData()->GetScalars();
    vtkDataArray* b = other->GetPointData()->GetScalars();
    vtkSmartPointer<vtkDataArray> both;
    both.TakeReference(a->NewInstance());
    both->SetNumberOfComponents(2);
    both->SetNumberOfTuples(a->GetNumberOfTuples());
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      both->SetComponent(i, 0, a->GetComponent(i, 0));
      both->SetComponent(i, 1, b->GetComponent(i, 0));
    }
    image->GetPointData()->SetScalars(both);
    images.push_back(image);
    pools.push_back(fx.Dir + "/components-" + std::to_string(k) + ".spp");
    Check(
      Fixture::Write(image, pools.back()), "two-component step " + std::to_string(k) + " written");
    reader->AddTimeStep(pools.back().c_str(), Times[k]);
    vtkNew<vtkMultiVolumeRayCastMapper> incore;
    incore->SetInputData(image);
    Configure(incore);
    reference.push_back(s.Render(incore));
  }
  vtkNew<vtkMultiVolumeRayCastMapper> paged;
  paged->SetInputConnection(reader->GetOutputPort());
  Configure(paged);
  paged->SetAtlasBudget(2 * 160 * BrickMB); // every brick of both components
  reader->UpdateInformation();
  SetTime(paged, Times[1]);
  int frames = 0;
  const auto first = Converge(s, paged, frames);
  const ChannelError e = ImageError(first, reference[1]);
  std::cout << "Components, step 1: converged after " << frames << " frames, against in core RMS "
            << e.Rms << ", max " << e.Max << "\n";
  Check(frames > 0 && e.Max <= ImagePolicy::TwoProgramsMax && e.Rms <= 0.05,
    "two components, step 1: paged converges to the in-core image");
  for (int next : { 2, 3, 0 })
  {
    const Switch w = SwitchTo(s, paged, next, reference[next]);
    const std::string at = "two components, switch to step " + std::to_string(next);
    Check(w.Wanted == 2 * HeldPages && w.Resident == 2 * HeldPages,
      at + ": all " + std::to_string(2 * HeldPages) +
        " held pages of both components' next step prefetched");
    Check(w.Read == 0 && w.Waits == 0, at + ": 0 pages read synchronously, 0 I/O-wait frames");
    Check(w.Error.Max <= ImagePolicy::TwoProgramsMax && w.Error.Rms <= 0.05,
      at + ": its first frame is the step's image");
  }
  for (const std::string& pool : pools)
  {
    std::remove(pool.c_str());
    std::remove(strata::PagePoolFormat::GetComponentFileName(pool, 1).c_str());
  }
}

int TestMultiVolumeTimeSeries(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  Fixture fx(paths.Output);
  RunSubTests(
    {
      { "ReaderSteps", [&] { ReaderSteps(fx); } },
      { "ImagesPerStep", [&] { ImagesPerStep(fx); } },
      { "Prefetch", [&] { Prefetch(fx); } },
      { "HiddenBricks", [&] { HiddenBricks(fx); } },
      { "Components", [&] { Components(fx); } },
      { "BadInput", [&] { BadInput(fx); } },
      { "NoOtherMessages", [&] { CheckNoVtkMessages(output); } },
    },
    Failures);
  std::cout << (Failures() ? "FAILED" : "passed") << "\n";
  return Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}
