// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// A window resized between renders: both mappers, in both stages, must draw at the new size what
// a fresh window of that size draws (the same program twice: bit-exact, StrataImagePolicy.h),
// growing and shrinking. The buffers sized to the viewport (the volume caster's integration
// buffers and scene depth, the horizon caster's staging images, the feedback images) are
// reallocated on a resize, and a pass that kept the old ones drew into textures nobody reads: a
// Strata Volume vanished in ParaView's GUI when its view was resized (issue 29).
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <array>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace strata_test;

// The scene's camera, fixed (not reset from the window), so that two windows of one size see
// exactly the same.
void PlaceCamera(vtkRenderer* ren, const double focal[3], const double position[3])
{
  vtkCamera* c = ren->GetActiveCamera();
  c->SetFocalPoint(focal[0], focal[1], focal[2]);
  c->SetPosition(position[0], position[1], position[2]);
  c->SetViewUp(0.0, 0.0, 1.0);
  c->SetViewAngle(30.0);
  c->SetClippingRange(1.0, 5000.0);
}

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  vtkMultiVolumeRayCastMapper* Paged = nullptr; ///< a paged volume's mapper: render until settled
};

// Renders; a paged scene until its cut has settled (the pages between frames), as a user's view
// refines.
void Render(const Scene& s)
{
  s.Win->Render();
  for (int f = 0; s.Paged && f < 200 && !s.Paged->GetPagingStatistics().Converged; ++f)
  {
    s.Paged->WaitForPages(1.0);
    s.Win->Render();
  }
}

// Renders a scene made by `make` at sizes[0], then resized to each later size in turn, and
// compares every render with a fresh window of that size.
void CheckResizes(const std::string& name,
  const std::function<Scene(int, int)>& make,
  const std::vector<std::array<int, 2>>& sizes)
{
  Scene resized = make(sizes[0][0], sizes[0][1]);
  for (size_t k = 0; k < sizes.size(); ++k)
  {
    const int w = sizes[k][0], h = sizes[k][1];
    resized.Win->SetSize(w, h);
    Render(resized);
    const std::vector<unsigned char> mine = ReadRGB(resized.Win);
    Scene fresh = make(w, h);
    Render(fresh);
    const std::vector<unsigned char> theirs = ReadRGB(fresh.Win);
    long differing = 0, drawn = 0;
    for (size_t p = 0; p + 2 < theirs.size() && mine.size() == theirs.size(); p += 3)
    {
      differing +=
        (mine[p] != theirs[p] || mine[p + 1] != theirs[p + 1] || mine[p + 2] != theirs[p + 2]) ? 1
                                                                                               : 0;
      drawn += (theirs[p] | theirs[p + 1] | theirs[p + 2]) != 0 ? 1 : 0;
    }
    const std::string what = name + " at " + std::to_string(w) + " x " + std::to_string(h) +
                             (k == 0 ? " (first render)" : " (after a resize)");
    std::cout << what << ": " << differing << " pixels differ from a fresh window's, " << drawn
              << " drawn\n";
    Check(mine.size() == theirs.size() && mine.size() == size_t(3) * w * h,
      what + ": the read-back has the window's size");
    Check(drawn > w * h / 20, what + ": the scene is drawn");
    Check(differing == 0, what + ": equal to a fresh render at that size");
  }
}

const std::vector<std::array<int, 2>> Sizes = { { 160, 128 },
  { 224, 176 },
  { 96, 144 },
  { 160, 128 } };

Scene InCoreVolumeScene(int w, int h, vtkMultiVolumeRayCastMapper::Stages stage, int rays)
{
  Scene s;
  MakeWindow(s.Win, s.Ren, w, h);
  const double spacing[3] = { 1.0, 1.0, 1.0 }, origin[3] = { 0.0, 0.0, 0.0 };
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetInputData(MakeBlobVolume(40, 36, 32, spacing, origin, 1));
  mapper->SetStage(stage);
  mapper->SetRaysPerPixel(rays);
  mapper->SetSampleDistance(0.5);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(MakeVolumeProperty(0));
  s.Ren->AddVolume(volume);
  const double focal[3] = { 20.0, 18.0, 16.0 }, position[3] = { -60.0, -90.0, 70.0 };
  PlaceCamera(s.Ren, focal, position);
  return s;
}

// The volume of InCoreVolumeScene paged from a pool of 16^3 pages (written once), with feedback,
// rendered until its cut settles.
Scene PagedVolumeScene(int w,
  int h,
  vtkMultiVolumeRayCastMapper::Stages stage,
  const std::string& directory)
{
  static vtkSmartPointer<vtkPagePoolReader> pool;
  if (!pool)
  {
    const double spacing[3] = { 1.0, 1.0, 1.0 }, origin[3] = { 0.0, 0.0, 0.0 };
    pool = WritePagedTwin(
      MakeBlobVolume(40, 36, 32, spacing, origin, 1), directory + "/window-resize.spp", 16);
  }
  Scene s;
  MakeWindow(s.Win, s.Ren, w, h);
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(pool->GetFileName());
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  mapper->SetStage(stage);
  mapper->SetSampleDistance(0.5);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(MakeVolumeProperty(0));
  s.Ren->AddVolume(volume);
  s.Paged = mapper;
  const double focal[3] = { 20.0, 18.0, 16.0 }, position[3] = { -60.0, -90.0, 70.0 };
  PlaceCamera(s.Ren, focal, position);
  return s;
}

Scene HorizonScene(int w, int h, vtkStackedHeightFieldMapper::Stages stage)
{
  Scene s;
  MakeWindow(s.Win, s.Ren, w, h);
  vtkNew<vtkStackedHeightFieldMapper> mapper;
  for (const auto& horizon : MakeDemoHorizons())
    mapper->AddInputData(horizon);
  mapper->SetStage(stage);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  s.Ren->AddActor(actor);
  s.Ren->SetBackground(0.0, 0.0, 0.0);
  const double focal[3] = { 1000.0, 750.0, -300.0 }, position[3] = { -900.0, -1400.0, 900.0 };
  PlaceCamera(s.Ren, focal, position);
  return s;
}
}

int TestWindowResize(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  using V = vtkMultiVolumeRayCastMapper::Stages;
  using H = vtkStackedHeightFieldMapper::Stages;
  std::vector<SubTest> parts;
  for (const auto stage : { V::Fragment, V::Compute })
  {
    const std::string s = stage == V::Compute ? "compute" : "fragment";
    parts.push_back({ "volume, " + s,
      [stage]
      {
        CheckResizes(
          "volume, " + std::string(stage == V::Compute ? "compute" : "fragment"),
          [stage](int w, int h) { return InCoreVolumeScene(w, h, stage, 1); },
          Sizes);
      } });
    parts.push_back({ "paged volume, " + s,
      [stage, s, &paths]
      {
        CheckResizes(
          "paged volume, " + s,
          [stage, &paths](int w, int h) { return PagedVolumeScene(w, h, stage, paths.Output); },
          Sizes);
      } });
    parts.push_back({ "volume, 2 rays, " + s,
      [stage]
      {
        CheckResizes(
          "volume, 2 rays, " + std::string(stage == V::Compute ? "compute" : "fragment"),
          [stage](int w, int h) { return InCoreVolumeScene(w, h, stage, 2); },
          Sizes);
      } });
  }
  for (const auto stage : { H::Fragment, H::Compute })
  {
    const std::string s = stage == H::Compute ? "compute" : "fragment";
    parts.push_back({ "horizons, " + s,
      [stage, s]
      {
        CheckResizes(
          "horizons, " + s, [stage](int w, int h) { return HorizonScene(w, h, stage); }, Sizes);
      } });
  }
  parts.push_back({ "no VTK errors or warnings", [output] { CheckNoVtkMessages(output); } });
  return RunSubTests(parts, Failures);
}
