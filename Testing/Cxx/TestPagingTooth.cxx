// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The demo's tooth scenes paged: the CT at full resolution, its factor-4 volume, and the hybrid
// of that volume and its points, each with the volume in a brick pool behind a
// vtkPagePoolReader (the hybrid through vtkHybridVolumeMapper's input 0). Along a scripted
// orbit, every frame before the cache settles is the in-core rendering of exactly the cut it
// drew (SetFixedCut on an in-core twin: no holes, no garbage bricks), the hybrid's slabs share
// one cut per frame, and once settled each paged image equals the in-core one.
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataRealVolumes.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h" // For ImageError

#include "vtkCamera.h"
#include "vtkHybridVolumeFilter.h"
#include "vtkHybridVolumeMapper.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>

using namespace strata_test;

namespace
{
const int Size = 128;

// The paged mapper, the in-core mapper of the same data, and the in-core twin that draws the
// paged mapper's cut; for the hybrid the ray casters inside.
struct Case
{
  std::string Name;
  vtkVolumeMapper* Paged;
  vtkVolumeMapper* InCore;
  vtkVolumeMapper* OfCut;
  vtkMultiVolumeRayCastMapper* PagedCaster;
  vtkMultiVolumeRayCastMapper* OfCutCaster;
};

void Configure(vtkMultiVolumeRayCastMapper* m, int brickSize)
{
  m->SetSampleDistance(0.5); // as the demo
  m->SetBrickSize(brickSize);
  m->SetAtlasBudget(64.0); // every brick fits
  m->SetPagesPerFrame(8);  // refine slowly: many intermediate frames
}
/// The tooth in a Size x Size window, seen as the demo shows it.
struct ToothView
{
  explicit ToothView(vtkImageData* tooth)
    : Tooth(tooth)
  {
    MakeWindow(this->Win, this->Ren, Size, Size);
    this->Volume->SetProperty(MakeRealVolumeProperty("tooth"));
    this->Ren->AddVolume(this->Volume);
    RealVolumeView("tooth", this->ViewDir, this->ViewUp);
  }
  /// The demo's view of the tooth.
  void Frame()
  {
    FrameVolumes(
      this->Ren, { { this->Tooth, this->Volume.Get() } }, this->ViewDir, this->ViewUp, 0.85);
  }
  std::vector<unsigned char> Render(vtkVolumeMapper* m)
  {
    this->Volume->SetMapper(m);
    this->Win->Render();
    return ReadRGB(this->Win);
  }
  vtkImageData* Tooth;
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  vtkNew<vtkVolume> Volume;
  double ViewDir[3], ViewUp[3];
};

/// Brick pools: the tooth in 16^3 bricks, its 26 x 24 x 41 factor-4 volume in 8^3.
void WritePools(const std::pair<vtkImageData*, std::pair<std::string, int>> (&pools)[2],
  const std::string& dir)
{
  for (const auto& p : pools)
  {
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputData(p.first);
    writer->SetFileName(p.second.first.c_str());
    writer->SetPageSize(p.second.second);
    Check(writer->Write(), "pool written: " + p.second.first);
    std::cout << "PagingTooth: " << p.second.first.substr(dir.size() + 1) << ": "
              << p.first->GetDimensions()[0] << "x" << p.first->GetDimensions()[1] << "x"
              << p.first->GetDimensions()[2] << ", " << writer->GetNumberOfPages() << " pages of "
              << p.second.second << "^3\n";
  }
}

void HeldCut(ToothView& v, const std::string& toothPool)
{
  auto render = [&v](vtkVolumeMapper* m) { return v.Render(m); };
  // HoldCut: renders after the first keep its cut while pages arrive (the hybrid's slabs).
  {
    v.Frame();
    vtkNew<vtkPagePoolReader> r;
    r->SetFileName(toothPool.c_str());
    vtkNew<vtkMultiVolumeRayCastMapper> m;
    m->SetInputConnection(r->GetOutputPort());
    Configure(m, 16);
    render(m);
    const auto first = m->GetCutBricks(0);
    m->HoldCutOn();
    bool kept = true;
    for (int f = 0; f < 5; ++f)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      render(m);
      kept = kept && m->GetCutBricks(0) == first;
    }
    m->HoldCutOff();
    for (int f = 0; f < 5; ++f)
      render(m);
    std::cout << "PagingTooth: held cut: " << first.size() << " bricks over 5 held renders, "
              << m->GetCutBricks(0).size() << " after 5 more unheld\n";
    Check(kept, "a held cut stays as it is");
    Check(m->GetCutBricks(0).size() > first.size(), "released, the cut refines again");
  }
}

/// One case's orbit: 8 steps of 5 degrees while the cache fills, then still until it settles;
/// every frame against the in-core rendering of its own cut, the last against the in-core one.
void PagedPath(ToothView& v, const Case& c)
{
  vtkRenderer* ren = v.Ren;
  vtkCamera* cam = ren->GetActiveCamera();
  auto render = [&v](vtkVolumeMapper* m) { return v.Render(m); };
  v.Frame();
  // The orbit: 8 steps of 5 degrees while the cache fills, then still until it settles.
  int frames = 0, compared = 0, converged = -1;
  double worstRms = 0.0, worstMax = 0.0;
  long worstDiffering = 0;
  std::vector<unsigned char> last;
  for (int f = 0; f < 300 && converged < 0; ++f)
  {
    if (f < 8)
    {
      cam->Azimuth(5.0);
      ren->ResetCameraClippingRange();
    }
    last = render(c.Paged);
    ++frames;
    const bool settled = c.PagedCaster->GetPagingStatistics().Converged;
    // Every frame of the path against the in-core rendering of its own cut.
    c.OfCutCaster->SetFixedCut(0, c.PagedCaster->GetCutBricks(0));
    const auto reference = render(c.OfCut);
    Check(c.OfCutCaster->GetCutBricks(0) == c.PagedCaster->GetCutBricks(0),
      "the in-core twin draws the paged frame's cut (" + c.Name + ")");
    const ChannelError e = ImageError(last, reference);
    worstRms = std::max(worstRms, e.Rms);
    worstMax = std::max(worstMax, e.Max);
    worstDiffering = std::max(worstDiffering, PixelsOff(last, reference, 8));
    ++compared;
    if (settled && f >= 8)
      converged = f;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const auto st = c.PagedCaster->GetPagingStatistics();
  std::vector<unsigned char> incore;
  for (int i = 0; i < 2; ++i)
    incore = render(c.InCore);
  const ChannelError e = ImageError(last, incore);
  const auto levels = c.PagedCaster->GetResidentBricksPerLevel(0);
  std::string perLevel;
  for (size_t l = 0; l < levels.size(); ++l)
    perLevel += (l ? "/" : "") + std::to_string(levels[l]);
  std::cout << "PagingTooth (" << c.Name << "): converged after " << frames << " frames; "
            << compared << " frames against the in-core rendering of their own cut: worst RMS "
            << worstRms << ", max " << worstMax << ", " << worstDiffering << " of " << Size * Size
            << " pixels off by more than 8/255; converged: RMS " << e.Rms << ", max difference "
            << e.Max << " to in-core; bricks per level " << perLevel << "; roots from the pipeline "
            << st.RootPagesFromPipeline << ", read on the render thread " << st.RootPagesRead
            << "; " << st.Failures << " failures\n";
  Check(converged > 0, "the paged " + c.Name + " view converges");
  Check(compared == frames, "the path's frames were compared (" + c.Name + ")");
  // The pool rounds coarse levels to uint8, the in-core tree keeps them in float: a coarse
  // brick may differ by half a data unit, which the transfer function's slope turns into a
  // few levels of colour (6 at most here). No hole or garbage brick fits under these bounds.
  Check(worstRms <= 0.5 && worstMax <= 16,
    "every intermediate frame is the rendering of its own cut (" + c.Name +
      "; RMS <= 0.5, max <= 16)");
  Check(e.Rms <= 0.25 && e.Max <= 2,
    "converged, the paged image equals the in-core one (" + c.Name + "; RMS <= 0.25, max <= 2)");
  Check(st.RootPagesRead == 0 && st.Failures == 0,
    "the root from the reader, no failures (" + c.Name + ")");
}
}

int TestPagingTooth(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  std::string why;
  vtkSmartPointer<vtkImageData> tooth = LoadRealVolume("tooth", paths, why);
  Check(tooth != nullptr, "the tooth loads (" + why + ")");
  if (!tooth)
    return EXIT_FAILURE;
  vtkNew<vtkHybridVolumeFilter> hybridFilter; // as the demo builds it
  hybridFilter->SetInputData(tooth);
  hybridFilter->SetFactor(4, 4, 4);
  hybridFilter->SetFilterToCubic();
  hybridFilter->SetThreshold(24.0);
  hybridFilter->Update();
  vtkImageData* low = hybridFilter->GetLowResolutionOutput();
  vtkPolyData* points = hybridFilter->GetPointsOutput();

  // Brick pools: the tooth in 16^3 bricks, its 26 x 24 x 41 factor-4 volume in 8^3.
  const std::string dir = paths.Output;
  const std::string toothPool = dir + "/paging-tooth.spp", lowPool = dir + "/paging-tooth-low.spp";
  const std::pair<vtkImageData*, std::pair<std::string, int>> pools[2] = {
    { tooth, { toothPool, 16 } }, { low, { lowPool, 8 } }
  };
  WritePools(pools, dir); // before the readers, the window and the mappers exist, as always
  vtkNew<vtkPagePoolReader> toothReader, lowReader;
  toothReader->SetFileName(toothPool.c_str());
  lowReader->SetFileName(lowPool.c_str());

  ToothView view(tooth);

  // Full resolution and the factor-4 volume: plain ray casters.
  vtkNew<vtkMultiVolumeRayCastMapper> fullPaged, fullInCore, fullOfCut, lowPaged, lowInCore,
    lowOfCut;
  fullPaged->SetInputConnection(toothReader->GetOutputPort());
  fullInCore->SetInputData(tooth);
  fullOfCut->SetInputData(tooth);
  for (auto* m : { fullPaged.Get(), fullInCore.Get(), fullOfCut.Get() })
    Configure(m, 16);
  lowPaged->SetInputConnection(lowReader->GetOutputPort());
  lowInCore->SetInputData(low);
  lowOfCut->SetInputData(low);
  for (auto* m : { lowPaged.Get(), lowInCore.Get(), lowOfCut.Get() })
    Configure(m, 8);
  // The hybrid: the factor-4 volume paged, the points in core.
  vtkNew<vtkHybridVolumeMapper> hybridPaged, hybridInCore, hybridOfCut;
  hybridPaged->SetInputConnection(lowReader->GetOutputPort());
  hybridInCore->SetInputData(low);
  hybridOfCut->SetInputData(low);
  for (auto* m : { hybridPaged.Get(), hybridInCore.Get(), hybridOfCut.Get() })
  {
    m->SetPointsInputData(points);
    m->SetPointShape(vtkHybridVolumeMapper::PointShapes::GaussianSplats);
    Configure(m->GetVolumeMapper(), 8);
  }
  const Case cases[] = {
    { "full resolution", fullPaged, fullInCore, fullOfCut, fullPaged, fullOfCut },
    { "factor 4", lowPaged, lowInCore, lowOfCut, lowPaged, lowOfCut },
    { "hybrid",
      hybridPaged,
      hybridInCore,
      hybridOfCut,
      hybridPaged->GetVolumeMapper(),
      hybridOfCut->GetVolumeMapper() },
  };
  RunSubTests(
    {
      { "HeldCut", [&] { HeldCut(view, toothPool); } },
      { "FullResolution", [&] { PagedPath(view, cases[0]); } },
      { "Factor4", [&] { PagedPath(view, cases[1]); } },
      { "Hybrid", [&] { PagedPath(view, cases[2]); } },
    },
    Failures);
  Check(toothReader->GetLevelRead() == toothReader->GetNumberOfLevels() - 1 &&
          lowReader->GetLevelRead() == lowReader->GetNumberOfLevels() - 1,
    "through the pipeline the readers serve their coarsest levels only");
  Check(output->Errors == 0 && output->Warnings == 0, "no VTK errors or warnings");
  std::remove(toothPool.c_str());
  std::remove(lowPool.c_str());
  std::cout << (Failures() ? "FAILED" : "passed") << "\n";
  return Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}
