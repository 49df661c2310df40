// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// What draping a volume on a horizon costs and how far it is from the per-pixel ideal. A seismic-
// like field (a 40 m wavelength reflector pattern, dipping and warped laterally) sampled on a
// rotated UTM volume of 12.5 x 12.5 x 4 m voxels; a fractal horizon through it on a grid rotated
// otherwise, of 6.25 m (2x finer than the traces) down to 50 m (4x coarser). For each horizon
// density and sample filter (vtkHorizonVolumeSampler: nearest, trilinear) the horizon is drawn
// coloured by the sampled grid (vtkStackedHeightFieldMapper::SetHorizonColorArray) and the drawn
// value at every pixel, the grid's bilinear at the exact hit (reference caster), is compared with
// the volume's trilinear value at that hit: the per-pixel draping this approximates. Times:
// sampling in core and through a page pool (median of 3), and the frame (median of 5, 256^2).
// Usage: BenchSubsurface header | run | report <csv> <png>  (-T <temporary folder>)
#include "StrataBenchChart.h"
#include "StrataHeightFieldCase.h"
#include "StrataHeightFieldScenes.h"
#include "StrataTestPaths.h"

#include "StrataHeightFieldStack.h"
#include "StrataImageSampling.h"
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkChart.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkHorizonVolumeSampler.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMatrix3x3.h"
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
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
const char* Header = "case,filter,horizon_spacing_m,horizon_points,sample_ms_in_core,sample_ms_"
                     "paged,pages_read,frame_ms,pixels,rms_error,max_error";
const double X0 = 500000.0, Y0 = 6600000.0;
const int VX = 161, VY = 161, VZ = 101; // 2 km x 2 km x 400 m

double Field(double x, double y, double z)
{
  const double u = x - X0, v = y - Y0;
  const double warp = 12.0 * std::sin(u / 230.0) * std::cos(v / 310.0) + 0.02 * u - 0.015 * v;
  return std::sin(2.0 * M_PI * (z + warp) / 40.0) * (0.6 + 0.4 * std::cos(u / 500.0));
}

double Seconds()
{
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

void Rotation(double degrees, double d[9])
{
  const double a = degrees * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
  const double r[9] = { c, -s, 0, s, c, 0, 0, 0, 1 };
  std::copy_n(r, 9, d);
}

void IndexToWorld(vtkImageData* image, const double idx[3], double scaleZ, double w[3])
{
  const double* o = image->GetOrigin();
  const double* s = image->GetSpacing();
  const double* d = image->GetDirectionMatrix()->GetData();
  const double p[3] = { idx[0] * s[0], idx[1] * s[1], idx[2] * (scaleZ != 0.0 ? scaleZ : s[2]) };
  for (int r = 0; r < 3; ++r)
    w[r] = o[r] + d[3 * r] * p[0] + d[3 * r + 1] * p[1] + d[3 * r + 2] * p[2];
}

vtkSmartPointer<vtkImageData> MakeVolume()
{
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->SetDimensions(VX, VY, VZ);
  volume->SetOrigin(X0, Y0, -1400.0);
  volume->SetSpacing(12.5, 12.5, 4.0);
  double d[9];
  Rotation(25.0, d);
  volume->SetDirectionMatrix(d);
  vtkNew<vtkFloatArray> a;
  a->SetName("amplitude");
  a->SetNumberOfTuples(VX * VY * VZ);
  for (int k = 0; k < VZ; ++k)
    for (int j = 0; j < VY; ++j)
      for (int i = 0; i < VX; ++i)
      {
        const double idx[3] = { double(i), double(j), double(k) };
        double w[3];
        IndexToWorld(volume, idx, 0.0, w);
        a->SetValue((vtkIdType(k) * VY + j) * VX + i, static_cast<float>(Field(w[0], w[1], w[2])));
      }
  volume->GetPointData()->SetScalars(a);
  return volume;
}

/// Trilinear of the volume's stored floats at world point w (the per-pixel ideal); NaN outside.
double VolumeAt(vtkImageData* volume, const double w[3])
{
  double x[3];
  volume->TransformPhysicalPointToContinuousIndex(w, x);
  return strata::SampleImage(volume, volume->GetPointData()->GetScalars(), x, false);
}

/// A fractal horizon (depths 1200-1100 m, HeightScale -1) over 1.6 km x 1.6 km at `spacing`.
vtkSmartPointer<vtkImageData> MakeHorizon(double spacing)
{
  const int n = static_cast<int>(std::lround(1600.0 / spacing)) + 1;
  std::vector<float> h(static_cast<size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      const double u = i * spacing / 1600.0, v = j * spacing / 1600.0;
      h[static_cast<size_t>(j) * n + i] = static_cast<float>(
        1200.0 + 60.0 * strata_test::FractalNoise(3 * u, 3 * v, 7, 5) + 40.0 * (u - v));
    }
  return strata_test::MakeHorizon(n, n, X0 + 350.0, Y0 + 50.0, spacing, spacing, 40.0, h);
}

struct Row
{
  std::string Filter;
  double Spacing = 0;
  vtkIdType Points = 0;
  double SampleMs = 0, PagedMs = 0, FrameMs = 0;
  vtkIdType Pages = 0;
  long Pixels = 0;
  double Rms = 0, Max = 0;
};

Row Measure(vtkImageData* volume,
  const std::string& pool,
  double spacing,
  bool nearest,
  const std::string& temp)
{
  Row row;
  row.Filter = nearest ? "nearest" : "trilinear";
  row.Spacing = spacing;
  auto horizon = MakeHorizon(spacing);
  row.Points = horizon->GetNumberOfPoints();
  vtkNew<vtkHorizonVolumeSampler> sampler;
  sampler->SetInputData(0, horizon);
  sampler->SetInputData(1, volume);
  sampler->SetHeightScale(-1.0);
  sampler->SetNearestNeighbor(nearest);
  std::vector<double> ms;
  for (int r = 0; r < 3; ++r)
  {
    sampler->Modified();
    const double t0 = Seconds();
    sampler->Update();
    ms.push_back(1e3 * (Seconds() - t0));
  }
  row.SampleMs = Median(ms);
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(pool.c_str());
  vtkNew<vtkHorizonVolumeSampler> paged;
  paged->SetInputData(0, horizon);
  paged->SetVolumeConnection(reader->GetOutputPort());
  paged->SetHeightScale(-1.0);
  paged->SetNearestNeighbor(nearest);
  ms.clear();
  for (int r = 0; r < 3; ++r)
  {
    paged->Modified();
    const double t0 = Seconds();
    paged->Update();
    ms.push_back(1e3 * (Seconds() - t0));
  }
  row.PagedMs = Median(ms);
  row.Pages = paged->GetNumberOfPagesRead();

  // Drawn coloured by the sampled grid; the reference's exact hits for the error.
  vtkSmartPointer<vtkImageData> draped = sampler->GetOutput();
  strata_test::HeightFieldScene s(temp, { draped }, 256, 256);
  s.Mapper->SetHeightScale(-1.0);
  s.Mapper->SetHorizonColorArray(0, "amplitude");
  vtkNew<vtkColorTransferFunction> colors;
  colors->AddRGBPoint(-1.0, 0.1, 0.2, 0.8);
  colors->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
  colors->AddRGBPoint(1.0, 0.8, 0.1, 0.1);
  s.Mapper->SetHorizonLookupTable(0, colors);
  double c[3];
  strata_test::Center(draped, c);
  const double pos[3] = { c[0] - 900, c[1] - 1500, -1200 + 1500 }, foc[3] = { c[0], c[1], -1200 };
  const double up[3] = { 0, 0, 1 };
  s.Camera(pos, foc, up);
  s.Win->Render();
  ms.clear();
  for (int f = 0; f < 5; ++f)
  {
    s.Ren->GetActiveCamera()->Azimuth(0.2);
    s.Ren->ResetCameraClippingRange();
    const double t0 = Seconds();
    s.Win->Render();
    ms.push_back(1e3 * (Seconds() - t0));
  }
  row.FrameMs = Median(ms);
  auto r = strata_test::CompareWithReference(
    s.Win, s.Ren, s.Actor, s.Mapper, s.Images, "subsurface-drape", temp);
  strata::HeightFieldStack attributes;
  int dims[3];
  draped->GetDimensions(dims);
  attributes.Initialize(dims[0], dims[1]);
  attributes.AddLayer(
    vtkFloatArray::SafeDownCast(draped->GetPointData()->GetArray("amplitude"))->GetPointer(0));
  double sum = 0.0;
  for (size_t i = 0; i < r.RefIds.size(); ++i)
  {
    if (r.RefIds[i] != 0)
      continue;
    const double* g = &r.RefPoints[3 * i];
    double drawn, w[3];
    IndexToWorld(draped, g, -1.0, w);
    const double exact = VolumeAt(volume, w);
    if (std::isnan(exact) || !attributes.Interpolate(0, g[0], g[1], drawn))
      continue;
    const double e = drawn - exact;
    sum += e * e;
    row.Max = std::max(row.Max, std::abs(e));
    ++row.Pixels;
  }
  row.Rms = row.Pixels ? std::sqrt(sum / row.Pixels) : 0.0;
  return row;
}

int Report(const std::string& csvPath, const std::string& png)
{
  std::ifstream csv(csvPath);
  std::string line;
  std::getline(csv, line);
  std::map<std::string, std::vector<std::pair<double, double>>> series;
  while (std::getline(csv, line))
  {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');)
      f.push_back(x);
    if (f.size() < 11)
      continue;
    // Error against the whole cost of a new drape: sampling in core plus one frame.
    series[f[1]].emplace_back(std::stod(f[4]) + std::stod(f[7]), std::stod(f[9]));
  }
  strata_bench::Chart chart("Draping a volume on a horizon, llvmpipe 256 x 256: RMS error of the "
                            "drawn amplitude (of 1) against the per-pixel value",
    14,
    "sampling in core + one frame (ms)",
    true,
    "RMS error",
    true,
    true);
  const unsigned char colours[2][3] = { { 200, 60, 40 }, { 40, 90, 200 } };
  int k = 0;
  for (auto& s : series)
  {
    std::sort(s.second.begin(), s.second.end());
    chart.Add(vtkChart::LINE, s.first, s.second, colours[k++ % 2]);
  }
  chart.Write(png);
  std::cout << png << "\n";
  return 0;
}
}

int main(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::TakeFromArguments(argc, argv);
  const std::string what = argc > 1 ? argv[1] : "run";
  if (what == "header")
  {
    std::cout << Header << "\n";
    return 0;
  }
  if (what == "report" && argc > 3)
    return Report(argv[2], argv[3]);
  auto volume = MakeVolume();
  const std::string pool = paths.Output + "/BenchSubsurface.spp";
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputData(volume);
  writer->SetFileName(pool.c_str());
  writer->SetPageSize(32);
  if (!writer->Write())
    return 1;
  for (double spacing : { 6.25, 12.5, 25.0, 50.0 })
    for (bool nearest : { true, false })
    {
      const Row r = Measure(volume, pool, spacing, nearest, paths.Output);
      std::printf("drape,%s,%g,%lld,%.1f,%.1f,%lld,%.1f,%ld,%.5f,%.5f\n",
        r.Filter.c_str(),
        r.Spacing,
        static_cast<long long>(r.Points),
        r.SampleMs,
        r.PagedMs,
        static_cast<long long>(r.Pages),
        r.FrameMs,
        r.Pixels,
        r.Rms,
        r.Max);
      std::fflush(stdout);
    }
  std::remove(pool.c_str());
  return 0;
}
