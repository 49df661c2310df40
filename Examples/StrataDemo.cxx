// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The main demo: renders (1) three crossing synthetic horizons with holes, a well path as a VTK
// tube and a target sphere, in core and paged out of core from tile pools, (2) the four Reek
// horizons (Irap binary grids on a rotated UTM-scale grid), (3) three overlapping volumes and (4)
// the tooth CT at full resolution, at 1/4 resolution and as the hybrid of the two (points where the
// coarse volume errs); writes one PNG per image. Usage:
//   StrataDemo <output-dir> [-D <data-dir>] [--shared-data <shared-data-dir>]
// (StrataTestPaths.h; scripts/demo passes Testing/Data and ../shared/data): each scene's files are
// read from the data folder, else from the shared one. Prints each image's path, last.
#include "StrataDemoScene.h"
#include "StrataImageHelpers.h"
#include "StrataRealVolumes.h"
#include "StrataSubsurfaceDemo.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkHorizonVolumeSampler.h"
#include "vtkHybridVolumeFilter.h"
#include "vtkHybridVolumeMapper.h"
#include "vtkImageAppend.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPagePoolReader.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
// Points where the factor-4 volume misses the original by more than this (of 255).
constexpr double HybridThreshold = 24.0;

std::string Save(vtkRenderWindow* win, const std::string& path)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(win);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->Write();
  return path;
}
}

int main(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::TakeFromArguments(argc, argv);
  const std::string out = argc > 1 ? argv[1] : ".";
  // Where the scenes' files are looked for, in order.
  std::vector<std::string> dataDirs = { paths.Data };
  if (!paths.SharedData.empty())
  {
    dataDirs.push_back(paths.SharedData);
  }
  std::vector<std::string> written;

  // --- Scene 0: the subsurface scene: two synthetic surveys from the Reek horizons (one
  // paged), the top horizon translucent, the second draped with the amplitude, the base by
  // depth, a well.
  std::string reekDir;
  for (size_t a = 0; a < dataDirs.size() && reekDir.empty(); ++a)
  {
    std::ifstream probe(dataDirs[a] + "/horizons/reek_01_topreek_rota.gri");
    if (probe)
    {
      reekDir = dataDirs[a] + "/horizons/";
    }
  }
  if (!reekDir.empty())
  {
    vtkNew<vtkRenderWindow> win;
    win->SetSize(800, 600);
    win->SetMultiSamples(0);
    vtkNew<vtkRenderer> ren;
    ren->SetBackground(0.08, 0.09, 0.12);
    win->AddRenderer(ren);
    strata_test::SubsurfaceDemo scene;
    if (strata_test::AddSubsurfaceDemo(ren, reekDir, out, scene))
    {
      strata_test::FrameReekScene(ren, scene.Horizons, 2.0);
      int frame = 0;
      for (; frame < 40; ++frame)
      {
        win->Render();
        if (scene.VolumeMapper->GetPagingStatistics().Converged)
          break;
        scene.VolumeMapper->WaitForPages(1.0);
      }
      std::cerr << "subsurface: " << scene.Drape->GetNumberOfSampledPoints()
                << " horizon points draped (" << scene.Drape->GetNumberOfPagesRead()
                << " pages read); survey A paged, settled after " << frame << " frames\n";
      written.push_back(Save(win, out + "/strata-subsurface.png"));
    }
    strata_test::RemoveSubsurfaceDemoFiles(scene);
    if (getenv("STRATA_DEMO_ONLY_SUBSURFACE"))
    {
      std::cout << written.back() << "\n";
      return EXIT_SUCCESS;
    }
  }

  // --- Scene 1: synthetic stack, well and target (shared with TestHeightFieldDemo).
  {
    vtkNew<vtkRenderWindow> win;
    win->SetSize(800, 600);
    win->SetMultiSamples(0);
    vtkNew<vtkRenderer> ren;
    win->AddRenderer(ren);
    auto scene = strata_test::AddDemoScene(ren);
    win->Render();
    written.push_back(Save(win, out + "/strata-horizons-synthetic.png"));

    // --- The same stack out of core: each horizon written to a tile pool, read back by a
    // vtkPagePoolReader and paged by the mapper (coarse tiles first, refined as the page cache
    // fills) until the cache settles; the image then equals the in-core one.
    std::vector<std::string> pools;
    vtkNew<vtkStackedHeightFieldMapper> paged;
    paged->SetTileSize(32); // the pools' tile stride: leaves never straddle tiles
    std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
    for (size_t k = 0; k < scene.Horizons.size(); ++k)
    {
      pools.push_back(out + "/strata-demo-horizon-" + std::to_string(k) + ".spp");
      vtkNew<vtkImageToPagePoolWriter> writer;
      writer->SetInputData(scene.Horizons[k]);
      writer->SetFileName(pools.back().c_str());
      writer->SetPageSize(33);
      writer->Write();
      auto reader = vtkSmartPointer<vtkPagePoolReader>::New();
      reader->SetFileName(pools.back().c_str());
      paged->AddInputConnection(reader->GetOutputPort());
      readers.push_back(reader);
    }
    scene.Mapper->SetTileSize(32);
    win->Render();
    const std::vector<unsigned char> incore = strata_test::ReadRGB(win);
    scene.Stack->SetMapper(paged);
    int frames = 0;
    for (; frames < 500 && !paged->GetPagingStatistics().Converged; ++frames)
    {
      win->Render();
      if (frames == 0) // the roots alone: the readers' coarsest levels, stitched
        written.push_back(Save(win, out + "/strata-horizons-paged-first-frame.png"));
      paged->WaitForPages(1.0);
    }
    win->Render();
    const std::vector<unsigned char> mine = strata_test::ReadRGB(win);
    int maxDifference = 0;
    for (size_t q = 0; q < mine.size() && q < incore.size(); ++q)
      maxDifference = std::max(maxDifference, std::abs(int(mine[q]) - int(incore[q])));
    written.push_back(Save(win, out + "/strata-horizons-paged.png"));
    const auto st = paged->GetPagingStatistics();
    std::cerr << "paged horizons: " << pools.size() << " tile pools of 33^2 tiles; settled after "
              << frames << " frames, " << st.FinestTiles << " level-0 tiles of " << st.CutTiles
              << ", " << st.BytesRead / 1024 << " KiB read; max difference to the in-core image "
              << maxDifference << "\n";
    scene.Stack->SetMapper(scene.Mapper);
    paged->ReleaseGraphicsResources(win);
    readers.clear();
    for (const auto& pool : pools)
      std::remove(pool.c_str());
  }

  // --- Scene 2: the four Reek horizons.
  if (reekDir.empty())
  {
    std::cerr << "Reek horizons not found in the data directories given; skipping that image.\n";
  }
  else
  {
    const char* names[4] = { "reek_01_topreek_rota.gri",
      "reek_02_midreek_rota.gri",
      "reek_03_lowreek_rota.gri",
      "reek_04_basereek_rota.gri" };
    vtkNew<vtkStackedHeightFieldMapper> mapper;
    std::vector<vtkSmartPointer<vtkIrapBinaryGridReader>> readers;
    for (const char* name : names)
    {
      auto reader = vtkSmartPointer<vtkIrapBinaryGridReader>::New();
      reader->SetFileName((reekDir + name).c_str());
      mapper->AddInputConnection(reader->GetOutputPort());
      readers.push_back(reader);
    }
    mapper->SetHeightScale(-1.0); // depths grow downwards
    mapper->SetColorMode(vtkStackedHeightFieldMapper::ColorModes::LookupTable);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->SetScale(1, 1, 8); // 8x vertical exaggeration: the reservoir is thin
    actor->GetProperty()->SetSpecular(0.2);
    vtkNew<vtkRenderWindow> win;
    win->SetSize(800, 600);
    win->SetMultiSamples(0);
    vtkNew<vtkRenderer> ren;
    ren->SetBackground(0.08, 0.09, 0.12);
    win->AddRenderer(ren);
    ren->AddActor(actor);
    strata_test::FrameReekScene(ren, actor, 1.3);
    win->Render();
    written.push_back(Save(win, out + "/strata-horizons-reek.png"));
  }
  // --- Scene 3: three overlapping volumes (the Bucky ball and two analytic volumes).
  {
    std::string dataDir;
    for (size_t a = 0; a < dataDirs.size() && dataDir.empty(); ++a)
    {
      if (std::ifstream(dataDirs[a] + "/volumes/bucky.raw"))
      {
        dataDir = dataDirs[a];
      }
    }
    vtkNew<vtkRenderWindow> win;
    win->SetSize(800, 600);
    win->SetMultiSamples(0);
    vtkNew<vtkRenderer> ren;
    ren->SetBackground(0.08, 0.09, 0.12);
    win->AddRenderer(ren);
    std::vector<std::pair<vtkSmartPointer<vtkImageData>, vtkSmartPointer<vtkVolume>>> inputs;
    if (dataDir.empty() || !strata_test::AddVolumeDemoScene(ren, dataDir, inputs))
    {
      std::cerr
        << "volumes/bucky.raw not found in the data directories given; skipping that image.\n";
    }
    else
    {
      win->Render();
      written.push_back(Save(win, out + "/strata-volumes.png"));
    }
  }

  // --- Scene 4: a real CT volume (the tooth) at full resolution, as its factor-4 volume alone,
  // and as that volume plus points where it is wrong (hybrid point + volume rendering).
  {
    std::string why;
    vtkSmartPointer<vtkImageData> tooth = strata_test::LoadRealVolume("tooth", paths, why);
    if (!tooth)
    {
      std::cerr << "tooth volume: " << why << "; skipping the hybrid images.\n";
    }
    else
    {
      vtkNew<vtkHybridVolumeFilter> hybridFilter;
      hybridFilter->SetInputData(tooth);
      hybridFilter->SetFactor(4, 4, 4);
      hybridFilter->SetFilterToCubic();
      hybridFilter->SetThreshold(HybridThreshold);
      hybridFilter->Update();
      vtkNew<vtkRenderWindow> win;
      win->SetSize(600, 600);
      win->SetMultiSamples(0);
      vtkNew<vtkRenderer> ren;
      ren->SetBackground(0.08, 0.09, 0.12);
      win->AddRenderer(ren);
      vtkNew<vtkVolume> volume;
      volume->SetProperty(strata_test::MakeRealVolumeProperty("tooth"));
      ren->AddVolume(volume);
      vtkNew<vtkMultiVolumeRayCastMapper> full, low;
      vtkNew<vtkHybridVolumeMapper> hybrid;
      full->SetInputData(tooth);
      low->SetInputData(hybridFilter->GetLowResolutionOutput());
      hybrid->SetInputConnection(hybridFilter->GetOutputPort(0));
      hybrid->SetPointsInputConnection(hybridFilter->GetOutputPort(1));
      full->SetSampleDistance(0.5);
      low->SetSampleDistance(0.5);
      hybrid->GetVolumeMapper()->SetSampleDistance(0.5);
      hybrid->SetPointShape(vtkHybridVolumeMapper::PointShapes::GaussianSplats);
      volume->SetMapper(full);
      double dir[3], up[3];
      strata_test::RealVolumeView("tooth", dir, up);
      strata_test::FrameVolumes(ren, { { tooth.Get(), volume.Get() } }, dir, up, 0.85);
      const std::pair<vtkVolumeMapper*, const char*> views[3] = {
        { full, "full" }, { low, "low" }, { hybrid, "hybrid" }
      };
      vtkNew<vtkImageAppend> strip; // the three side by side
      strip->SetAppendAxis(0);
      for (const auto& view : views)
      {
        volume->SetMapper(view.first);
        win->Render();
        written.push_back(Save(win, out + "/strata-tooth-" + view.second + ".png"));
        vtkNew<vtkWindowToImageFilter> grab;
        grab->SetInput(win);
        grab->ReadFrontBufferOff();
        grab->Update();
        vtkNew<vtkImageData> copy;
        copy->DeepCopy(grab->GetOutput());
        strip->AddInputData(copy);
      }
      vtkNew<vtkPNGWriter> stripWriter;
      stripWriter->SetInputConnection(strip->GetOutputPort());
      stripWriter->SetFileName((out + "/strata-tooth-compare.png").c_str());
      stripWriter->Write();
      written.push_back(out + "/strata-tooth-compare.png");
      std::cerr << "tooth: " << tooth->GetDimensions()[0] << "x" << tooth->GetDimensions()[1] << "x"
                << tooth->GetDimensions()[2] << " voxels; factor 4 -> "
                << hybridFilter->GetLowResolutionOutput()->GetNumberOfPoints()
                << " low-resolution voxels + "
                << hybridFilter->GetPointsOutput()->GetNumberOfPoints() << " points (|error| > "
                << HybridThreshold << ")\n";
    }
  }

  for (const auto& path : written)
  {
    std::cout << path << "\n";
  }
  return written.empty() ? 1 : 0;
}
