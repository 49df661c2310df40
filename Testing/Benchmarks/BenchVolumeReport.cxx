// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// BenchVolume report: the summary tables and the RMS-vs-time plot from bench-results/volume.csv
// (the rows the other sub-modes of BenchVolume.cxx print).
#include "BenchVolumeReport.h"

#include "StrataBenchChart.h"
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataMultiVolumeReferenceIntegrator.h"
#include "StrataRealVolumes.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeBSPTree.h"
#include "StrataVolumeScenes.h"
#include "vtkAxis.h"
#include "vtkCamera.h"
#include "vtkChartXY.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNrrdReader.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlotPoints.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkXMLImageDataReader.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h> // For getpid
#include <vector>
#include <vtksys/SystemTools.hxx>

namespace
{
const double NaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::map<std::string, std::string>> ReadCsv(const std::string& path)
{
  std::vector<std::map<std::string, std::string>> rows;
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> names;
  auto split = [](const std::string& s)
  {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string f;
    while (std::getline(ss, f, ','))
      out.push_back(f);
    if (!s.empty() && s.back() == ',')
      out.emplace_back();
    return out;
  };
  while (std::getline(in, line))
  {
    if (line.empty())
      continue;
    auto fields = split(line);
    if (names.empty())
    {
      names = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < names.size(); ++i)
      row[names[i]] = i < fields.size() ? fields[i] : "";
    rows.push_back(row);
  }
  return rows;
}

double Number(const std::map<std::string, std::string>& row, const std::string& key)
{
  auto it = row.find(key);
  return it == row.end() || it->second.empty() ? NaN : std::atof(it->second.c_str());
}

std::string Get(const std::map<std::string, std::string>& row, const std::string& key)
{
  auto it = row.find(key);
  return it == row.end() ? std::string() : it->second;
}

/// RMS error against ms per frame, one series per (data set, classification), as a PNG.
void Plot(const std::vector<std::map<std::string, std::string>>& rows, const std::string& png)
{
  strata_bench::Chart chart(
    "vtkMultiVolumeRayCastMapper on llvmpipe, 256 x 256: RMS error against the "
    "reference vs frame time, every setting",
    16,
    "ms per frame (log)",
    true,
    "RMS error against the reference, 8-bit units (log)",
    true,
    false);

  std::vector<std::string> datasets;
  for (const auto& r : rows)
  {
    const std::string c = Get(r, "case");
    if (c.rfind("accuracy-", 0) == 0 && !std::isnan(Number(r, "rms_error")) &&
        std::find(datasets.begin(), datasets.end(), c) == datasets.end())
      datasets.push_back(c);
  }
  const unsigned char colours[4][3] = {
    { 0, 114, 178 }, { 213, 94, 0 }, { 0, 158, 115 }, { 204, 121, 167 }
  };
  const int markers[3] = { vtkPlotPoints::CIRCLE, vtkPlotPoints::SQUARE, vtkPlotPoints::DIAMOND };
  const char* kinds[3] = { "post", "pre", "pre-approx" };
  double range[4] = { VTK_DOUBLE_MAX, 0.0, VTK_DOUBLE_MAX, 0.0 };
  for (size_t d = 0; d < datasets.size(); ++d)
    for (int k = 0; k < 3; ++k)
    {
      const std::string label = datasets[d].substr(9) + ", " + kinds[k];
      std::vector<std::pair<double, double>> pts;
      for (const auto& r : rows)
      {
        const double ms = Number(r, "ms_per_frame"), rms = Number(r, "rms_error");
        if (Get(r, "case") == datasets[d] && Get(r, "classification") == kinds[k] && ms > 0 &&
            rms > 0)
        {
          pts.emplace_back(ms, rms);
          range[0] = std::min(range[0], ms);
          range[1] = std::max(range[1], ms);
          range[2] = std::min(range[2], rms);
          range[3] = std::max(range[3], rms);
        }
      }
      if (auto* points =
            vtkPlotPoints::SafeDownCast(chart.Add(vtkChart::POINTS, label, pts, colours[d % 4])))
      {
        points->SetMarkerStyle(markers[k]);
        points->SetMarkerSize(9);
      }
    }
  // The blend-mode knob: one series per data set and mode (crosses), both sample distances.
  const char* blendModes[6] = {
    "composite", "maximum", "minimum", "average", "additive", "isosurface"
  };
  const unsigned char blendColours[6][3] = { { 0, 0, 0 },
    { 230, 159, 0 },
    { 86, 180, 233 },
    { 240, 228, 66 },
    { 0, 114, 178 },
    { 213, 94, 0 } };
  for (const auto& r0 : rows)
  {
    const std::string c = Get(r0, "case");
    if (c.rfind("blend-", 0) != 0 || Get(r0, "blend_mode") != "composite" ||
        Get(r0, "sample_distance") != "1.000")
      continue;
    for (int m = 0; m < 6; ++m)
    {
      std::vector<std::pair<double, double>> pts;
      for (const auto& r : rows)
      {
        const double ms = Number(r, "ms_per_frame"), rms = Number(r, "rms_error");
        if (Get(r, "case") == c && Get(r, "blend_mode") == blendModes[m] && ms > 0 && rms > 0)
        {
          pts.emplace_back(ms, rms);
          range[0] = std::min(range[0], ms);
          range[1] = std::max(range[1], ms);
          range[2] = std::min(range[2], rms);
          range[3] = std::max(range[3], rms);
        }
      }
      if (auto* points = vtkPlotPoints::SafeDownCast(
            chart.Add(vtkChart::POINTS, c.substr(6) + ", " + blendModes[m], pts, blendColours[m])))
      {
        points->SetMarkerStyle(vtkPlotPoints::CROSS);
        points->SetMarkerSize(9);
      }
    }
  }
  // The translucent-layers knob (triangles): K = 1 .. 7 layers for six planes.
  std::vector<std::pair<double, double>> layerPoints;
  for (const auto& r : rows)
  {
    const double ms = Number(r, "ms_per_frame"), rms = Number(r, "rms_error");
    if (Get(r, "case") == "layers-blob" && ms > 0 && rms > 0)
    {
      layerPoints.emplace_back(ms, rms);
      range[0] = std::min(range[0], ms);
      range[1] = std::max(range[1], ms);
      range[2] = std::min(range[2], rms);
      range[3] = std::max(range[3], rms);
    }
  }
  const unsigned char layerColour[3] = { 120, 120, 120 };
  if (auto* points = vtkPlotPoints::SafeDownCast(chart.Add(vtkChart::POINTS,
        "two blobs, 6 translucent planes, layers 1-7 (128^2)",
        layerPoints,
        layerColour)))
  {
    points->SetMarkerStyle(vtkPlotPoints::PLUS);
    points->SetMarkerSize(9);
  }
  if (range[1] > 0.0)
  {
    // Margins so that no point sits on the frame, and room above the points for the legend.
    vtkAxis* x = chart.GetChart()->GetAxis(vtkAxis::BOTTOM);
    vtkAxis* y = chart.GetChart()->GetAxis(vtkAxis::LEFT);
    x->SetBehavior(vtkAxis::FIXED);
    y->SetBehavior(vtkAxis::FIXED);
    x->SetUnscaledRange(range[0] / 1.25, range[1] * 1.25);
    y->SetUnscaledRange(
      range[2] / 1.25, range[3] * std::max(3.0, std::pow(range[3] / range[2], 0.6)));
  }
  chart.Write(png);
}

/// The `components` rows: ms in core and paged per mode, their ratio and the paged image's RMS.
void ComponentsTable(const std::vector<std::map<std::string, std::string>>& rows)
{
  const std::regex rms("RMS to the in-core image ([0-9.e-]+); (\\d+) bricks resident");
  bool header = false;
  for (const auto& paged : rows)
  {
    const std::string method = Get(paged, "method");
    const size_t at = method.rfind("-paged");
    if (Get(paged, "case").rfind("components-", 0) != 0 || at == std::string::npos)
      continue;
    const std::string base = method.substr(0, at);
    const std::map<std::string, std::string>* inCore = nullptr;
    for (const auto& r : rows)
      if (Get(r, "case") == Get(paged, "case") && Get(r, "method") == base + "-in-core")
        inCore = &r;
    std::smatch m;
    const std::string note = Get(paged, "note");
    const bool figures = std::regex_search(note, m, rms);
    if (!header)
      std::printf("\nComponents in core (float channels) and paged (a volume of one scalar per "
                  "component in the atlas)\n%-18s %-22s %10s %10s %8s %10s %9s\n",
        "case",
        "mode",
        "in_core_ms",
        "paged_ms",
        "ratio",
        "paged_rms",
        "resident");
    header = true;
    const double a = inCore ? Number(*inCore, "ms_per_frame") : NaN,
                 b = Number(paged, "ms_per_frame");
    std::printf("%-18s %-22s %10.1f %10.1f %8.2f %10s %9s\n",
      Get(paged, "case").c_str(),
      base.c_str(),
      a,
      b,
      b / a,
      figures ? m[1].str().c_str() : "-",
      figures ? m[2].str().c_str() : "-");
  }
}

/// The lean atlas: bytes per brick, slots under one budget and the error that budget leaves,
/// by scalar type (the `storage` rows; the figures are read back from their notes).
void StorageTable(const std::vector<std::map<std::string, std::string>>& rows)
{
  const std::regex figures("atlas (\\w+); (\\d+) bytes per brick; budget ([0-9.]+) MiB holds "
                           "(\\d+) slots; (\\d+) bricks resident \\(every brick: (\\d+)\\); RMS "
                           "to the float32 image with room for every brick ([0-9.e-]+)");
  bool header = false;
  for (const auto& r : rows)
  {
    std::smatch m;
    const std::string note = Get(r, "note");
    if (Get(r, "case").rfind("storage-", 0) != 0 || !std::regex_search(note, m, figures))
      continue;
    if (!header)
      std::printf("\nAtlas bytes per brick by scalar type (one budget; RMS against float32 with "
                  "room for every brick)\n%-24s %-24s %-8s %14s %10s %6s %9s %9s %9s\n",
        "case",
        "method",
        "atlas",
        "bytes_per_brick",
        "budget_mib",
        "slots",
        "resident",
        "rms",
        "ms");
    header = true;
    std::printf("%-24s %-24s %-8s %14s %10s %6s %9s %9s %9s\n",
      Get(r, "case").c_str(),
      Get(r, "method").c_str(),
      m[1].str().c_str(),
      m[2].str().c_str(),
      m[3].str().c_str(),
      m[4].str().c_str(),
      (m[5].str() + "/" + m[6].str()).c_str(),
      m[7].str().c_str(),
      Get(r, "ms_per_frame").c_str());
  }
}

/// The brick atlas's indirection against one plain texture (issue 16: atlas ms / no-atlas ms
/// <= 1.05 on llvmpipe), from the `frame` rows of the single and sparse cases.
void AtlasCostTable(const std::vector<std::map<std::string, std::string>>& rows,
  const std::vector<std::string>& cases)
{
  std::printf("\nBrick atlas vs one plain texture (ratio = strata ms / strata-no-atlas ms, "
              "target <= 1.05)\n");
  std::printf("%-24s %9s %12s %7s %5s\n", "case", "atlas_ms", "no_atlas_ms", "ratio", "met");
  for (const auto& c : cases)
  {
    if (c.rfind("single-", 0) != 0 && c.rfind("sparse-", 0) != 0)
      continue;
    double atlas = NaN, plain = NaN;
    for (const auto& r : rows)
      if (Get(r, "case") == c && !Get(r, "ms_per_frame").empty())
      {
        if (Get(r, "method") == "strata")
          atlas = Number(r, "ms_per_frame");
        else if (Get(r, "method") == "strata-no-atlas")
          plain = Number(r, "ms_per_frame");
      }
    const double ratio = atlas / plain;
    std::printf("%-24s %9.1f %12.1f %7.2f %5s\n",
      c.c_str(),
      atlas,
      plain,
      ratio,
      std::isnan(ratio) ? "-"
      : ratio <= 1.05   ? "yes"
                        : "NO");
  }
}

/// The compute stage against the fragment stage (issue 28: GPU time compute / fragment <= 0.1
/// on an H200, compute's GPU time <= 0.1 of vtkGPUVolumeRayCastMapper's, atlas / no atlas <=
/// 1.05), from the rows timed side by side in one run. On llvmpipe GL_TIME_ELAPSED undercounts
/// fragment work: compare the stages there by wall clock.
void StageTable(const std::vector<std::map<std::string, std::string>>& rows,
  const std::vector<std::string>& cases)
{
  std::printf("\nCompute vs fragment stage (ratios compute / fragment; vs VTK: compute / "
              "vtkGPUVolumeRayCastMapper)\n");
  std::printf("%-28s %-16s %9s %9s %10s %10s %9s\n",
    "case",
    "method",
    "wall_ms",
    "gpu_ms",
    "wall_ratio",
    "gpu_ratio",
    "gpu_vs_vtk");
  for (const auto& c : cases)
  {
    std::map<std::string, const std::map<std::string, std::string>*> by;
    for (const auto& r : rows)
      if (Get(r, "case") == c && !Get(r, "ms_per_frame").empty())
        by[Get(r, "method")] = &r;
    const auto* vtk =
      by.count("vtkGPUVolumeRayCastMapper") ? by["vtkGPUVolumeRayCastMapper"] : nullptr;
    for (const std::string base : { "strata", "strata-no-atlas" })
    {
      if (!by.count(base) || !by.count(base + "-compute"))
        continue;
      const auto& f = *by[base];
      const auto& k = *by[base + "-compute"];
      const double gpuVtk = vtk ? Number(k, "gpu_ms") / Number(*vtk, "gpu_ms") : NaN;
      std::printf("%-28s %-16s %9.1f %9.2f %10.2f %10.2f %9.2f\n",
        c.c_str(),
        base.c_str(),
        Number(k, "ms_per_frame"),
        Number(k, "gpu_ms"),
        Number(k, "ms_per_frame") / Number(f, "ms_per_frame"),
        Number(k, "gpu_ms") / Number(f, "gpu_ms"),
        gpuVtk);
    }
    if (by.count("strata-compute") && by.count("strata-no-atlas-compute"))
      std::printf("%-28s %-16s atlas / no atlas in the compute stage: wall %.2f, GPU %.2f\n",
        c.c_str(),
        "",
        Number(*by["strata-compute"], "ms_per_frame") /
          Number(*by["strata-no-atlas-compute"], "ms_per_frame"),
        Number(*by["strata-compute"], "gpu_ms") / Number(*by["strata-no-atlas-compute"], "gpu_ms"));
  }
}

/// Where a frame's time goes, for every row timed with the frame timer (StrataFrameTimer.h):
/// wall, GPU (GL_TIME_ELAPSED; llvmpipe undercounts fragment work) and render-thread CPU ms.
void FrameTimeTable(const std::vector<std::map<std::string, std::string>>& rows)
{
  std::printf("\nWhere a frame's time goes (wall, GPU by GL_TIME_ELAPSED, render thread's CPU)\n");
  std::printf("%-24s %-26s %10s %9s %9s %9s  %s\n",
    "case",
    "method",
    "viewport",
    "wall_ms",
    "gpu_ms",
    "cpu_ms",
    "stage");
  for (const auto& r : rows)
  {
    if (Get(r, "stage").empty())
      continue;
    const std::string viewport = Get(r, "width") + "x" + Get(r, "height");
    std::printf("%-24s %-26s %10s %9.1f %9.2f %9.2f  %s\n",
      Get(r, "case").c_str(),
      Get(r, "method").c_str(),
      viewport.c_str(),
      Number(r, "ms_per_frame"),
      Number(r, "gpu_ms"),
      Number(r, "cpu_ms"),
      Get(r, "stage").c_str());
  }
}
}

int Report(const std::string& csv, const std::string& png)
{
  const auto rows = ReadCsv(csv);
  std::set<std::string> seen;
  std::vector<std::string> cases;
  for (const auto& r : rows)
    if (seen.insert(Get(r, "case")).second)
      cases.push_back(Get(r, "case"));

  // 1. The settings grid, one table per data set: "ms / RMS" per rays-coherence column.
  const char* combos[5][2] = {
    { "1", "off" }, { "2", "off" }, { "2", "on" }, { "5", "off" }, { "5", "on" }
  };
  for (const auto& c : cases)
  {
    if (c.rfind("accuracy-", 0) != 0)
      continue;
    std::printf("\n%s: ms per frame, RMS error against the pixel-centre reference and (in\n"
                "brackets) against the reference through the same sub-pixel rays; 8-bit units\n",
      c.c_str());
    std::printf("%-11s %-14s %5s", "class", "order", "d");
    for (const auto& k : combos)
      std::printf(
        "  %20s", (std::string("rays ") + k[0] + (k[1][1] == 'n' ? " coherent" : "")).c_str());
    std::printf("\n");
    std::vector<std::string> keys;
    for (const auto& r : rows)
    {
      if (Get(r, "case") != c)
        continue;
      if (!Get(r, "note").empty() && Get(r, "classification").empty())
      {
        std::printf("  %s\n", Get(r, "note").c_str());
        continue;
      }
      const std::string key =
        Get(r, "classification") + "|" + Get(r, "order") + "|" + Get(r, "sample_distance");
      if (std::find(keys.begin(), keys.end(), key) != keys.end())
        continue;
      keys.push_back(key);
      std::printf("%-11s %-14s %5s",
        Get(r, "classification").c_str(),
        Get(r, "order").c_str(),
        Get(r, "sample_distance").c_str());
      for (const auto& k : combos)
      {
        std::string cell = "-";
        for (const auto& s : rows)
          if (Get(s, "case") == c &&
              Get(s, "classification") + "|" + Get(s, "order") + "|" + Get(s, "sample_distance") ==
                key &&
              Get(s, "rays") == k[0] && Get(s, "coherence") == k[1])
          {
            char b[64];
            std::snprintf(b,
              sizeof(b),
              "%.1f %.3f (%.3f)",
              Number(s, "ms_per_frame"),
              Number(s, "rms_error"),
              Number(s, "rms_error_same_rays"));
            cell = b;
          }
        std::printf("  %20s", cell.c_str());
      }
      std::printf("\n");
    }
  }

  // 1b. The blend-mode knob: each mode against the reference of that mode.
  for (const auto& c : cases)
  {
    if (c.rfind("blend-", 0) != 0)
      continue;
    std::printf("\n%s: blend modes, ms per frame and RMS error against the reference of the "
                "mode (8-bit units)\n%-11s %5s %9s %9s  %s\n",
      c.c_str(),
      "mode",
      "d",
      "ms",
      "rms",
      "note");
    for (const auto& r : rows)
      if (Get(r, "case") == c)
        std::printf("%-11s %5s %9s %9s  %s\n",
          Get(r, "blend_mode").c_str(),
          Get(r, "sample_distance").c_str(),
          Get(r, "ms_per_frame").c_str(),
          Get(r, "rms_error").c_str(),
          Get(r, "note").c_str());
  }

  // 2. Strata against VTK: time ratio against its target.
  std::printf("\nStrata vs vtkGPUVolumeRayCastMapper (same sample distance, property, camera; "
              "ratio = Strata ms / VTK ms)\n");
  std::printf("%-24s %6s %9s %9s %7s %8s %5s %12s %9s %9s %8s %8s  %s\n",
    "case",
    "size",
    "strata_ms",
    "vtk_ms",
    "ratio",
    "target",
    "met",
    "no_atlas_ms",
    "rms_str",
    "rms_vtk",
    "rss_str",
    "rss_vtk",
    "note");
  for (const auto& c : cases)
  {
    double target = NaN;
    if (c.rfind("single-", 0) == 0)
      target = 1.2;
    else if (c.rfind("sparse-", 0) == 0)
      target = 1.0 / 1.5;
    else if (c.rfind("multi", 0) == 0)
      target = 1.0;
    else
      continue;
    const std::map<std::string, std::string>* s = nullptr;
    const std::map<std::string, std::string>* v = nullptr;
    const std::map<std::string, std::string>* plain = nullptr;
    for (const auto& r : rows)
      if (Get(r, "case") == c)
      {
        const std::string m = Get(r, "method");
        if (m == "strata")
          s = &r;
        else if (m == "strata-no-atlas")
          plain = &r;
        else if (m == "vtkGPUVolumeRayCastMapper")
          v = &r;
      }
    auto fmt = [](double x, const char* f)
    {
      if (std::isnan(x))
        return std::string("-");
      char b[32];
      std::snprintf(b, sizeof(b), f, x);
      return std::string(b);
    };
    const double sm = s ? Number(*s, "ms_per_frame") : NaN,
                 vm = v ? Number(*v, "ms_per_frame") : NaN;
    const double ratio = sm / vm;
    std::string note;
    for (auto* r : { s, v, plain })
      if (r && Get(*r, "ms_per_frame").empty() && !Get(*r, "note").empty())
        note = Get(*r, "note");
    std::printf("%-24s %6s %9s %9s %7s %8s %5s %12s %9s %9s %8s %8s  %s\n",
      c.c_str(),
      s ? Get(*s, "width").c_str() : "-",
      fmt(sm, "%.1f").c_str(),
      fmt(vm, "%.1f").c_str(),
      fmt(ratio, "%.2f").c_str(),
      ("<= " + fmt(target, "%.2f")).c_str(),
      std::isnan(ratio) ? "-"
      : ratio <= target ? "yes"
                        : "NO",
      fmt(plain ? Number(*plain, "ms_per_frame") : NaN, "%.1f").c_str(),
      fmt(s ? Number(*s, "rms_error") : NaN, "%.3f").c_str(),
      fmt(v ? Number(*v, "rms_error") : NaN, "%.3f").c_str(),
      fmt(s ? Number(*s, "peak_rss_mb") : NaN, "%.0f").c_str(),
      fmt(v ? Number(*v, "peak_rss_mb") : NaN, "%.0f").c_str(),
      note.c_str());
  }

  AtlasCostTable(rows, cases);
  StageTable(rows, cases);
  FrameTimeTable(rows);
  StorageTable(rows);
  ComponentsTable(rows);
  bool layersHeader = false;
  for (const auto& r : rows)
  {
    if (Get(r, "case") != "layers-blob" || Get(r, "ms_per_frame").empty())
      continue;
    if (!layersHeader)
      std::printf("\nTranslucent layers (six planes of opacity 0.4 through two volumes, "
                  "128 x 128): ms per frame and RMS against the reference\n%-18s %9s %9s  %s\n",
        "method",
        "ms",
        "rms",
        "note");
    layersHeader = true;
    std::printf("%-18s %9s %9s  %s\n",
      Get(r, "method").c_str(),
      Get(r, "ms_per_frame").c_str(),
      Get(r, "rms_error").c_str(),
      Get(r, "note").c_str());
  }

  // 3. BSP rebuilds.
  std::printf("\nBSP rebuild (strata::VolumeBSPTree::Build; the paper reports 0.15 to 0.29 ms)\n");
  for (const auto& r : rows)
    if (Get(r, "case").rfind("bsp", 0) == 0)
      std::printf("%-10s %7.4f ms per build, %s fragments  (%s)\n",
        Get(r, "case").c_str(),
        Number(r, "ms_per_frame"),
        Get(r, "fragments").c_str(),
        Get(r, "note").c_str());

  // 4. Anything skipped.
  for (const auto& r : rows)
    if (Get(r, "ms_per_frame").empty() && !Get(r, "note").empty())
      std::printf("\nNOTE %s (%s): %s",
        Get(r, "case").c_str(),
        Get(r, "method").c_str(),
        Get(r, "note").c_str());
  std::printf("\n");
  Plot(rows, png);
  std::printf("\n%s\n", png.c_str());
  return 0;
}
