// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The stacked height-field mapper paging the demo's horizons from tile pools (one
// vtkPagePoolReader per horizon in front of vtkStackedHeightFieldMapper):
//  1. every frame of a scripted camera path before the cache settles is a valid coarser
//     rendering: it equals (within a stated bound) the in-core rendering of exactly the
//     heights the cut holds (the pager's CPU lookup), so there are no holes and no garbage
//     tiles; and the first frame already covers what the full data covers;
//  2. converged, the paged image equals the in-core image of the same data, shaded and in
//     horizon ids, with level-of-detail feedback (the default) and without; with feedback the
//     tiles hidden under other horizons stay coarse, and out-of-view tiles stay coarse when
//     zoomed in. Paged and in core are two programs (strata::HeightFieldShaderComposer::Key::Paged:
//     heights through the tile atlas's page table, or one array texture): the shaded images
//     may differ by ImagePolicy::TwoProgramsMax (1 of 255, StrataImagePolicy.h rule 2); the
//     horizon ids are discrete and stay exact;
//  3. the demo's other horizon scene, the four Reek horizons (Irap binary grids with holes on a
//     rotated UTM-scale grid, 8x vertical exaggeration), paged the same way: every path frame
//     is the rendering of its cut, and converged the image is the in-core one;
//  4. faults: a corrupt tile, a pool truncated while rendering, a truncated pool and a missing
//     file give VTK errors and no crash; the horizons keep their coarser tiles.
#include "StrataDemoScene.h"
#include "StrataErrorCounter.h"
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h" // For ImageError

#include "StrataHeightFieldPager.h"
#include "StrataPagePoolFile.h"
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <thread>
#include <unistd.h>

using namespace strata_test;

namespace
{
const int Page = 33; // stride 32: the quadtree's 32-cell leaves never straddle tiles

// The heights the paged mapper's cut holds now, as in-core images (its CPU reference lookup).
std::vector<vtkSmartPointer<vtkImageData>> CutAsImages(vtkStackedHeightFieldMapper* paged,
  const std::vector<vtkSmartPointer<vtkImageData>>& full)
{
  const strata::HeightFieldPager* pager = paged->GetPager();
  std::vector<vtkSmartPointer<vtkImageData>> out;
  for (size_t k = 0; k < full.size(); ++k)
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->CopyStructure(full[k]);
    vtkNew<vtkFloatArray> h;
    h->SetNumberOfTuples(static_cast<vtkIdType>(pager->GetNX()) * pager->GetNY());
    for (int j = 0; j < pager->GetNY(); ++j)
      for (int i = 0; i < pager->GetNX(); ++i)
      {
        const float v = pager->GetHeight(static_cast<int>(k), i, j);
        h->SetValue(static_cast<vtkIdType>(j) * pager->GetNX() + i,
          std::abs(v) < 1e30f ? v : std::numeric_limits<float>::quiet_NaN());
      }
    image->GetPointData()->SetScalars(h);
    out.push_back(image);
  }
  return out;
}

// One vtkPagePoolReader per pool in front of `m`, kept in `readers`.
void PagedFrom(const std::vector<std::string>& pools,
  vtkStackedHeightFieldMapper* m,
  std::vector<vtkSmartPointer<vtkPagePoolReader>>& readers)
{
  for (const auto& pool : pools)
  {
    auto r = vtkSmartPointer<vtkPagePoolReader>::New();
    r->SetFileName(pool.c_str());
    m->AddInputConnection(r->GetOutputPort());
    readers.push_back(r);
  }
}

// Points on tile lines where the pages of the two (or four) tiles meeting there disagree: a
// crack the ray could pass through. Stitching makes it 0 for every cut.
long Seams(const strata::HeightFieldPager* pager, double tolerance)
{
  const int S = pager->GetPageSize() - 1;
  const int* tiles = pager->GetTiles();
  long bad = 0;
  auto same = [&](float a, float b)
  { return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= tolerance; };
  for (int h = 0; h < pager->GetNumberOfHorizons(); ++h)
  {
    for (int k = 1; k < tiles[0]; ++k) // vertical lines x = k S
      for (int j = 0; j < pager->GetNY(); ++j)
      {
        const int ty = std::min(j / S, tiles[1] - 1);
        bad += same(pager->GetTileHeight(h, k - 1, ty, k * S, j),
                 pager->GetTileHeight(h, k, ty, k * S, j))
                 ? 0
                 : 1;
      }
    for (int k = 1; k < tiles[1]; ++k) // horizontal lines y = k S
      for (int i = 0; i < pager->GetNX(); ++i)
      {
        const int tx = std::min(i / S, tiles[0] - 1);
        bad += same(pager->GetTileHeight(h, tx, k - 1, i, k * S),
                 pager->GetTileHeight(h, tx, k, i, k * S))
                 ? 0
                 : 1;
      }
  }
  return bad;
}

struct Difference
{
  long Differing = 0; ///< pixels with any channel off by more than 8/255
  int Max = 0;
  long Covered = 0; ///< pixels that are not background in the reference
};

Difference Compare(const std::vector<unsigned char>& a,
  const std::vector<unsigned char>& b,
  const std::vector<unsigned char>& background)
{
  Difference d;
  for (size_t p = 0; p + 2 < a.size(); p += 3)
  {
    int m = 0;
    for (int c = 0; c < 3; ++c)
      m = std::max(m, std::abs(int(a[p + c]) - int(b[p + c])));
    d.Max = std::max(d.Max, m);
    d.Differing += m > 8 ? 1 : 0;
    d.Covered +=
      (b[p] != background[p] || b[p + 1] != background[p + 1] || b[p + 2] != background[p + 2]) ? 1
                                                                                                : 0;
  }
  return d;
}
}

// A path's frames against the in-core rendering of their own cuts: the worst difference, the
// largest coverage change, the fewest covered pixels and how many frames were compared.
struct CutFrames
{
  Difference Worst;
  long WorstCoverage = 0;
  long SmallestCovered = 1L << 30;
  long Compared = 0;
  Difference Add(const std::vector<unsigned char>& frame,
    const std::vector<unsigned char>& ofCut,
    const std::vector<unsigned char>& background)
  {
    const Difference d = Compare(frame, ofCut, background);
    this->WorstCoverage = std::max(this->WorstCoverage,
      std::abs(
        Compare(ofCut, ofCut, background).Covered - Compare(frame, frame, background).Covered));
    this->SmallestCovered = std::min(this->SmallestCovered, d.Covered);
    if (d.Differing > this->Worst.Differing || this->Compared == 0)
      this->Worst = d;
    ++this->Compared;
    return d;
  }
};

// Gives `twin` (an in-core mapper) exactly the heights `paged`'s cut holds now.
void SetCutInputs(vtkStackedHeightFieldMapper* twin,
  vtkStackedHeightFieldMapper* paged,
  const std::vector<vtkSmartPointer<vtkImageData>>& full)
{
  twin->RemoveAllInputConnections(0);
  for (const auto& image : CutAsImages(paged, full))
    twin->AddInputDataObject(image);
}

// The demo's Reek scene (StrataDemo, scene 2) paged from tile pools against the same scene in
// core: a path of frames each against the rendering of its own cut, then converged.
void ReekPaged(const std::string& dataDir, const std::string& dir)
{
  const char* names[4] = { "reek_01_topreek_rota.gri",
    "reek_02_midreek_rota.gri",
    "reek_03_lowreek_rota.gri",
    "reek_04_basereek_rota.gri" };
  std::vector<vtkSmartPointer<vtkImageData>> horizons;
  std::vector<std::string> pools;
  vtkIdType holes = 0;
  double range[2] = { 1e300, -1e300 };
  for (int k = 0; k < 4; ++k)
  {
    vtkNew<vtkIrapBinaryGridReader> reader;
    reader->SetFileName((dataDir + "/horizons/" + names[k]).c_str());
    reader->Update();
    holes += reader->GetNumberOfNoDataValues();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->ShallowCopy(reader->GetOutput());
    double r[2];
    image->GetPointData()->GetScalars()->GetRange(r);
    range[0] = std::min(range[0], r[0]);
    range[1] = std::max(range[1], r[1]);
    horizons.push_back(image);
    const std::string pool = dir + "/hf-paging-reek-" + std::to_string(k) + ".spp";
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(pool.c_str());
    writer->SetPageSize(Page);
    Check(writer->Write(), "Reek tile pool written");
    pools.push_back(pool);
  }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  const int w = 200, h = 150;
  MakeWindow(win, ren, w, h);
  ren->SetBackground(0.08, 0.09, 0.12);
  // One colour map over the data's range for all three mappers: the built-in one spans each
  // mapper's own stack, which a coarse cut narrows.
  vtkNew<vtkLookupTable> lut;
  lut->SetTableRange(range);
  lut->SetHueRange(0.66, 0.0);
  lut->Build();
  vtkNew<vtkStackedHeightFieldMapper> incore, paged, coarse;
  for (vtkStackedHeightFieldMapper* m : { incore.Get(), paged.Get(), coarse.Get() })
  {
    m->SetTileSize(32);
    m->SetHeightScale(-1.0);
    m->SetColorMode(vtkStackedHeightFieldMapper::ColorModes::LookupTable);
    m->SetHeightLookupTable(lut);
  }
  for (const auto& image : horizons)
    incore->AddInputDataObject(image);
  paged->SetPagesPerFrame(4);
  std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
  PagedFrom(pools, paged, readers);
  vtkNew<vtkActor> actor;
  actor->SetMapper(incore);
  actor->SetScale(1, 1, 8);
  actor->GetProperty()->SetSpecular(0.2);
  ren->AddActor(actor);
  auto render = [&](vtkStackedHeightFieldMapper* m)
  {
    actor->SetMapper(m);
    win->Render();
    return ReadRGB(win);
  };
  std::vector<unsigned char> background;
  {
    actor->VisibilityOff();
    background = render(incore);
    actor->VisibilityOn();
  }
  // The demo's camera, closer (the demo's framing leaves 10 % of this small window covered).
  FrameReekScene(ren, actor, 2.4);
  vtkCamera* cam = ren->GetActiveCamera();

  // Levels are built around holes (strata::PagePoolWriter), so the roots alone already cover all
  // the full data cover: no hole that the rays could not see through to ask for detail.
  const long coveredFull = Compare(render(incore), render(incore), background).Covered;
  const std::vector<unsigned char> roots = render(paged);
  const long coveredRoots = Compare(roots, roots, background).Covered;
  std::cout << "HFPaging: Reek: first frame (roots only) covers " << coveredRoots
            << " pixels, in core " << coveredFull << "\n";
  Check(coveredRoots >= coveredFull, "the Reek roots cover what the full data cover");

  CutFrames cut;
  long worstSeams = 0;
  int frames = 0, converged = -1;
  std::vector<unsigned char> last;
  for (int f = 0; f < 300 && converged < 0; ++f)
  {
    if (f < 8)
    {
      cam->Azimuth(4.0);
      ren->ResetCameraClippingRange();
    }
    last = render(paged);
    ++frames;
    const auto st = paged->GetPagingStatistics();
    worstSeams = std::max(worstSeams, Seams(paged->GetPager(), 1e-2));
    SetCutInputs(coarse, paged, horizons);
    cut.Add(last, render(coarse), background);
    if (st.Converged && f >= 8)
      converged = f;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const auto st = paged->GetPagingStatistics();
  const auto incoreImage = render(incore);
  const Difference d = Compare(last, incoreImage, background);
  if (d.Max > 0)
  {
    WritePNG(dir + "/hf-paging-reek-paged.png", last, w, h);
    WritePNG(dir + "/hf-paging-reek-incore.png", incoreImage, w, h);
  }
  std::cout << "HFPaging: Reek: 4 pools of 554 x 451 (" << holes
            << " no-data nodes); converged after " << frames << " frames; " << cut.Compared
            << " frames compared with the rendering of their own cut (each >= "
            << cut.SmallestCovered << " covered pixels): worst " << cut.Worst.Differing << " of "
            << cut.Worst.Covered << " covered pixels differ by more than 8/255 (max "
            << cut.Worst.Max << "), coverage by at most " << cut.WorstCoverage << " pixels, "
            << worstSeams << " seam points; converged: max difference " << d.Max << " ("
            << d.Differing << " pixels off by more than 8/255) over " << d.Covered
            << " covered pixels; " << st.FinestTiles << " level-0 tiles resident of " << st.CutTiles
            << "; " << st.Failures << " failures\n";
  Check(converged > 0, "the paged Reek horizons converge");
  Check(holes > 0 && cut.Compared == frames && cut.SmallestCovered > 5000,
    "the Reek path's frames were compared, holes and all");
  Check(worstSeams == 0, "Reek: no seams between tiles of different levels");
  Check(cut.Worst.Differing <= std::max(4L, cut.Worst.Covered / 2000) && cut.WorstCoverage <= 10,
    "every Reek frame is the rendering of its cut (<= 0.05 % of pixels, coverage within 10 "
    "pixels)");
  // Converged, the cut's heights render as in core, by another program (paged vs in core,
  // StrataImagePolicy.h rule 2): the paged lookup's float arithmetic on this UTM-scale grid
  // moved a channel of a pixel by 1/255 on llvmpipe (seen: one).
  Check(d.Max <= ImagePolicy::TwoProgramsMax && d.Differing == 0 && d.Covered > 5000,
    "converged, the paged Reek scene equals the in-core one (max 1/255)");
  Check(st.Failures == 0 && st.RootPagesRead == 0, "Reek: no failures, roots from the readers");
  for (const auto& pool : pools)
    std::remove(pool.c_str());
}

namespace
{
/// What the parts share: the demo stack in a 200 x 150 window (no well, no target, no gradient),
/// its camera's home, the tile pools, the in-core mapper, the twin that draws a frame's cut
/// (Coarse), the paged mapper of the camera path and its readers; then the converged state and
/// the faults' views.
struct HFPagingFixture
{
  explicit HFPagingFixture(const std::string& dir)
    : Dir(dir)
  {
    MakeWindow(this->Win, this->Ren, W, H);
    this->Scene = AddDemoScene(this->Ren);
    this->Scene.Well->VisibilityOff();
    this->Scene.Target->VisibilityOff();
    this->Ren->GradientBackgroundOff();
    this->Home->DeepCopy(this->Ren->GetActiveCamera());
  }
  std::vector<unsigned char> Render(vtkStackedHeightFieldMapper* m)
  {
    this->Scene.Stack->SetMapper(m);
    this->Win->Render();
    return ReadRGB(this->Win);
  }
  static constexpr int W = 200, H = 150;
  std::string Dir;
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  DemoScene Scene;
  vtkNew<vtkCamera> Home;
  std::vector<std::string> Pools;
  /// Made after the pools are written, as the test always did.
  vtkSmartPointer<vtkStackedHeightFieldMapper> Coarse;
  vtkSmartPointer<vtkStackedHeightFieldMapper> Paged;
  std::vector<vtkSmartPointer<vtkPagePoolReader>> Readers;
  std::vector<unsigned char> Background;
  vtkStackedHeightFieldMapper::PagingStatistics ConvergedStats; ///< the path's, converged
  std::vector<unsigned char> ConvergedFull;                     ///< the in-core image then
  int BlindFinestTiles = 0;        ///< level-0 tiles without feedback, converged
  std::vector<unsigned char> Full; ///< the faults' in-core view (from home)
  double RootError = 0.0;          ///< the root-only rendering's RMS error there
};

void PoolsAndReferences(HFPagingFixture& fx)
{
  DemoScene& scene = fx.Scene;
  std::vector<std::string>& pools = fx.Pools;
  vtkStackedHeightFieldMapper* incore = fx.Scene.Mapper;
  std::vector<vtkSmartPointer<vtkPagePoolReader>>& readers = fx.Readers;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  const std::string& dir = fx.Dir;
  // One tile pool per horizon.
  for (size_t k = 0; k < scene.Horizons.size(); ++k)
  {
    const std::string pool = dir + "/hf-paging-" + std::to_string(k) + ".spp";
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputData(scene.Horizons[k]);
    writer->SetFileName(pool.c_str());
    writer->SetPageSize(Page);
    Check(writer->Write(), "tile pool written");
    pools.push_back(pool);
  }
  strata::PagePoolFile probe;
  probe.Open(pools[0]);
  std::cout << "HFPaging: " << scene.Horizons.size() << " pools of " << probe.GetNumberOfPages()
            << " tiles in " << probe.GetNumberOfLevels() << " levels\n";
  probe.Close();

  // In-core references: the demo mapper as is, and a twin that draws whatever heights it gets.
  fx.Coarse = vtkSmartPointer<vtkStackedHeightFieldMapper>::New();
  fx.Paged = vtkSmartPointer<vtkStackedHeightFieldMapper>::New();
  vtkStackedHeightFieldMapper* coarse = fx.Coarse;
  vtkStackedHeightFieldMapper* paged = fx.Paged;
  incore->SetTileSize(32);
  coarse->SetTileSize(32);
  paged->SetTileSize(32);
  paged->SetPagesPerFrame(3);
  paged->PrefetchOn(); // read-ahead on the path (the other mappers read on demand alone)
  PagedFrom(pools, paged, readers);
  scene.Stack->VisibilityOff();
  fx.Background = render(incore);
  scene.Stack->VisibilityOn();
}

void CameraPath(HFPagingFixture& fx)
{
  vtkRenderer* ren = fx.Ren;
  DemoScene& scene = fx.Scene;
  vtkCamera* cam = fx.Ren->GetActiveCamera();
  vtkStackedHeightFieldMapper* incore = fx.Scene.Mapper;
  vtkStackedHeightFieldMapper* coarse = fx.Coarse;
  vtkStackedHeightFieldMapper* paged = fx.Paged;
  const std::vector<unsigned char>& background = fx.Background;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  // 1. A camera path: orbit and dolly while the cache fills; each frame against the in-core
  // rendering of its own cut.
  const auto fullFirst = render(incore);
  const long coveredFull = Compare(fullFirst, fullFirst, background).Covered;
  CutFrames cut;
  long worstSeams = 0, mixedFrames = 0;
  int frames = 0, converged = -1;
  for (int f = 0; f < 200 && converged < 0; ++f)
  {
    if (f < 12)
    {
      cam->Azimuth(f < 6 ? 6.0 : -4.0);
      cam->Dolly(f < 6 ? 1.06 : 0.97);
      ren->ResetCameraClippingRange();
    }
    const auto image = render(paged);
    ++frames;
    const auto st = paged->GetPagingStatistics();
    if (f == 0)
    {
      Check(paged->GetPaged() && st.RootPagesRead == 0,
        "paged from the pools; the roots came from the readers' coarsest levels (no read on the "
        "render thread)");
      const long covered = Compare(image, image, background).Covered;
      std::cout << "HFPaging: first frame (roots only): " << covered << " covered pixels, in-core "
                << coveredFull << "\n";
    }
    worstSeams = std::max(worstSeams, Seams(paged->GetPager(), 1e-3));
    mixedFrames += st.FinestTiles < st.CutTiles ? 1 : 0;
    SetCutInputs(coarse, paged, scene.Horizons);
    const Difference d = cut.Add(image, render(coarse), background);
    if (std::getenv("STRATA_DEBUG_PAGING"))
      std::cout << "  frame " << f << ": tiles " << st.CutTiles << " (finest " << st.FinestTiles
                << "), pending " << st.PendingPages << ", entered " << st.Entered << ", differing "
                << d.Differing << ", max " << d.Max << "\n";
    if (st.Converged && f >= 12)
      converged = f;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::cout << "HFPaging: converged after " << frames << " frames; " << cut.Compared
            << " frames compared with the rendering of their own cut (each >= "
            << cut.SmallestCovered << " covered pixels); worst: " << cut.Worst.Differing << " of "
            << cut.Worst.Covered << " covered pixels differ by more than 8/255 (max "
            << cut.Worst.Max << "); coverage differs by at most " << cut.WorstCoverage
            << " pixels; " << mixedFrames << " frames mixed levels, worst " << worstSeams
            << " tile-line points where neighbouring pages disagree\n";
  Check(converged > 0, "the paged horizons converge");
  Check(worstSeams == 0 && mixedFrames >= 20,
    "no seams: where tiles of different levels meet, their pages agree");
  // Stitched, the search's surface is the cut's level-0 surface: no cracks at level seams (35
  // of 23033 pixels differed before stitching, where rays passed through them).
  Check(cut.Worst.Differing <= std::max(4L, cut.Worst.Covered / 2000),
    "every intermediate frame is the rendering of its cut (<= 0.05 % of pixels)");
  Check(
    cut.WorstCoverage <= 10, "no holes: each frame covers what its cut's in-core rendering covers");
  Check(cut.Compared == frames && frames >= 20 && cut.SmallestCovered > 5000,
    "every frame of the path was compared and shows the horizons");
}

void Converged(HFPagingFixture& fx)
{
  vtkStackedHeightFieldMapper* incore = fx.Scene.Mapper;
  vtkStackedHeightFieldMapper* paged = fx.Paged;
  const std::vector<unsigned char>& background = fx.Background;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  // 2. Converged: the in-core image, shaded and in ids.
  fx.ConvergedStats = paged->GetPagingStatistics();
  fx.ConvergedFull = render(incore);
  const auto& st = fx.ConvergedStats;
  const auto& full = fx.ConvergedFull;
  const auto mine = render(paged);
  const Difference d = Compare(mine, full, background);
  std::cout << "HFPaging: converged, shaded: max difference " << d.Max << " over " << d.Covered
            << " covered pixels; " << st.FinestTiles << " level-0 tiles resident of " << st.CutTiles
            << "; " << st.BytesRead / 1024 << " KiB read\n";
  // Paged vs in core: two programs (rule 2 of StrataImagePolicy.h), 1 of 255.
  Check(d.Max <= ImagePolicy::TwoProgramsMax && d.Covered > 10000,
    "converged paged rendering equals the in-core one (shaded, max 1/255)");
  incore->SetOutputMode(vtkStackedHeightFieldMapper::OutputModes::HorizonId);
  paged->SetOutputMode(vtkStackedHeightFieldMapper::OutputModes::HorizonId);
  const Difference ids = Compare(render(paged), render(incore), background);
  std::cout << "HFPaging: converged, horizon ids: max difference " << ids.Max << "\n";
  // Ids are discrete: exact, whatever the program.
  Check(ids.Max == 0, "converged paged rendering equals the in-core one (ids)");
  incore->SetOutputMode(vtkStackedHeightFieldMapper::OutputModes::Shaded);
  paged->SetOutputMode(vtkStackedHeightFieldMapper::OutputModes::Shaded);
}

void WithoutFeedback(HFPagingFixture& fx)
{
  vtkStackedHeightFieldMapper* paged = fx.Paged;
  std::vector<vtkSmartPointer<vtkPagePoolReader>>& readers = fx.Readers;
  const std::vector<unsigned char>& background = fx.Background;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  const auto& st = fx.ConvergedStats;
  const auto& full = fx.ConvergedFull;
  // Without feedback every tile in view is refined by its screen-space error; with it only
  // the tiles rays hit, so the parts of the lower horizons hidden under the upper ones stay
  // coarse: fewer level-0 tiles, the same image.
  vtkNew<vtkStackedHeightFieldMapper> blind;
  blind->SetTileSize(32);
  blind->LevelOfDetailFeedbackOff();
  for (const auto& r : readers)
    blind->AddInputConnection(r->GetOutputPort());
  for (int f = 0; f < 300 && !blind->GetPagingStatistics().Converged; ++f)
  {
    render(blind);
    blind->WaitForPages(1.0);
  }
  const auto sb = blind->GetPagingStatistics();
  fx.BlindFinestTiles = sb.FinestTiles;
  const Difference db = Compare(render(blind), full, background);
  std::cout << "HFPaging: level-0 tiles resident with feedback " << st.FinestTiles << " ("
            << st.FeedbackPages << " tiles asked for), without " << sb.FinestTiles
            << "; without feedback max difference " << db.Max << "; feedback reduction "
            << paged->GetPagingStatistics().FeedbackMilliseconds << " ms\n";
  Check(st.FeedbackUsed && !sb.FeedbackUsed, "feedback drives the cut when on, not when off");
  Check(sb.Converged && db.Max <= ImagePolicy::TwoProgramsMax,
    "without feedback the converged image is the in-core one too (paged vs in core: max 1/255)");
  Check(st.FinestTiles < sb.FinestTiles,
    "with feedback hidden tiles stay coarse (fewer level-0 tiles)");
}

void DeferredReadBack(HFPagingFixture& fx)
{
  std::vector<vtkSmartPointer<vtkPagePoolReader>>& readers = fx.Readers;
  const std::vector<unsigned char>& background = fx.Background;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  const auto& full = fx.ConvergedFull;
  // Read back at the next frame instead of after the draw: the cut sees the same feedback.
  vtkNew<vtkStackedHeightFieldMapper> deferred;
  deferred->SetTileSize(32);
  deferred->SetPagesPerFrame(3);
  deferred->DeferFeedbackReadBackOn();
  for (const auto& r : readers)
    deferred->AddInputConnection(r->GetOutputPort());
  int df = 0;
  for (; df < 300 && !deferred->GetPagingStatistics().Converged; ++df)
  {
    render(deferred);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const auto sd = deferred->GetPagingStatistics();
  const Difference dd = Compare(render(deferred), full, background);
  std::cout << "HFPaging: deferred feedback read-back: converged after " << df << " frames, "
            << sd.FinestTiles << " level-0 tiles, max difference " << dd.Max << "\n";
  Check(sd.Converged && sd.FeedbackUsed && dd.Max <= ImagePolicy::TwoProgramsMax &&
          sd.FinestTiles < fx.BlindFinestTiles,
    "with the read-back deferred, feedback converges to the in-core image (max 1/255) and keeps "
    "hidden tiles coarse");
}

void BlendedRefinement(HFPagingFixture& fx)
{
  vtkRenderer* ren = fx.Ren;
  vtkCamera* cam = fx.Ren->GetActiveCamera();
  vtkCamera* home = fx.Home;
  std::vector<std::string>& pools = fx.Pools;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  {
    // Refinement without pops: at a still camera, the largest change of any grid height from
    // one frame to the next, tiles blending in over MorphFrames frames and at once.
    cam->DeepCopy(home);
    ren->ResetCameraClippingRange();
    double jump[2] = { 0.0, 0.0 };
    int settled[2] = { 0, 0 };
    for (int morph = 0; morph < 2; ++morph)
    {
      vtkNew<vtkStackedHeightFieldMapper> m;
      m->SetTileSize(32);
      m->SetPagesPerFrame(3);
      m->SetMorphFrames(morph ? 4 : 0);
      std::vector<vtkSmartPointer<vtkPagePoolReader>> rs;
      PagedFrom(pools, m, rs);
      std::vector<float> before;
      for (int f = 0; f < 300 && !m->GetPagingStatistics().Converged; ++f)
      {
        render(m);
        const strata::HeightFieldPager* pg = m->GetPager();
        std::vector<float> now;
        for (int k = 0; k < pg->GetNumberOfHorizons(); ++k)
          for (int j = 0; j < pg->GetNY(); ++j)
            for (int i = 0; i < pg->GetNX(); ++i)
              now.push_back(pg->GetHeight(k, i, j));
        for (size_t q = 0; q < now.size() && q < before.size(); ++q)
          if (!std::isnan(now[q]) && !std::isnan(before[q]))
            jump[morph] = std::max(jump[morph], double(std::abs(now[q] - before[q])));
        before.swap(now);
        settled[morph] = f + 1;
        m->WaitForPages(1.0);
      }
    }
    std::cout << "HFPaging: largest height change between two frames: " << jump[0]
              << " refining at once (" << settled[0] << " frames), " << jump[1]
              << " blending over 4 frames (" << settled[1] << " frames)\n";
    Check(jump[1] > 0.0 && jump[1] <= 0.6 * jump[0],
      "blended refinement: no frame jumps by more than 0.6 of the largest unblended pop");
  }
}

void ZoomedIn(HFPagingFixture& fx)
{
  vtkRenderer* ren = fx.Ren;
  vtkCamera* cam = fx.Ren->GetActiveCamera();
  vtkCamera* home = fx.Home;
  std::vector<std::string>& pools = fx.Pools;
  vtkStackedHeightFieldMapper* incore = fx.Scene.Mapper;
  std::vector<vtkSmartPointer<vtkPagePoolReader>>& readers = fx.Readers;
  const std::vector<unsigned char>& background = fx.Background;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  {
    // Zoomed into a corner: tiles out of view are never refined.
    cam->DeepCopy(home);
    cam->Dolly(10.0);
    ren->ResetCameraClippingRange();
    vtkNew<vtkStackedHeightFieldMapper> zoomed;
    zoomed->SetTileSize(32);
    for (const auto& r : readers)
      zoomed->AddInputConnection(r->GetOutputPort());
    for (int f = 0; f < 200 && !zoomed->GetPagingStatistics().Converged; ++f)
    {
      render(zoomed);
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    const auto st = zoomed->GetPagingStatistics();
    const int* tiles = zoomed->GetPager()->GetTiles();
    const int all = tiles[0] * tiles[1] * static_cast<int>(pools.size());
    const Difference d = Compare(render(zoomed), render(incore), background);
    std::cout << "HFPaging: zoomed in: " << st.FinestTiles << " of " << all
              << " level-0 tiles resident; max difference " << d.Max << " to in-core\n";
    Check(st.Converged && st.FinestTiles < all / 2, "tiles out of view stay coarse");
    Check(d.Max <= ImagePolicy::TwoProgramsMax,
      "zoomed in, converged paged rendering equals the in-core one (max 1/255)");
  }
}

void FaultViews(HFPagingFixture& fx)
{
  vtkRenderer* ren = fx.Ren;
  vtkCamera* cam = fx.Ren->GetActiveCamera();
  vtkCamera* home = fx.Home;
  std::vector<std::string>& pools = fx.Pools;
  vtkStackedHeightFieldMapper* incore = fx.Scene.Mapper;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  // 4. Faults.
  cam->DeepCopy(home);
  ren->ResetCameraClippingRange();
  fx.Full = render(incore);
  const auto& full = fx.Full;
  // The error of the root-only rendering: what "coarser" may cost at most.
  double& rootError = fx.RootError;
  {
    vtkNew<vtkStackedHeightFieldMapper> m;
    std::vector<vtkSmartPointer<vtkPagePoolReader>> rs;
    PagedFrom(pools, m, rs);
    m->SetAtlasBudget(1.0); // 240 tiles: ample
    m->SetPagesPerFrame(1);
    rootError = ImageError(render(m), full).Rms;
  }
}

void CorruptTile(HFPagingFixture& fx)
{
  std::vector<std::string>& pools = fx.Pools;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  const std::string& dir = fx.Dir;
  const std::vector<unsigned char>& full = fx.Full;
  const double rootError = fx.RootError;
  const std::string corrupt = dir + "/hf-paging-corrupt.spp";
  Check(CopyFile(pools[1], corrupt) && CorruptPage(corrupt, 40, 9),
    "page 40 corrupted"); // a level-0 tile in view
  {
    vtkNew<vtkStackedHeightFieldMapper> m;
    std::vector<vtkSmartPointer<vtkPagePoolReader>> rs;
    PagedFrom({ pools[0], corrupt, pools[2] }, m, rs);
    vtkNew<ErrorCounter> errors;
    errors->Watch(m);
    for (auto& r : rs)
      errors->Watch(r);
    double worstRms = 0.0;
    std::vector<unsigned char> last;
    for (int f = 0; f < 80; ++f)
    {
      last = render(m);
      worstRms = std::max(worstRms, ImageError(last, full).Rms);
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    const bool named = errors->First.find("checksum") != std::string::npos &&
                       errors->First.find("coarser") != std::string::npos;
    std::cout << "HFPaging: corrupt tile: " << m->GetPagingStatistics().Failures << " failed, "
              << errors->Errors << " VTK error(s): \"" << errors->First
              << "\"; RMS to in-core: worst " << worstRms << ", last " << ImageError(last, full).Rms
              << " (roots only " << rootError << ")\n";
    Check(m->GetPagingStatistics().Failures == 1 && errors->Errors == 1 && named,
      "a corrupt tile: one clear error");
    Check(worstRms <= rootError + 0.5,
      "with a corrupt tile the horizons stay a valid coarser rendering");
  }
}

void TruncatedWhileRendering(HFPagingFixture& fx)
{
  std::vector<std::string>& pools = fx.Pools;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  const std::string& dir = fx.Dir;
  const std::vector<unsigned char>& full = fx.Full;
  const double rootError = fx.RootError;
  const std::string shrinking = dir + "/hf-paging-shrinking.spp";
  Check(CopyFile(pools[0], shrinking), "pool copied");
  {
    vtkNew<vtkStackedHeightFieldMapper> m;
    std::vector<vtkSmartPointer<vtkPagePoolReader>> rs;
    PagedFrom({ shrinking, pools[1], pools[2] }, m, rs);
    m->SetPagesPerFrame(1);
    vtkNew<ErrorCounter> errors;
    errors->Watch(m);
    for (auto& r : rs)
      errors->Watch(r);
    render(m);
    {
      strata::PagePoolFile file;
      file.Open(shrinking);
      const auto firstPage = file.GetPageEntry(0).Offset;
      file.Close();
      Check(truncate(shrinking.c_str(), static_cast<off_t>(firstPage)) == 0,
        "pool truncated behind the reader's back");
    }
    double worstRms = 0.0;
    for (int f = 0; f < 40; ++f)
    {
      worstRms = std::max(worstRms, ImageError(render(m), full).Rms);
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    const int failures = m->GetPagingStatistics().Failures;
    std::cout << "HFPaging: pool truncated while rendering: " << failures << " failed tiles, "
              << errors->Errors << " VTK errors; worst RMS " << worstRms << "\n";
    Check(failures > 0 && errors->Errors == failures,
      "read errors while rendering: one VTK error per failed tile");
    Check(worstRms <= rootError + 0.5, "after read errors the horizons keep their coarser tiles");
  }
}

void BrokenPools(HFPagingFixture& fx)
{
  std::vector<std::string>& pools = fx.Pools;
  auto render = [&fx](vtkStackedHeightFieldMapper* m) { return fx.Render(m); };
  const std::string& dir = fx.Dir;
  for (const std::string& bad : { dir + "/hf-paging-truncated.spp", dir + "/hf-no-such-pool.spp" })
  {
    if (bad.find("truncated") != std::string::npos)
      Check(CopyFile(pools[0], bad, 0.5), "truncated copy written");
    vtkNew<vtkStackedHeightFieldMapper> m;
    std::vector<vtkSmartPointer<vtkPagePoolReader>> rs;
    PagedFrom({ bad, pools[1], pools[2] }, m, rs);
    vtkNew<ErrorCounter> errors;
    errors->Watch(m);
    for (auto& r : rs)
      errors->Watch(r);
    render(m);
    std::cout << "HFPaging: " << bad.substr(dir.size() + 1) << ": " << errors->Errors
              << " VTK error(s): \"" << errors->First << "\"\n";
    Check(
      errors->Errors >= 1, "a broken pool (" + bad.substr(dir.size() + 1) + ") gives a VTK error");
  }
}

}

int TestHeightFieldPaging(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  HFPagingFixture fx(paths.Output);
  RunSubTests(
    {
      { "PoolsAndReferences", [&] { PoolsAndReferences(fx); } },
      { "CameraPath", [&] { CameraPath(fx); } },
      { "Converged", [&] { Converged(fx); } },
      { "WithoutFeedback", [&] { WithoutFeedback(fx); } },
      { "DeferredReadBack", [&] { DeferredReadBack(fx); } },
      { "BlendedRefinement", [&] { BlendedRefinement(fx); } },
      { "ZoomedIn", [&] { ZoomedIn(fx); } },
      // 3. The Reek scene.
      { "ReekPaged", [&] { ReekPaged(paths.Data, fx.Dir); } },
      { "FaultViews", [&] { FaultViews(fx); } },
      { "CorruptTile", [&] { CorruptTile(fx); } },
      { "TruncatedWhileRendering", [&] { TruncatedWhileRendering(fx); } },
      { "BrokenPools", [&] { BrokenPools(fx); } },
    },
    Failures);
  for (const auto& pool : fx.Pools)
    std::remove(pool.c_str());
  std::remove((fx.Dir + "/hf-paging-corrupt.spp").c_str());
  std::remove((fx.Dir + "/hf-paging-shrinking.spp").c_str());
  return Failures() == 0 ? 0 : 1;
}
