// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// What the layers per pixel cost and what they get right: six translucent horizons (opacity
// 0.3 each, undulating, 4 m apart) through two overlapping volumes at UTM coordinates, given to
// vtkMultiVolumeRayCastMapper (AddTranslucentActor) with TranslucentLayers K = 1 .. 7. Each
// frame is compared, pixel by pixel, with the double-precision reference that composites every
// crossing of every horizon at its exact depth (strata::HeightFieldReferenceCaster::CastAll through
// strata::MultiVolumeReferenceIntegrator::AddSurfaceCrossings); below six layers the farthest
// crossings are dropped. Time: median of 7 frames (128^2, llvmpipe), read back.
// Usage: BenchSubsurfaceLayers header | run | report <csv> <png>  (-T <temporary folder>)
#include "StrataBenchChart.h"
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkActor.h"
#include "vtkChart.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using namespace strata_test;
using Ref = strata::MultiVolumeReferenceIntegrator;
const char* Header = "case,layers,horizons,frame_ms,rms_error,max_error";
const double OX = 456000.0, OY = 6780000.0;
constexpr int Horizons = 6;
constexpr double Opacity = 0.3;

vtkSmartPointer<vtkImageData> Horizon(int k)
{
  std::vector<float> z(36 * 30);
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 36; ++i)
    {
      const double x = -6.0 + 2.0 * i, y = -6.0 + 2.0 * j;
      z[j * 36 + i] =
        static_cast<float>(4.0 + 4.0 * k + 0.08 * x - 0.05 * y + 1.5 * std::sin(0.2 * x + k));
    }
  return MakeHorizon(36, 30, OX - 6.0, OY - 6.0, 2.0, 2.0, 0.0, z);
}

void Color(int k, double rgb[3])
{
  const double s = k / double(Horizons - 1);
  rgb[0] = 0.9 - 0.7 * s;
  rgb[1] = 0.3 + 0.4 * std::sin(3.14159 * s);
  rgb[2] = 0.2 + 0.7 * s;
}

int Run(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  s.Add(Blob(40, 36, 32, 1.0, 1.0, 1.0, OX, OY, 0, 1), MakeVolumeProperty(0));
  vtkNew<vtkTransform> t;
  t->Translate(OX + 30, OY + 10, 4);
  t->RotateZ(30);
  s.Add(Blob(24, 20, 18, 1.6, 1.5, 1.4, 0, 0, 0, 2), MakeVolumeProperty(1), t);
  s.UseMultiVolume();
  vtkNew<vtkStackedHeightFieldMapper> hf;
  std::vector<vtkSmartPointer<vtkImageData>> horizons;
  std::vector<std::array<double, 3>> colors(Horizons);
  for (int k = 0; k < Horizons; ++k)
  {
    horizons.push_back(Horizon(k));
    hf->AddInputData(horizons.back());
    Color(k, colors[k].data());
    hf->SetHorizonColor(k, colors[k][0], colors[k][1], colors[k][2]);
    hf->SetHorizonOpacity(k, Opacity);
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(hf);
  actor->GetProperty()->LightingOff();
  s.Ren->AddActor(actor);
  s.Ren->SetBackground(128 / 255.0, 128 / 255.0, 128 / 255.0);
  s.Mapper->AddTranslucentActor(actor);
  const double pos[3] = { OX - 50, OY - 70, 80 }, focal[3] = { OX + 30, OY + 25, 14 };
  s.Camera(pos, focal);
  s.Win->Render();
  const int n = MultiVolumeCaseSize;
  std::vector<unsigned char> background(3 * size_t(n) * n, 128);
  Ref ref;
  ref.SetStepFraction(1.0 / 16.0);
  for (size_t i = 0; i < s.Images.size(); ++i)
    ref.AddVolume(ToReferenceVolume(s.Images[i], s.Volumes[i], s.Mapper, static_cast<int>(i)));
  ref.AddSurfaceCrossings(HorizonCrossings(hf, colors));
  std::vector<double> rgba;
  ref.IntegrateImage(ClipToWorld(s.Ren)->GetData(), n, n, rgba);
  const std::vector<double> expected = CompositeOver(rgba, background);
  for (int layers = 1; layers <= 7; ++layers)
  {
    s.Mapper->SetTranslucentLayers(layers);
    std::vector<double> ms;
    std::vector<unsigned char> image;
    for (int frame = 0; frame < 8; ++frame)
    {
      const auto t0 = std::chrono::steady_clock::now();
      s.Win->Render();
      image = ReadRGB(s.Win);
      const double dt =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (frame > 0) // the first frame after a change compiles
        ms.push_back(dt);
    }
    std::sort(ms.begin(), ms.end());
    const ChannelError e = ImageError(image, expected);
    std::printf("layers,%d,%d,%.2f,%.4f,%.3f\n", layers, Horizons, ms[ms.size() / 2], e.Rms, e.Max);
    std::fflush(stdout);
  }
  return 0;
}

int Report(const std::string& csvPath, const std::string& png)
{
  std::ifstream csv(csvPath);
  std::string line;
  std::getline(csv, line);
  std::vector<std::pair<double, double>> points;
  while (std::getline(csv, line))
  {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');)
      f.push_back(x);
    if (f.size() >= 6)
      points.emplace_back(std::stod(f[3]), std::max(std::stod(f[4]), 1e-3));
  }
  // In the order of K (the rows'), so that the line runs from one layer to seven.
  strata_bench::Chart chart("Translucent horizons inside volumes, llvmpipe 128 x 128: RMS error "
                            "(8-bit) against the reference for 1 to 7 layers per pixel",
    14,
    "frame (ms)",
    false,
    "RMS error",
    true,
    true);
  const unsigned char colour[3] = { 200, 60, 40 };
  chart.Add(vtkChart::LINE, "six horizons of opacity 0.3, K = 1 .. 7", points, colour);
  chart.Write(png);
  std::cout << png << "\n";
  return 0;
}
}

int main(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::TakeFromArguments(argc, argv);
  const std::string what = argc > 1 ? argv[1] : "run";
  if (what == "header")
  {
    std::cout << Header << "\n";
    return 0;
  }
  if (what == "report" && argc > 3)
    return Report(argv[2], argv[3]);
  return Run(paths);
}
