// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// GL lifetime of the mappers: every GL name a mapper creates (textures, buffers, vertex arrays,
// framebuffers) is deleted, in the context that made it, whichever of mapper and window goes
// first, and nothing grows over many lifetimes. Checked by counting the live names of each
// kind in the window's context (glIsTexture, glIsBuffer, glIsVertexArray, glIsFramebuffer over
// the name range, StrataGLNames) for every mapper and mode: horizons in core and paged (tile atlas,
// page table, feedback), volumes with the atlas, without it, and paged (feedback), and the hybrid.
// - Mapper first: after an empty frame (VTK's own names) the scene is drawn twice, then its
//   mapper is taken off the prop and dropped while the prop stays in the renderer; the window
//   must hold exactly its names of before. Nothing but the mapper's strata::GraphicsResources can
//   release them then (VTK releases a prop's resources when it leaves a renderer, not when its
//   mapper does), so the test fails when the callback is removed.
// - Window change: drawn in one window, then the mapper is moved to a prop in a second one;
//   the first must be back to its names of before (the callback releases the old window's
//   names, in that window's context, when the mapper registers with another).
// - Window first: the window is destroyed while the mapper lives, then the mapper: no GL
//   error, no crash, nothing reported.
// Memory: the heap in use (StrataMemory.h) after the sixth round within 1 MB of the one after
// the third (measured 3 KB; each round creates and destroys 18 windows and scenes, and llvmpipe
// keeps textures on the heap: a leak of one atlas a round would be 8 MB), and the resident size
// within 24 MB (not asserted under AddressSanitizer, whose quarantine fills: 25 MB measured).
#include "StrataGLNames.h"
#include "StrataHeightFieldScenes.h" // For MakeHorizon
#include "StrataMemory.h"            // For ResidentKiB, HeapInUseKiB, UnderAddressSanitizer
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h" // For MakeBlobVolume, MakeVolumeProperty

#include "vtkAbstractVolumeMapper.h"
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkHybridVolumeMapper.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkLight.h"
#include "vtkMapper.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

using namespace strata_test;

namespace
{
const double HeapGrowthBoundKiB = 1024.0;

// A gently waving horizon of n x n points.
vtkSmartPointer<vtkImageData> Grid(int n, double height, double slope)
{
  std::vector<float> z(size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      z[size_t(j) * n + i] = static_cast<float>(height + slope * std::sin(0.3 * i) * j);
  return MakeHorizon(n, n, 0.0, 0.0, 1.0, 1.0, 0.0, z);
}

vtkSmartPointer<vtkImageData> Blob(int n, double shift)
{
  const double spacing[3] = { 1.0, 1.0, 1.0 }, origin[3] = { shift, 0.0, 0.0 };
  return MakeBlobVolume(n, n, n, spacing, origin, 1);
}

vtkSmartPointer<vtkVolumeProperty> Property(bool shade)
{
  vtkSmartPointer<vtkVolumeProperty> p = MakeVolumeProperty(shade ? 1 : 0);
  p->SetShade(shade);
  return p;
}

std::string WritePool(vtkImageData* image, const std::string& name, int page)
{
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(name.c_str());
  writer->SetPageSize(page);
  Check(writer->Write(), "pool " + name + " written");
  std::cout << "pool " << name << " written\n";
  return name;
}

/// A scene: its prop and mapper, how to put a mapper on a prop of its kind (a new prop when
/// given none; null takes it off), and the readers it pages from.
struct Scene
{
  vtkSmartPointer<vtkProp> Prop;
  vtkSmartPointer<vtkAbstractMapper3D> Mapper;
  std::function<vtkSmartPointer<vtkProp>(vtkAbstractMapper3D*, vtkProp*)> Attach;
  std::vector<vtkSmartPointer<vtkObject>> Keep;
};

using Maker = std::function<Scene()>;

Scene Horizons(const std::vector<std::string>& pools)
{
  Scene s;
  vtkNew<vtkStackedHeightFieldMapper> mapper;
  if (pools.empty())
  {
    mapper->AddInputDataObject(Grid(33, 0.0, 0.5));
    mapper->AddInputDataObject(Grid(33, 4.0, -0.5));
  }
  for (const std::string& pool : pools)
  {
    auto reader = vtkSmartPointer<vtkPagePoolReader>::New();
    reader->SetFileName(pool.c_str());
    mapper->AddInputConnection(reader->GetOutputPort());
    s.Keep.push_back(reader);
  }
  mapper->SetColorMode(vtkStackedHeightFieldMapper::ColorModes::LookupTable);
  s.Attach = [](vtkAbstractMapper3D* m, vtkProp* p)
  {
    vtkSmartPointer<vtkActor> actor = vtkActor::SafeDownCast(p);
    if (!actor)
      actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(vtkMapper::SafeDownCast(m));
    return vtkSmartPointer<vtkProp>(actor);
  };
  s.Mapper = mapper;
  s.Prop = s.Attach(mapper, nullptr);
  return s;
}

Scene Volumes(bool atlas, const std::string& pool)
{
  Scene s;
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetUseBrickAtlas(atlas);
  mapper->SetBrickSize(8);
  mapper->SetSampleDistance(0.5);
  auto multi = vtkSmartPointer<vtkMultiVolume>::New();
  multi->SetMapper(mapper);
  for (int port = 0; port < 2; ++port)
  {
    if (port == 0 && !pool.empty())
    {
      auto reader = vtkSmartPointer<vtkPagePoolReader>::New();
      reader->SetFileName(pool.c_str());
      mapper->SetInputConnection(port, reader->GetOutputPort());
      s.Keep.push_back(reader);
    }
    else
    {
      mapper->SetInputDataObject(port, Blob(20, 8.0 * port));
    }
    vtkNew<vtkVolume> member;
    member->SetProperty(Property(port == 1));
    multi->SetVolume(member, port);
  }
  s.Attach = [](vtkAbstractMapper3D* m, vtkProp* p)
  {
    // Members of the same properties on a new vtkMultiVolume, or the given one's mapper set.
    vtkSmartPointer<vtkMultiVolume> target = vtkMultiVolume::SafeDownCast(p);
    if (!target)
    {
      target = vtkSmartPointer<vtkMultiVolume>::New();
      for (int port = 0; port < 2; ++port)
      {
        vtkNew<vtkVolume> member;
        member->SetProperty(Property(port == 1));
        target->SetVolume(member, port);
      }
    }
    target->SetMapper(vtkAbstractVolumeMapper::SafeDownCast(m));
    return vtkSmartPointer<vtkProp>(target);
  };
  s.Mapper = mapper;
  s.Prop = multi;
  return s;
}

Scene Hybrid()
{
  Scene s;
  vtkNew<vtkHybridVolumeMapper> mapper;
  mapper->SetInputData(Blob(12, 0.0));
  mapper->SetPointsInputData(MakeHybridPointLine(50, 0.15));
  mapper->SetNumberOfSlabs(3);
  s.Attach = [](vtkAbstractMapper3D* m, vtkProp* p)
  {
    vtkSmartPointer<vtkVolume> volume = vtkVolume::SafeDownCast(p);
    if (!volume)
    {
      volume = vtkSmartPointer<vtkVolume>::New();
      volume->SetProperty(Property(true));
    }
    volume->SetMapper(vtkAbstractVolumeMapper::SafeDownCast(m));
    return vtkSmartPointer<vtkProp>(volume);
  };
  s.Mapper = mapper;
  s.Prop = s.Attach(mapper, nullptr);
  return s;
}

vtkSmartPointer<vtkRenderWindow> MakeWindow(vtkRenderer* ren)
{
  auto win = vtkSmartPointer<vtkRenderWindow>::New();
  win->SetSize(64, 64);
  win->SetMultiSamples(0);
  win->AddRenderer(ren);
  ren->SetBackground(0.1, 0.1, 0.1);
  vtkNew<vtkLight> light;
  ren->AddLight(light);
  return win;
}

void Frame(vtkRenderer* ren, vtkRenderWindow* win, vtkProp* prop)
{
  ren->AddViewProp(prop);
  ren->ResetCamera();
  ren->GetActiveCamera()->Azimuth(20.0);
  ren->GetActiveCamera()->Elevation(15.0);
  win->Render();
  ren->GetActiveCamera()->Azimuth(10.0);
  win->Render();
}

// One round of the three orders for one scene; `report` prints the counts (first round).
void Round(const std::string& name, const Maker& make, CapturingOutputWindow* errors, bool report)
{
  // Mapper first.
  {
    vtkNew<vtkRenderer> ren;
    auto win = MakeWindow(ren);
    win->Render();
    const GLNames before = CountGLNames(win);
    Scene scene = make();
    Frame(ren, win, scene.Prop);
    const GLNames drawn = CountGLNames(win);
    // The mapper goes, the prop stays in the renderer: only the callback reaches the mapper.
    scene.Attach(nullptr, scene.Prop);
    scene.Mapper = nullptr;
    scene.Keep.clear();
    const GLNames after = CountGLNames(win);
    ren->RemoveViewProp(scene.Prop);
    scene = Scene();
    if (report)
      std::cout << name << ": " << before.Text() << " before, " << drawn.Text() << " drawn, "
                << after.Text() << " after the mapper\n";
    Check(drawn.Total() > before.Total(), name + ": the mapper made GL names");
    Check(after == before, name + ", mapper first: every name it made is gone");
  }
  // Window change.
  {
    vtkNew<vtkRenderer> ren1, ren2;
    auto win1 = MakeWindow(ren1);
    auto win2 = MakeWindow(ren2);
    win1->Render();
    const GLNames before = CountGLNames(win1);
    Scene scene = make();
    Frame(ren1, win1, scene.Prop);
    // The mapper moves to a prop of the second window; the first prop stays where it was.
    scene.Attach(nullptr, scene.Prop);
    vtkSmartPointer<vtkProp> moved = scene.Attach(scene.Mapper, nullptr);
    Frame(ren2, win2, moved);
    Check(CountGLNames(win1) == before,
      name + ", moved to another window: the first holds none of its names");
    ren2->RemoveViewProp(moved);
    ren1->RemoveViewProp(scene.Prop);
    moved = nullptr;
    scene = Scene();
  }
  // Window first.
  {
    vtkNew<vtkRenderer> ren;
    auto win = MakeWindow(ren);
    Scene scene = make();
    Frame(ren, win, scene.Prop);
    const int reported = errors->Errors + errors->Warnings;
    win = nullptr;
    ren->RemoveAllViewProps();
    scene = Scene();
    Check(errors->Errors + errors->Warnings == reported,
      name + ", window first: the mapper went without a word");
  }
}
}

int TestGraphicsResources(int argc, char* argv[])
{
  CapturingOutputWindow* errors = CapturingOutputWindow::Install();
  const std::filesystem::path dir = TestPaths::FromArguments(argc, argv).Output;
  const std::vector<std::string> tiles = {
    WritePool(Grid(33, 0.0, 0.5), (dir / "graphics-resources-a.spp").string(), 9),
    WritePool(Grid(33, 4.0, -0.5), (dir / "graphics-resources-b.spp").string(), 9)
  };
  const std::string bricks =
    WritePool(Blob(20, 0.0), (dir / "graphics-resources-v.spp").string(), 8);

  const std::vector<std::pair<std::string, Maker>> scenes = {
    { "horizons in core", [] { return Horizons({}); } },
    { "horizons paged", [&] { return Horizons(tiles); } },
    { "volumes, atlas", [] { return Volumes(true, ""); } },
    { "volumes, plain textures", [] { return Volumes(false, ""); } },
    { "volumes, one paged", [&] { return Volumes(true, bricks); } },
    { "hybrid", [] { return Hybrid(); } },
  };
  const int rounds = 6;
  double rss3 = 0, heap3 = 0;
  for (int round = 0; round < rounds; ++round)
  {
    for (const auto& s : scenes)
      Round(s.first, s.second, errors, round == 0);
    if (round == 2)
    {
      rss3 = ResidentKiB();
      heap3 = HeapInUseKiB();
    }
  }
  const double rss = ResidentKiB(), heap = HeapInUseKiB();
  std::cout << "resident " << rss3 / 1024.0 << " MB after round 3, " << rss / 1024.0
            << " MB after round " << rounds << "; heap in use " << heap3 / 1024.0 << " MB, then "
            << heap / 1024.0 << " MB\n";
  Check(heap - heap3 < HeapGrowthBoundKiB, "the heap does not grow over the rounds");
  if (UnderAddressSanitizer())
    std::cout << "the resident set is not asserted under AddressSanitizer (its quarantine fills)\n";
  else
    Check(rss - rss3 < 24 * 1024, "memory does not grow over the rounds (< 24 MB)");
  Check(errors->Errors + errors->Warnings == 0, "no VTK error or warning");
  std::cout << "TestGraphicsResources: " << Failures() << " failure(s)\n";
  return Failures() == 0 ? 0 : 1;
}
