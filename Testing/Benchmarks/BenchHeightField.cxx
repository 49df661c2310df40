// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Benchmark of the stacked height-field ray caster against what a VTK user does today (each
// grid as a triangle mesh through vtkPolyDataMapper). One process per (case, method), so that
// peak RSS belongs to that method alone; scripts/bench heightfield runs them all and collects
// the CSV. Usage:
//   BenchHeightField frame <points-per-horizon> <raycast|mesh> [<w>x<h>] [--stage <s>]
//                      -> one CSV line: case, method, wall ms per frame, peak RSS MB, GPU ms
//                         (GL_TIME_ELAPSED; -1 without timer queries), render-thread CPU ms,
//                         viewport width and height, stage (StrataFrameTimer.h): the ray
//                         caster's stage in use (fragment or compute; --stage fragment, compute
//                         or auto, default fragment), vtk for the mesh
//   BenchHeightField accuracy <points-per-horizon>             -> step vs error vs ms lines
// STRATA_BENCH_TILE and STRATA_BENCH_STEP override the mapper's tile size and linear-search step
// in `frame` runs with the ray caster; `accuracy` writes its id images to `-T <dir>` (default the
// current directory, StrataTestPaths.h).
#include "StrataFrameTimer.h"
#include "StrataHeightFieldScenes.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

using strata_test::PeakRssMB;

namespace
{
// The user's mesh: points (x, y, z) and two triangles per valid cell, as vtkPolyData.
vtkSmartPointer<vtkPolyData> MeshOf(vtkImageData* image)
{
  int d[3];
  image->GetDimensions(d);
  auto* h = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToFloat();
  pts->SetNumberOfPoints(vtkIdType(d[0]) * d[1]);
  const double* o = image->GetOrigin();
  const double* s = image->GetSpacing();
  for (int j = 0; j < d[1]; ++j)
    for (int i = 0; i < d[0]; ++i)
    {
      const vtkIdType id = vtkIdType(j) * d[0] + i;
      pts->SetPoint(id, o[0] + i * s[0], o[1] + j * s[1], h->GetValue(id));
    }
  vtkNew<vtkCellArray> tris;
  tris->AllocateEstimate(2 * vtkIdType(d[0] - 1) * (d[1] - 1), 3);
  for (int j = 0; j + 1 < d[1]; ++j)
    for (int i = 0; i + 1 < d[0]; ++i)
    {
      const vtkIdType a = vtkIdType(j) * d[0] + i, b = a + 1, c = a + d[0], e = c + 1;
      if (std::isnan(h->GetValue(a)) || std::isnan(h->GetValue(b)) || std::isnan(h->GetValue(c)) ||
          std::isnan(h->GetValue(e)))
        continue;
      const vtkIdType t1[3] = { a, b, e }, t2[3] = { a, e, c };
      tris->InsertNextCell(3, t1);
      tris->InsertNextCell(3, t2);
    }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetPolys(tris);
  return poly;
}

void PlaceCamera(vtkRenderer* ren, double extent, int view)
{
  vtkCamera* c = ren->GetActiveCamera();
  const double cx = 0.5 * extent, cy = 0.375 * extent;
  const double a = 0.6 + 1.1 * view;
  c->SetFocalPoint(cx, cy, -420);
  c->SetPosition(cx - 1.1 * extent * std::cos(a), cy - 1.1 * extent * std::sin(a), 0.6 * extent);
  c->SetViewUp(0, 0, 1);
  ren->ResetCameraClippingRange();
}

/// Median times of two frames in each of `views` views, after each view's first frame
/// (uploads, shader compile).
strata_bench::FrameTime MedianTimes(vtkRenderWindow* win,
  vtkRenderer* ren,
  double extent,
  int views)
{
  std::vector<strata_bench::FrameTime> frames;
  for (int v = 0; v < views; ++v)
  {
    PlaceCamera(ren, extent, v);
    win->Render();
    for (int r = 0; r < 2; ++r)
      frames.push_back(strata_bench::FrameTimer::Time(win));
  }
  return strata_bench::FrameTimer::Median(frames);
}

double MedianMs(vtkRenderWindow* win, vtkRenderer* ren, double extent, int views)
{
  return MedianTimes(win, ren, extent, views).WallMs;
}
}

int main(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::TakeFromArguments(argc, argv);
  // --stage <fragment|compute|auto>, taken out of the arguments.
  auto stage = vtkStackedHeightFieldMapper::Stages::Fragment;
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--stage") == 0)
    {
      const std::string value = argv[i + 1];
      stage = value == "compute" ? vtkStackedHeightFieldMapper::Stages::Compute
              : value == "auto"  ? vtkStackedHeightFieldMapper::Stages::Auto
                                 : vtkStackedHeightFieldMapper::Stages::Fragment;
      for (int j = i; j + 2 <= argc; ++j)
        argv[j] = argv[j + 2];
      argc -= 2;
      break;
    }
  if (argc < 3)
  {
    std::cerr << "usage: BenchHeightField frame <points> <raycast|mesh> [<width>x<height>] "
                 "[--stage fragment|compute|auto] | accuracy <points>\n";
    return 2;
  }
  const std::string mode = argv[1];
  const long points = std::atol(argv[2]);
  const int nx = static_cast<int>(std::lround(std::sqrt(points * 4.0 / 3.0)));
  const int ny = static_cast<int>(points / nx);
  const double spacing = 2000.0 / nx; // a 2 km x 1.5 km survey whatever the resolution
  auto horizons = strata_test::MakeDemoHorizons(nx, ny, 0, 0, spacing, 0);
  // The viewport of `frame` runs (512 x 512 by default; 1920x1080 as a data-center GPU's view).
  int width = 512, height = 512;
  if (mode == "frame" && argc > 4 && std::sscanf(argv[4], "%dx%d", &width, &height) != 2)
  {
    std::cerr << "BenchHeightField: the viewport is <width>x<height>, not " << argv[4] << "\n";
    return 2;
  }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  strata_test::MakeWindow(win, ren, width, height);
  const std::string label = "3x" + std::to_string((points + 500000) / 1000000) + "M";

  if (mode == "frame")
  {
    const std::string method = argc > 3 ? argv[3] : "raycast";
    if (method == "mesh")
    {
      for (auto& h : horizons)
      {
        vtkNew<vtkPolyDataMapper> m;
        m->SetInputData(MeshOf(h));
        m->ScalarVisibilityOff();
        vtkNew<vtkActor> a;
        a->SetMapper(m);
        ren->AddActor(a);
      }
      horizons.clear(); // the user keeps only the meshes
    }
    vtkNew<vtkStackedHeightFieldMapper> m;
    if (method != "mesh")
    {
      m->SetStage(stage);
      for (auto& h : horizons)
        m->AddInputDataObject(h);
      if (const char* tile = std::getenv("STRATA_BENCH_TILE"))
        m->SetTileSize(std::atoi(tile));
      if (const char* step = std::getenv("STRATA_BENCH_STEP"))
        m->SetLinearSearchStep(std::atof(step));
      vtkNew<vtkActor> a;
      a->SetMapper(m);
      ren->AddActor(a);
    }
    const strata_bench::FrameTime t = MedianTimes(win, ren, 2000.0, 3);
    // The ray caster's stage in use; the mesh is VTK's.
    const char* used = method == "mesh" ? "vtk"
                       : m->GetStageInUse() == vtkStackedHeightFieldMapper::Stages::Compute
                         ? "compute"
                         : "fragment";
    std::printf("%s,%s,%.1f,%.0f,%.2f,%.2f,%d,%d,%s\n",
      label.c_str(),
      method.c_str(),
      t.WallMs,
      PeakRssMB(),
      t.GpuMs,
      t.CpuMs,
      width,
      height,
      used);
    return 0;
  }
  // Accuracy: linear-search step against the fraction of pixels that differ from the exact
  // reference, with the time per frame, on two scenes. "smooth": the stack above, seen from the
  // benchmark's cameras; every crossing is at least a cell long, so even one sample per cell
  // finds it. "rough": the same stack plus +-2 cells of per-point noise, seen at 6 degrees above
  // the horizons: rays graze bumps that they enter and leave within one cell, which only a
  // finer linear search catches.
  vtkNew<vtkStackedHeightFieldMapper> m;
  vtkNew<vtkActor> a;
  a->SetMapper(m);
  ren->AddActor(a);
  for (const std::string scene : { "smooth", "rough" })
  {
    if (scene == "rough")
    {
      for (auto& h : horizons)
      {
        auto* z = vtkFloatArray::SafeDownCast(h->GetPointData()->GetScalars());
        for (vtkIdType i = 0; i < z->GetNumberOfValues(); ++i)
        {
          const uint32_t hash = static_cast<uint32_t>(i) * 2654435761u;
          z->SetValue(i, z->GetValue(i) + float(spacing * 2.0 * ((hash >> 8) / 8388608.0 - 1.0)));
        }
        z->Modified();
      }
    }
    m->RemoveAllInputConnections(0);
    for (auto& h : horizons)
      m->AddInputDataObject(h);
    for (double step : { 1.0, 0.5, 0.25, 0.125, 0.0625 })
    {
      m->SetLinearSearchStep(step);
      double ms;
      if (scene == "smooth")
      {
        ms = MedianMs(win, ren, 2000.0, 2);
        PlaceCamera(ren, 2000.0, 0);
      }
      else
      {
        vtkCamera* c = ren->GetActiveCamera();
        c->SetFocalPoint(1000, 750, -300);
        c->SetPosition(1000 - 1600, 750 - 900, -300 + 1836 * std::tan(6.0 * std::acos(-1.0) / 180));
        c->SetViewUp(0, 0, 1);
        ren->ResetCameraClippingRange();
        win->Render();
        std::vector<double> t;
        for (int r = 0; r < 5; ++r)
        {
          const auto t0 = std::chrono::steady_clock::now();
          win->Render();
          win->WaitForCompletion();
          t.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
              .count());
        }
        std::sort(t.begin(), t.end());
        ms = t[t.size() / 2];
      }
      auto r =
        strata_test::CompareWithReference(win, ren, a, m, horizons, "bench-" + scene, paths.Output);
      std::printf("%s,%s,%g,%.1f,%.5f,%ld,%.0f\n",
        label.c_str(),
        scene.c_str(),
        step,
        ms,
        r.MismatchFraction(),
        r.Covered,
        r.DepthBoundViolations);
      std::fflush(stdout);
    }
  }
  return 0;
}
