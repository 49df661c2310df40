// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Benchmark of the hybrid point + volume representation (vtkHybridVolumeFilter +
// vtkHybridVolumeMapper), the paper's Figure 2 and 4 tables redone: for each real volume, the
// full-resolution rendering (vtkMultiVolumeRayCastMapper) is the reference; the plain
// down-sampled volumes (factors 2 and 4, cubic) and the hybrids (factor, error threshold, error
// grid, squares or splats) are rendered from the same view and measured against it: points,
// bytes on disk (strata::HybridVolumeFile: header + float low-resolution volume + 16 bytes per
// point), ms per frame, RMS and 99th-percentile pixel error. The headline compares at equal
// bytes: every factor-4 hybrid against the original resampled (cubic, vtkImageResample) to a
// float volume of the same bytes; "hybrid-budget" rows also fill exactly the bytes of the plain
// factor-2 (or 4) volume with the N largest errors of a factor-4 (or 8) one. Usage:
//   BenchHybrid header            -> the CSV header
//   BenchHybrid run <data>        -> the rows of one data set (tooth, engine, bonsai, bucky)
//   BenchHybrid report <csv> <png> -> the equal-bytes table and the error-vs-bytes plot
// Images 384 x 384, sample distance 0.5 voxel; ms per frame: median of 3 after one warm-up.
// The volumes are read as BenchVolume reads them (-D <data>, --shared-data <shared>).
#include "StrataBenchChart.h"
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataRealVolumes.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "StrataHybridVolumeFile.h"
#include "vtkChart.h"
#include "vtkHybridVolumeFilter.h"
#include "vtkHybridVolumeMapper.h"
#include "vtkImageData.h"
#include "vtkImageResample.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlotLine.h"
#include "vtkPlotPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
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
#include <vector>

namespace
{
const int Size = 384;
const char* Header = "case,method,factor,filter,threshold,error_grid,shape,points,bytes,ms_per_"
                     "frame,rms_error,p99_error,equal_bytes_as,note";

struct Measure
{
  double Ms = 0, Rms = 0, P99 = 0;
};

// Median frame time of 3 after a warm-up, and the image's error against `reference`.
Measure Render(vtkRenderWindow* win,
  vtkVolume* volume,
  vtkVolumeMapper* mapper,
  const std::vector<unsigned char>* reference,
  std::vector<unsigned char>* image = nullptr)
{
  volume->SetMapper(mapper);
  win->Render();
  std::vector<double> ms;
  for (int i = 0; i < 3; ++i)
  {
    const auto t0 = std::chrono::steady_clock::now();
    win->Render();
    win->WaitForCompletion();
    ms.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  Measure m;
  m.Ms = ms[1];
  const auto rgb = strata_test::ReadRGB(win);
  if (image)
    *image = rgb;
  if (reference)
  {
    std::vector<int> err(rgb.size());
    double sum = 0.0;
    for (size_t i = 0; i < rgb.size(); ++i)
    {
      err[i] = std::abs(int(rgb[i]) - int((*reference)[i]));
      sum += double(err[i]) * err[i];
    }
    m.Rms = std::sqrt(sum / std::max<size_t>(1, rgb.size()));
    std::sort(err.begin(), err.end());
    m.P99 = err.empty() ? 0.0 : err[std::min(err.size() - 1, size_t(0.99 * err.size()))];
  }
  return m;
}

double Bytes(vtkImageData* low, vtkIdType points)
{
  return strata::HybridVolumeFile::HeaderSize + 4.0 * low->GetNumberOfPoints() +
         double(strata::HybridVolumeFile::PointSize) * points;
}

int Run(const std::string& name, const strata_test::TestPaths& paths)
{
  std::string why;
  vtkSmartPointer<vtkImageData> image = strata_test::LoadRealVolume(name, paths, why);
  if (!image)
  {
    std::printf("%s,,,,,,,,,,,,skipped: %s\n", name.c_str(), why.c_str());
    return 0;
  }
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  strata_test::MakeWindow(win, ren, Size, Size);
  vtkNew<vtkVolume> volume;
  volume->SetProperty(strata_test::MakeRealVolumeProperty(name));
  ren->AddVolume(volume);
  double dir[3], up[3];
  strata_test::RealVolumeView(name, dir, up);
  strata_test::FrameVolumes(ren, { { image.Get(), volume.Get() } }, dir, up, 0.85);
  const double sampleDistance = 0.5;

  vtkNew<vtkMultiVolumeRayCastMapper> full;
  full->SetInputData(image);
  full->SetSampleDistance(sampleDistance);
  std::vector<unsigned char> reference;
  const Measure f = Render(win, volume, full, nullptr, &reference);
  const double fullBytes = strata::HybridVolumeFile::HeaderSize + 4.0 * image->GetNumberOfPoints();
  std::printf("%s,full,1,,,,,0,%.0f,%.2f,0,0,,%dx%dx%d original\n",
    name.c_str(),
    fullBytes,
    f.Ms,
    image->GetDimensions()[0],
    image->GetDimensions()[1],
    image->GetDimensions()[2]);
  std::fflush(stdout);

  // One filter per (factor, grid, threshold or budget); the mapper draws its outputs.
  vtkPiecewiseFunction* opacity = volume->GetProperty()->GetScalarOpacity(0);
  auto build = [&](int factor, int grid, double threshold, vtkIdType budget, bool weighted)
  {
    auto filter = vtkSmartPointer<vtkHybridVolumeFilter>::New();
    filter->SetInputData(image);
    filter->SetFactor(factor, factor, factor);
    filter->SetFilterToCubic();
    filter->SetErrorGridStep(grid, grid, grid);
    filter->SetThreshold(threshold);
    filter->SetPointBudget(budget);
    filter->SetOpacityFunction(weighted ? opacity : nullptr);
    filter->Update();
    return filter;
  };
  vtkNew<vtkMultiVolumeRayCastMapper> plain;
  plain->SetSampleDistance(sampleDistance);
  vtkNew<vtkHybridVolumeMapper> hybrid;
  hybrid->GetVolumeMapper()->SetSampleDistance(sampleDistance);
  std::map<int, double> plainBytes;
  for (int factor : { 2, 4, 8 })
  {
    auto filter = build(factor, 1, 1e30, 0, false);
    vtkImageData* low = filter->GetLowResolutionOutput();
    plain->SetInputData(low);
    const Measure m = Render(win, volume, plain, &reference);
    plainBytes[factor] = Bytes(low, 0);
    std::printf("%s,low-resolution,%d,cubic,,,,0,%.0f,%.2f,%.4f,%.1f,,\n",
      name.c_str(),
      factor,
      plainBytes[factor],
      m.Ms,
      m.Rms,
      m.P99);
    std::fflush(stdout);
  }
  auto hybridRows = [&](const char* method,
                      int factor,
                      int grid,
                      double threshold,
                      vtkIdType budget,
                      const std::string& note)
  {
    const bool weighted = std::string(method).find("-tf") != std::string::npos;
    auto filter = build(factor, grid, threshold, budget, weighted);
    vtkImageData* low = filter->GetLowResolutionOutput();
    vtkPolyData* points = filter->GetPointsOutput();
    hybrid->SetInputData(low);
    hybrid->SetPointsInputData(points);
    for (auto shape : { vtkHybridVolumeMapper::PointShapes::Squares,
           vtkHybridVolumeMapper::PointShapes::GaussianSplats })
    {
      hybrid->SetPointShape(shape);
      const Measure m = Render(win, volume, hybrid, &reference);
      std::printf("%s,%s,%d,cubic,%g,%d,%s,%lld,%.0f,%.2f,%.4f,%.1f,,%s\n",
        name.c_str(),
        method,
        factor,
        budget > 0 ? 0.0 : threshold,
        grid,
        shape == vtkHybridVolumeMapper::PointShapes::Squares ? "squares" : "splats",
        static_cast<long long>(points->GetNumberOfPoints()),
        Bytes(low, points->GetNumberOfPoints()),
        m.Ms,
        m.Rms,
        m.P99,
        note.c_str());
      std::fflush(stdout);
    }
    // Plain down-sampling to the same bytes: the original resampled (cubic) by the factor that
    // makes its float volume as large as this hybrid's file.
    const double bytes = Bytes(low, points->GetNumberOfPoints());
    if (std::string(method) != "hybrid-budget" && factor == 4 && points->GetNumberOfPoints() >= 100)
    {
      const double r = std::cbrt(
        4.0 * image->GetNumberOfPoints() / (bytes - strata::HybridVolumeFile::HeaderSize));
      vtkNew<vtkImageResample> resample;
      resample->SetInputData(image);
      resample->SetMagnificationFactors(1.0 / r, 1.0 / r, 1.0 / r);
      resample->SetInterpolationModeToCubic();
      resample->Update();
      plain->SetInputData(resample->GetOutput());
      const Measure m = Render(win, volume, plain, &reference);
      std::printf("%s,low-resolution-equal-bytes,%.3f,cubic,,,,0,%.0f,%.2f,%.4f,%.1f,%s/%g/"
                  "%d,resampled by 1/%.3f "
                  "per axis to the bytes of the factor-4 %s with threshold %g and error grid %d\n",
        name.c_str(),
        r,
        Bytes(resample->GetOutput(), 0),
        m.Ms,
        m.Rms,
        m.P99,
        method,
        threshold,
        grid,
        r,
        method,
        threshold,
        grid);
      std::fflush(stdout);
    }
  };
  for (int factor : { 2, 4 })
    for (int grid : { 1, 2 })
      for (double threshold : { 16.0, 32.0, 64.0 })
        hybridRows("hybrid", factor, grid, threshold, 0, "ranked by |error|");
  // Ranked by the opacity the low-resolution volume misses under the transfer function.
  for (int grid : { 1, 2 })
    for (double threshold : { 0.01, 0.03, 0.1 })
      hybridRows("hybrid-tf", 4, grid, threshold, 0, "ranked by missing opacity");
  // Equal bytes: the points fill exactly the difference to the plain volume one factor finer.
  for (int factor : { 4, 8 })
  {
    auto probe = build(factor, 1, 1e30, 0, false);
    const double room = plainBytes[factor / 2] - Bytes(probe->GetLowResolutionOutput(), 0);
    const vtkIdType budget = static_cast<vtkIdType>(room / strata::HybridVolumeFile::PointSize);
    for (const char* method : { "hybrid-budget", "hybrid-tf-budget" })
      hybridRows(method,
        factor,
        1,
        0.0,
        std::max<vtkIdType>(budget, 1),
        "point budget " + std::to_string(budget) + ": bytes of the plain factor-" +
          std::to_string(factor / 2) + " volume");
  }
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

double Num(const std::map<std::string, std::string>& r, const std::string& k)
{
  auto it = r.find(k);
  return it == r.end() || it->second.empty() ? -1.0 : std::atof(it->second.c_str());
}

std::string Str(const std::map<std::string, std::string>& r, const std::string& k)
{
  auto it = r.find(k);
  return it == r.end() ? std::string() : it->second;
}

int Report(const std::string& csv, const std::string& png)
{
  const auto rows = ReadCsv(csv);
  std::vector<std::string> datasets;
  for (const auto& r : rows)
    if (std::find(datasets.begin(), datasets.end(), Str(r, "case")) == datasets.end() &&
        Num(r, "bytes") > 0)
      datasets.push_back(Str(r, "case"));
  // Headline: each factor-4 hybrid against the plain volume resampled to its bytes (the better
  // of squares and splats), then the point budgets that fill a plain factor-2 / 4 volume's bytes.
  std::printf("\nEqual bytes: factor-4 hybrids (cubic) against the original resampled (cubic) to "
              "the same bytes\n");
  std::printf("%-8s %-22s %10s %8s %11s %11s %8s\n",
    "data",
    "hybrid (method/threshold/grid)",
    "bytes",
    "points",
    "plain RMS",
    "hybrid RMS",
    "better");
  // Headline family: ranked by missing opacity on the error grid of step 2 (a point per 2^3
  // voxels); the volume counts when that family beats plain at every size it was measured at.
  int wins = 0;
  for (const auto& d : datasets)
  {
    int won = 0, compared = 0, familyWon = 0, familyCompared = 0;
    for (const auto& p : rows)
    {
      if (Str(p, "case") != d || Str(p, "method") != "low-resolution-equal-bytes")
        continue;
      double hybridRms = -1, points = 0;
      std::string key = Str(p, "equal_bytes_as");
      for (const auto& r : rows)
      {
        std::ostringstream k;
        k << Str(r, "method") << "/" << Num(r, "threshold") << "/" << Num(r, "error_grid");
        if (Str(r, "case") == d && int(Num(r, "factor")) == 4 && k.str() == key &&
            (hybridRms < 0 || Num(r, "rms_error") < hybridRms))
        {
          hybridRms = Num(r, "rms_error");
          points = Num(r, "points");
        }
      }
      if (hybridRms < 0)
        continue;
      ++compared;
      won += hybridRms < Num(p, "rms_error") ? 1 : 0;
      if (key.rfind("hybrid-tf/", 0) == 0 && key.size() > 2 && key.substr(key.size() - 2) == "/2")
      {
        ++familyCompared;
        familyWon += hybridRms < Num(p, "rms_error") ? 1 : 0;
      }
      std::printf("%-8s %-22s %10.0f %8.0f %11.3f %11.3f %8s\n",
        d.c_str(),
        key.c_str(),
        Num(p, "bytes"),
        points,
        Num(p, "rms_error"),
        hybridRms,
        hybridRms < Num(p, "rms_error") ? "hybrid" : "plain");
    }
    std::printf("%-8s hybrid better in %d of %d configurations; ranked by missing opacity, error "
                "grid 2: %d of %d\n",
      d.c_str(),
      won,
      compared,
      familyWon,
      familyCompared);
    wins += familyCompared > 0 && familyWon == familyCompared ? 1 : 0;
  }
  std::printf("hybrid (ranked by missing opacity, error grid 2) beats plain down-sampling at equal "
              "bytes at every size on %d of %zu volumes\n",
    wins,
    datasets.size());
  std::printf(
    "\nPoint budgets filling a plain volume's bytes (factor f hybrid vs plain factor f/2)\n");
  for (const auto& d : datasets)
    for (const auto& r : rows)
      if (Str(r, "case") == d && Str(r, "method").find("budget") != std::string::npos)
        for (const auto& p : rows)
          if (Str(p, "case") == d && Str(p, "method") == "low-resolution" &&
              Num(p, "factor") * 2 == Num(r, "factor"))
            std::printf("%-8s %-16s factor %g %-7s %8.0f points, %10.0f bytes: hybrid RMS %.3f, "
                        "plain factor %g RMS %.3f\n",
              d.c_str(),
              Str(r, "method").c_str(),
              Num(r, "factor"),
              Str(r, "shape").c_str(),
              Num(r, "points"),
              Num(r, "bytes"),
              Num(r, "rms_error"),
              Num(p, "factor"),
              Num(p, "rms_error"));

  strata_bench::Chart chart("Hybrid point + volume vs plain down-sampling, llvmpipe 384 x 384: RMS "
                            "error against full resolution vs bytes",
    15,
    "bytes on disk (log)",
    true,
    "RMS error, 8-bit units",
    false,
    true);
  const unsigned char colours[4][3] = {
    { 0, 114, 178 }, { 213, 94, 0 }, { 0, 158, 115 }, { 204, 121, 167 }
  };
  for (size_t d = 0; d < datasets.size(); ++d)
    for (int kind = 0; kind < 2; ++kind)
    {
      const std::string label = datasets[d] + (kind == 0 ? ", plain down-sampling" : ", hybrid");
      std::vector<std::pair<double, double>> pts;
      for (const auto& r : rows)
      {
        const std::string m = Str(r, "method");
        if (Str(r, "case") == datasets[d] && Num(r, "bytes") > 0 && Num(r, "rms_error") >= 0 &&
            (kind == 0 ? m.rfind("low-resolution", 0) == 0 : m.rfind("hybrid", 0) == 0))
          pts.emplace_back(Num(r, "bytes"), Num(r, "rms_error"));
      }
      std::sort(pts.begin(), pts.end());
      vtkPlot* plot =
        chart.Add(kind == 0 ? vtkChart::LINE : vtkChart::POINTS, label, pts, colours[d % 4]);
      if (auto* points = vtkPlotPoints::SafeDownCast(plot))
      {
        points->SetMarkerStyle(vtkPlotPoints::CIRCLE);
        points->SetMarkerSize(8);
      }
      if (auto* line = vtkPlotLine::SafeDownCast(plot))
        line->SetMarkerStyle(vtkPlotPoints::SQUARE);
    }
  chart.Write(png);
  return 0;
}
}

int main(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::TakeFromArguments(argc, argv);
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "header")
  {
    std::printf("%s\n", Header);
    return 0;
  }
  if (mode == "run" && argc > 2)
    return Run(argv[2], paths);
  if (mode == "report" && argc > 3)
    return Report(argv[2], argv[3]);
  std::cerr << "usage: BenchHybrid header | run <data> | report <csv> <png>\n";
  return 2;
}
