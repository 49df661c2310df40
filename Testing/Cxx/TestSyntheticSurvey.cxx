// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkSyntheticSurveyWriter: a 10 x 12 trace survey at 456000 E, 6780000 N, turned 30 degrees,
// 25 m x 12.5 m bins, written from three horizons given here in closed form (planes of two-way
// time, so that bilinear sampling is exact): one on an axis-aligned grid, one on a grid turned
// 140 degrees with a hole (no data west of 456000 E), one axis-aligned. Checked:
// - read back by vtkSegyVolumeReader with its default placement: georeferenced, the corner
//   traces within 1 cm of where they were written (coordinates rounded to cm), rotation and
//   bins as written;
// - every reflection: the sample of largest amplitude of the reflection's sign within the
//   wavelet's main lobe (+-7 ms at 30 Hz) lies within half a sample (1 ms) of the horizon's
//   time at that trace without noise (the wavelet is sampled exactly and is symmetric: the
//   nearest sample is the largest), and within one sample with noise 0.002 (seed 7; near the
//   peak the wavelet changes by less than the noise from one sample to the next, so the noise
//   can move the largest sample by one; measured 1.77 ms), and its world z is minus that time
//   (the horizons' HeightScale -1); in the hole the middle horizon gives no reflection and the
//   two layers it parted merge;
// - without noise, every sample equals the sum of reflection coefficient x Ricker computed
//   here (float rounding: 1e-6);
// - the same seed writes the same bytes, another seed other noise;
// - strata-convert (and vtkImageToPagePoolWriter) page it: the pool keeps the georeference
//   (origin, spacing, direction) and every sample;
// - errors: no horizons, too many impedances, a sample interval of no whole microseconds, an
//   unwritable path: reported, Write() false, nothing left.
#include "StrataErrorCounter.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkIrapBinaryGridReader.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkSegyVolumeReader.h"
#include "vtkSyntheticSurveyWriter.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace
{
using strata_test::Check;
using strata_test::ErrorCounter;

constexpr double Pi = 3.14159265358979323846;
const double Centre[2] = { 456060.0, 6780130.0 };

/// Horizon h's two-way time (ms) at map (x, y): a gently dipping plane.
double HorizonTime(int h, double x, double y)
{
  const double base[3] = { 300.0, 420.0, 540.0 };
  const double dip[3][2] = { { 0.05, 0.02 }, { -0.03, 0.04 }, { 0.02, -0.05 } };
  return base[h] + dip[h][0] * (x - Centre[0]) + dip[h][1] * (y - Centre[1]);
}

/// Horizon 1 has no data west of this easting (whole cells; traces within a cell of it are not
/// checked).
constexpr double HoleEast = 456000.0;

/// Horizon h on a 60 x 60 grid of 10 m turned `degrees`, centred on the survey.
vtkSmartPointer<vtkImageData> MakeHorizon(int h, double degrees)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  const int n = 60;
  const double s = 10.0;
  const double a = degrees * Pi / 180.0, c = std::cos(a), sn = std::sin(a);
  image->SetDimensions(n, n, 1);
  image->SetSpacing(s, s, 1.0);
  const double half = 0.5 * (n - 1) * s;
  image->SetOrigin(Centre[0] - c * half + sn * half, Centre[1] - sn * half - c * half, 0.0);
  const double d[9] = { c, -sn, 0, sn, c, 0, 0, 0, 1 };
  image->SetDirectionMatrix(d);
  vtkNew<vtkFloatArray> values;
  values->SetName("twt");
  values->SetNumberOfTuples(n * n);
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      double p[3];
      image->TransformIndexToPhysicalPoint(i, j, 0, p);
      const bool hole = h == 1 && p[0] < HoleEast;
      values->SetValue(j * n + i,
        hole ? std::numeric_limits<float>::quiet_NaN()
             : static_cast<float>(HorizonTime(h, p[0], p[1])));
    }
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

const double Impedance[4] = { 4e6, 5e6, 4.5e6, 6e6 };

void Configure(vtkSyntheticSurveyWriter* w,
  const std::vector<vtkSmartPointer<vtkImageData>>& horizons)
{
  for (const auto& h : horizons)
    w->AddInputDataObject(0, h);
  w->SetOrigin(456000.0, 6780000.0);
  w->SetRotation(30.0);
  w->SetLines(10, 12);
  w->SetBins(25.0, 12.5);
  w->SetSamples(400, 2.0, 100);
  w->SetPeakFrequency(30.0);
  w->SetNoiseLevel(0.002);
  w->SetSeed(7);
  for (int k = 0; k < 4; ++k)
    w->SetImpedance(k, Impedance[k]);
}

/// The reflections (time, coefficient) of the trace at map (x, y), computed here.
std::vector<std::pair<double, double>> Reflections(double x, double y)
{
  std::vector<std::pair<double, double>> r;
  double above = Impedance[0];
  for (int h = 0; h < 3; ++h)
  {
    if (h == 1 && x < HoleEast)
      continue;
    r.emplace_back(HorizonTime(h, x, y), (Impedance[h + 1] - above) / (Impedance[h + 1] + above));
    above = Impedance[h + 1];
  }
  return r;
}

double Ricker(double t, double f)
{
  const double a = Pi * f * t / 1000.0;
  return (1.0 - 2.0 * a * a) * std::exp(-a * a);
}

std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct Fixture
{
  std::vector<vtkSmartPointer<vtkImageData>> Horizons{ MakeHorizon(0, 0.0),
    MakeHorizon(1, 140.0),
    MakeHorizon(2, 0.0) };
  std::string Out;
  std::string Path;
};

void Georeference(const Fixture& f)
{
  vtkNew<vtkSyntheticSurveyWriter> writer;
  Configure(writer, f.Horizons);
  vtkNew<vtkSegyVolumeReader> reader;
  vtkNew<ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(f.Path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  const double* spacing = image->GetSpacing();
  double worst = 0.0;
  for (int i : { 0, 9 })
  {
    for (int x : { 0, 11 })
    {
      double expected[2], p[3];
      writer->MapPosition(i, x, expected);
      image->TransformIndexToPhysicalPoint(x, 0, i, p);
      worst = std::max(worst, std::hypot(p[0] - expected[0], p[1] - expected[1]));
    }
  }
  std::cout << "  " << dims[0] << " x " << dims[1] << " x " << dims[2] << ", spacing " << spacing[0]
            << " " << spacing[1] << " " << spacing[2] << ", rotation " << reader->GetGridRotation()
            << ", corners off by " << worst << " m\n";
  Check(errors->Errors == 0 && errors->Warnings == 0 && reader->GetGeoreferenced() &&
          dims[0] == 12 && dims[1] == 400 && dims[2] == 10 && reader->GetFirstInline() == 1000 &&
          reader->GetFirstCrossline() == 2000,
    "read back: 12 crosslines x 400 samples x 10 inlines, georeferenced, no warnings");
  Check(worst < 0.01 && std::abs(reader->GetGridRotation() - 30.0) < 0.01 &&
          std::abs(spacing[0] - 12.5) < 0.005 && std::abs(spacing[2] - 25.0) < 0.005 &&
          spacing[1] == 2.0 && image->GetOrigin()[2] == -100.0,
    "read back: corners within 1 cm, 30 degrees, 12.5 m x 25 m bins, 2 ms from z = -100");
}

/// Peaks of `path` within `bound` ms of their horizons.
void Peaks(const std::string& path, double bound, const std::string& name)
{
  vtkNew<vtkSegyVolumeReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  long checked = 0, misplaced = 0, merged = 0;
  double worst = 0.0;
  for (int k = 0; k < 10; ++k)
  {
    for (int x = 0; x < 12; ++x)
    {
      double p[3];
      image->TransformIndexToPhysicalPoint(x, 0, k, p);
      if (std::abs(p[0] - HoleEast) < 15.0)
        continue; // within a cell of the hole's edge
      const auto reflections = Reflections(p[0], p[1]);
      merged += reflections.size() == 2;
      for (const auto& r : reflections)
      {
        // The sample of largest signed amplitude in the main lobe, +-7 ms.
        int best = -1;
        double bestValue = -1e30;
        for (int s = 0; s < 400; ++s)
        {
          const double t = 100.0 + 2.0 * s;
          const double v = (r.second > 0 ? 1 : -1) * image->GetScalarComponentAsDouble(x, s, k, 0);
          if (std::abs(t - r.first) <= 7.0 && v > bestValue)
          {
            best = s;
            bestValue = v;
          }
        }
        double q[3];
        image->TransformIndexToPhysicalPoint(x, best, k, q);
        const double off = std::abs(-q[2] - r.first);
        worst = std::max(worst, off);
        ++checked;
        misplaced += off > bound + 1e-9;
      }
    }
  }
  std::cout << "  " << name << ": " << checked << " reflections checked (" << merged
            << " traces in the hole), largest peak-to-horizon distance " << worst << " ms\n";
  Check(checked > 200 && merged > 20 && merged < 100 && misplaced == 0,
    name + ": every reflection's peak within " + std::to_string(bound) +
      " ms of its horizon, at world z = -time");
}

void Exact(const Fixture& f)
{
  vtkNew<vtkSyntheticSurveyWriter> writer;
  Configure(writer, f.Horizons);
  writer->SetNoiseLevel(0.0);
  const std::string path = f.Out + "/exact.sgy";
  writer->SetFileName(path.c_str());
  Check(writer->Write(), "noise-free survey written");
  vtkNew<vtkSegyVolumeReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  double worst = 0.0;
  for (int k = 0; k < 10; ++k)
  {
    for (int x = 0; x < 12; ++x)
    {
      double p[2];
      writer->MapPosition(k, x, p);
      if (std::abs(p[0] - HoleEast) < 15.0)
        continue;
      const auto reflections = Reflections(p[0], p[1]);
      for (int s = 0; s < 400; ++s)
      {
        double expected = 0.0;
        for (const auto& r : reflections)
          expected += r.second * Ricker(100.0 + 2.0 * s - r.first, 30.0);
        worst = std::max(worst, std::abs(image->GetScalarComponentAsDouble(x, s, k, 0) - expected));
      }
    }
  }
  std::cout << "  noise-free: largest difference from the reflections x Ricker " << worst << "\n";
  Check(worst < 1e-6, "noise-free: every sample = sum of reflection coefficient x Ricker");
}

void Seeds(const Fixture& f)
{
  vtkNew<vtkSyntheticSurveyWriter> writer;
  Configure(writer, f.Horizons);
  const std::string again = f.Out + "/again.sgy", other = f.Out + "/other.sgy";
  writer->SetFileName(again.c_str());
  writer->Write();
  writer->SetSeed(8);
  writer->SetFileName(other.c_str());
  writer->Write();
  const std::string a = Slurp(f.Path), b = Slurp(again), c = Slurp(other);
  Check(!a.empty() && a == b && c.size() == a.size() && c != a,
    "the same seed writes the same bytes, another seed other noise");
}

void Pool(const Fixture& f, const std::string& converter)
{
  vtkNew<vtkSegyVolumeReader> reader;
  reader->SetFileName(f.Path.c_str());
  reader->Update();
  vtkImageData* survey = reader->GetOutput();
  auto same = [&](const std::string& pool, const std::string& what)
  {
    vtkNew<vtkPagePoolReader> r;
    r->SetFileName(pool.c_str());
    r->Update();
    vtkImageData* paged = r->GetOutput();
    reader->UpdateWholeExtent(); // the pool writer left a slab's update extent behind
    bool ok = paged->GetNumberOfPoints() == survey->GetNumberOfPoints();
    for (int c = 0; c < 3 && ok; ++c)
      ok = paged->GetOrigin()[c] == survey->GetOrigin()[c] &&
           paged->GetSpacing()[c] == survey->GetSpacing()[c];
    for (int e = 0; e < 9 && ok; ++e)
      ok = paged->GetDirectionMatrix()->GetData()[e] == survey->GetDirectionMatrix()->GetData()[e];
    vtkDataArray* a = paged->GetPointData()->GetArray(0);
    vtkDataArray* b = survey->GetPointData()->GetScalars();
    for (vtkIdType n = 0; ok && n < b->GetNumberOfTuples(); ++n)
      ok = a->GetComponent(n, 0) == b->GetComponent(n, 0);
    Check(ok, what + ": the pool keeps the georeference and every sample");
  };
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort());
  const std::string pool = f.Out + "/synthetic.spp";
  writer->SetFileName(pool.c_str());
  writer->SetPageSize(8);
  Check(writer->Write(), "vtkImageToPagePoolWriter wrote the pool");
  same(pool, "vtkImageToPagePoolWriter");
  if (converter.empty())
  {
    std::cout << "  strata-convert not built: skipped\n";
    return;
  }
  const std::string converted = f.Out + "/converted.spp";
  const std::string command =
    "'" + converter + "' '" + f.Path + "' '" + converted + "' --page-size 16 >/dev/null 2>&1";
  Check(std::system(command.c_str()) == 0, "strata-convert exits 0");
  same(converted, "strata-convert");
}

/// strata-synth on the four Reek horizons (Irap binary, 20 m grid turned 140 degrees), every
/// 16th node: the survey is that grid, and strata-convert pages it.
void Tool(const Fixture& f, const std::string& converter, const std::string& data)
{
  const std::string synth = vtksys::SystemTools::GetFilenamePath(converter) + "/strata-synth";
  if (converter.empty() || !vtksys::SystemTools::FileExists(synth, true))
  {
    std::cout << "  strata-synth not built: skipped\n";
    return;
  }
  const std::string path = f.Out + "/reek.sgy";
  std::string command = "'" + synth + "'";
  for (const char* h : { "reek_01_topreek_rota.gri",
         "reek_02_midreek_rota.gri",
         "reek_03_lowreek_rota.gri",
         "reek_04_basereek_rota.gri" })
    command += " '" + data + "/horizons/" + h + "'";
  command += " --step 16 --seed 3 -o '" + path + "' >/dev/null 2>&1";
  Check(std::system(command.c_str()) == 0, "strata-synth on the Reek horizons exits 0");
  vtkNew<vtkIrapBinaryGridReader> top;
  top->SetFileName((data + "/horizons/reek_01_topreek_rota.gri").c_str());
  top->Update();
  vtkNew<vtkSegyVolumeReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* survey = reader->GetOutput();
  int dims[3], grid[3];
  survey->GetDimensions(dims);
  top->GetOutput()->GetDimensions(grid);
  const double* o = survey->GetOrigin();
  const double* g = top->GetOutput()->GetOrigin();
  std::cout << "  reek: " << dims[0] << " x " << dims[1] << " x " << dims[2] << ", rotation "
            << reader->GetGridRotation() << ", bins " << survey->GetSpacing()[0] << " x "
            << survey->GetSpacing()[2] << ", origin off the grid's by "
            << std::hypot(o[0] - g[0], o[1] - g[1]) << " m\n";
  Check(reader->GetGeoreferenced() && dims[0] == (grid[0] - 1) / 16 + 1 &&
          dims[2] == (grid[1] - 1) / 16 + 1 && std::abs(reader->GetGridRotation() - 140.0) < 0.01 &&
          std::abs(survey->GetSpacing()[0] - 320.0) < 0.01 &&
          std::abs(survey->GetSpacing()[2] - 320.0) < 0.01 &&
          std::hypot(o[0] - g[0], o[1] - g[1]) < 0.01,
    "strata-synth: the survey is the horizons' grid, every 16th node, turned 140 degrees");
  const std::string pool = f.Out + "/reek.spp";
  Check(std::system(
          ("'" + converter + "' '" + path + "' '" + pool + "' >/dev/null 2>&1").c_str()) == 0 &&
          vtksys::SystemTools::FileExists(pool),
    "strata-convert pages strata-synth's survey");
}

void Errors(const Fixture& f)
{
  auto rejects = [&](vtkSyntheticSurveyWriter* w,
                   const std::string& path,
                   const std::string& expect,
                   const std::string& what)
  {
    vtkNew<ErrorCounter> errors;
    errors->Watch(w);
    w->SetFileName(path.c_str());
    const bool wrote = w->Write();
    std::cout << "  " << what << ": " << errors->First << "\n";
    Check(!wrote && errors->Errors > 0 && errors->First.find(expect) != std::string::npos &&
            !vtksys::SystemTools::FileExists(path),
      what + ": reported (\"" + expect + "\"), nothing written");
  };
  const std::string bad = f.Out + "/bad.sgy";
  {
    vtkNew<vtkSyntheticSurveyWriter> w;
    rejects(w, bad, "no horizons", "no horizons");
  }
  {
    vtkNew<vtkSyntheticSurveyWriter> w;
    Configure(w, f.Horizons);
    w->SetImpedance(4, 7e6);
    rejects(w, bad, "5 impedances set for 3 horizons", "too many impedances");
  }
  {
    vtkNew<vtkSyntheticSurveyWriter> w;
    Configure(w, f.Horizons);
    w->SetSamples(400, 0.0005, 0);
    rejects(w, bad, "not a whole number of microseconds", "sample interval 0.5 microseconds");
  }
  {
    vtkNew<vtkSyntheticSurveyWriter> w;
    Configure(w, f.Horizons);
    rejects(w, f.Out + "/no-such-folder/s.sgy", "cannot create", "unwritable path");
  }
}
}

int TestSyntheticSurvey(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  Fixture f;
  f.Out = paths.Output + "/TestSyntheticSurvey";
  vtksys::SystemTools::MakeDirectory(f.Out);
  f.Path = f.Out + "/synthetic.sgy";
  {
    vtkNew<vtkSyntheticSurveyWriter> writer;
    Configure(writer, f.Horizons);
    writer->SetFileName(f.Path.c_str());
    Check(writer->Write(), "the survey is written");
  }
  const char* env = std::getenv("STRATA_CONVERT_TOOL");
  std::string converter =
    env ? env
        : vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::GetRealPath("/proc/self/exe")) +
            "/strata-convert";
  if (!vtksys::SystemTools::FileExists(converter, true))
    converter.clear();
  return strata_test::RunSubTests(
    {
      { "Georeference", [&] { Georeference(f); } },
      { "Exact", [&] { Exact(f); } },
      { "Peaks", [&] { Peaks(f.Out + "/exact.sgy", 1.0, "noise-free"); } },
      { "NoisyPeaks", [&] { Peaks(f.Path, 2.0, "noise 0.002"); } },
      { "Seeds", [&] { Seeds(f); } },
      { "Pool", [&] { Pool(f, converter); } },
      { "Tool", [&] { Tool(f, converter, paths.Data); } },
      { "Errors", [&] { Errors(f); } },
    },
    strata_test::Failures);
}
