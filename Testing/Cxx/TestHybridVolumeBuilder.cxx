// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The hybrid point/volume preprocessing against a brute-force computation written here from
// the definitions in StrataHybridVolumeBuilder.h: low-resolution values, error field, exact point
// sets (threshold, budget, error-grid step, planted spike), the optimized filter's bound,
// constant volumes, dimensions not divisible by the factor, bounded memory, and the file
// format (bit-exact round trip, corrupt files rejected).
#include "StrataSubTests.h"
#include "StrataTestPaths.h"

#include "StrataHybridVolumeBuilder.h"
#include "StrataHybridVolumeFile.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <tuple>
#include <vector>

namespace
{
using Filter = strata::HybridVolumeFile::FilterType;
int failures = 0;
void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "  ok   " : "  FAIL ") << what << "\n";
  failures += ok ? 0 : 1;
}

struct Volume
{
  int N[3];
  std::vector<float> V;
  float At(int x, int y, int z) const
  {
    x = std::min(std::max(x, 0), N[0] - 1);
    y = std::min(std::max(y, 0), N[1] - 1);
    z = std::min(std::max(z, 0), N[2] - 1);
    return V[(static_cast<size_t>(z) * N[1] + y) * N[0] + x];
  }
};

Volume Smooth(int nx, int ny, int nz, bool noise)
{
  Volume v{ { nx, ny, nz }, {} };
  uint32_t h = 12345;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
      {
        h = h * 1664525u + 1013904223u;
        const double r = noise ? (h >> 8) / 16777216.0 - 0.5 : 0.0;
        v.V.push_back(static_cast<float>(std::sin(0.7 * x) * std::cos(0.5 * y) + 0.3 * z / nz + r));
      }
  return v;
}

void Configure(strata::HybridVolumeBuilder& b, const Volume& v, int reads[1] = nullptr)
{
  const double spacing[3] = { 1, 1, 2 }, origin[3] = { 0, 0, 0 };
  b.SetInput(v.N,
    spacing,
    origin,
    [&v, reads](int first, int count, float* out)
    {
      const size_t slice = static_cast<size_t>(v.N[0]) * v.N[1];
      std::copy(v.V.begin() + first * slice, v.V.begin() + (first + count) * slice, out);
      if (reads)
      {
        reads[0] += count;
      }
      return true;
    });
}

// Kernels as the builder documents them, written independently (not normalised here).
double Kernel(Filter filter, int d, int f)
{
  const double a = std::abs(d) / static_cast<double>(f);
  switch (filter)
  {
    case Filter::Box:
      return a < 0.5 ? 1 : (a == 0.5 ? 0.5 : 0);
    case Filter::Linear:
      return a < 1 ? 1 - a : 0;
    default:
      return a < 1 ? 1.5 * a * a * a - 2.5 * a * a + 1
                   : (a < 2 ? -0.5 * a * a * a + 2.5 * a * a - 4 * a + 2 : 0);
  }
}

int LowDim(int n, int f)
{
  return n == 1 ? 1 : static_cast<int>(std::ceil((n - 1) / static_cast<double>(f))) + 1;
}

// Brute-force low-resolution volume: a full 3-D sum per point, plus the optimized cap.
std::vector<double> BruteLow(const Volume& v, Filter filter, const int f[3], double bound)
{
  const int l[3] = { LowDim(v.N[0], f[0]), LowDim(v.N[1], f[1]), LowDim(v.N[2], f[2]) };
  std::vector<double> out;
  for (int k = 0; k < l[2]; ++k)
    for (int j = 0; j < l[1]; ++j)
      for (int i = 0; i < l[0]; ++i)
      {
        double sum = 0, wsum = 0, lowest = 1e300;
        for (int dz = -2 * f[2]; dz <= 2 * f[2]; ++dz)
          for (int dy = -2 * f[1]; dy <= 2 * f[1]; ++dy)
            for (int dx = -2 * f[0]; dx <= 2 * f[0]; ++dx)
            {
              const double w =
                Kernel(filter, dx, f[0]) * Kernel(filter, dy, f[1]) * Kernel(filter, dz, f[2]);
              const double s = v.At(i * f[0] + dx, j * f[1] + dy, k * f[2] + dz);
              sum += w * s;
              wsum += w;
              if (std::abs(dx) < f[0] && std::abs(dy) < f[1] && std::abs(dz) < f[2])
              {
                lowest = std::min(lowest, s);
              }
            }
        double value = sum / wsum;
        if (filter == Filter::Optimized)
        {
          value = std::min(value, lowest + bound);
        }
        out.push_back(value);
      }
  return out;
}

// Brute-force trilinear reconstruction at original index (x, y, z).
double BruteReconstruct(const std::vector<float>& low,
  const int l[3],
  const int f[3],
  int x,
  int y,
  int z)
{
  const int p[3] = { x, y, z };
  double r = 0;
  for (int i = 0; i < l[0]; ++i)
    for (int j = 0; j < l[1]; ++j)
      for (int k = 0; k < l[2]; ++k)
      {
        const int q[3] = { i, j, k };
        double w = 1;
        for (int a = 0; a < 3; ++a)
        {
          // Hat function of the low-resolution point, or 1 on a one-point axis.
          w *= l[a] == 1 ? 1.0 : std::max(0.0, 1.0 - std::fabs(p[a] / double(f[a]) - q[a]));
        }
        r += w * low[(static_cast<size_t>(k) * l[1] + j) * l[0] + i];
      }
  return r;
}

struct Errors
{
  std::vector<std::tuple<int, int, int>> Pos;
  std::vector<double> E;
};

Errors BruteErrors(const Volume& v, const strata::HybridVolumeFile& out, const int step[3])
{
  Errors e;
  for (int z = 0; z < v.N[2]; z += step[2])
    for (int y = 0; y < v.N[1]; y += step[1])
      for (int x = 0; x < v.N[0]; x += step[0])
      {
        e.Pos.emplace_back(x, y, z);
        e.E.push_back(v.At(x, y, z) -
                      BruteReconstruct(out.LowResolution, out.LowDimensions, out.Factor, x, y, z));
      }
  return e;
}

std::vector<std::tuple<int, int, int>> Positions(const strata::HybridVolumeFile& out)
{
  std::vector<std::tuple<int, int, int>> p;
  for (const auto& q : out.Points)
  {
    p.emplace_back(q.Position[0], q.Position[1], q.Position[2]);
  }
  return p;
}

bool SameOutput(const strata::HybridVolumeFile& a, const strata::HybridVolumeFile& b)
{
  return a.LowResolution == b.LowResolution && a.Points.size() == b.Points.size() &&
         std::memcmp(a.Points.data(),
           b.Points.data(),
           a.Points.size() * sizeof(strata::HybridVolumeFile::Point)) == 0;
}

std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void Spit(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary).write(bytes.data(), bytes.size());
}
}

namespace
{
void LowResolutionVolume(const Volume& v, const int factors[3])
{
  std::cout << "Low-resolution volume against a brute-force 3-D filter (tolerance 1e-5: float\n"
               "storage of values of magnitude ~1.5, and a different summation order)\n";
  for (Filter filter : { Filter::Box, Filter::Linear, Filter::Cubic, Filter::Optimized })
  {
    strata::HybridVolumeBuilder b;
    Configure(b, v);
    b.SetFactor(factors[0], factors[1], factors[2]);
    b.SetFilter(filter);
    b.SetOverestimationBound(0.1);
    strata::HybridVolumeFile out;
    const bool built = b.Build(out);
    const std::vector<double> ref = BruteLow(v, filter, factors, 0.1);
    double worst = built ? 0 : 1e9;
    for (size_t i = 0; built && i < ref.size(); ++i)
    {
      worst = std::max(worst, std::fabs(ref[i] - out.LowResolution[i]));
    }
    Check(built && out.LowResolution.size() == ref.size() && worst < 1e-5 &&
            out.LowDimensions[0] == 7 && out.LowDimensions[1] == 4 && out.LowDimensions[2] == 5,
      "filter " + std::to_string(static_cast<int>(filter)) + ": low dims 7x4x5 (13x11x9, factors " +
        "2,4,2), max difference " + std::to_string(worst));
  }
}

void ErrorFieldAndPointCounts(const Volume& v, const int factors[3])
{
  std::cout << "Error field and exact point counts (threshold kept 1e-4 away from every error)\n";
  for (const int step : { 1, 2 })
  {
    const int steps[3] = { step, step + 1, 1 };
    strata::HybridVolumeBuilder b;
    Configure(b, v);
    b.SetFactor(factors[0], factors[1], factors[2]);
    b.SetFilter(Filter::Linear);
    b.SetErrorGridStep(steps[0], steps[1], steps[2]);
    double threshold = 0.2;
    strata::HybridVolumeFile ref;
    b.Build(ref); // only its low-resolution volume, checked above, is used here
    Errors e = BruteErrors(v, ref, steps);
    // Move the threshold off any error value so rounding cannot change the count.
    for (double x : e.E)
    {
      if (std::fabs(std::fabs(x) - threshold) < 1e-4)
      {
        threshold += 3e-4;
      }
    }
    b.SetThreshold(threshold);
    strata::HybridVolumeFile out;
    b.Build(out);
    std::vector<std::tuple<int, int, int>> expected;
    for (size_t i = 0; i < e.E.size(); ++i)
    {
      if (std::fabs(e.E[i]) > threshold)
      {
        expected.push_back(e.Pos[i]);
      }
    }
    std::sort(expected.begin(),
      expected.end(),
      [](const auto& a, const auto& b)
      {
        return std::make_tuple(std::get<2>(a), std::get<1>(a), std::get<0>(a)) <
               std::make_tuple(std::get<2>(b), std::get<1>(b), std::get<0>(b));
      });
    double worst = 0;
    for (const auto& p : out.Points)
    {
      const double be =
        v.At(p.Position[0], p.Position[1], p.Position[2]) - BruteReconstruct(out.LowResolution,
                                                              out.LowDimensions,
                                                              out.Factor,
                                                              p.Position[0],
                                                              p.Position[1],
                                                              p.Position[2]);
      worst = std::max(worst, std::fabs(be - p.Error));
    }
    Check(Positions(out) == expected && worst < 1e-6 && !expected.empty(),
      "error grid step " + std::to_string(steps[0]) + "," + std::to_string(steps[1]) +
        ",1: " + std::to_string(out.Points.size()) + " points with |e| > " +
        std::to_string(threshold) + " (brute force " + std::to_string(expected.size()) +
        "), stored errors within " + std::to_string(worst));

    // Budget: the N largest |e|, the same set as sorting the brute-force errors.
    const uint64_t budget = expected.size() / 3;
    b.SetPointBudget(budget);
    b.SetThreshold(0);
    strata::HybridVolumeFile top;
    b.Build(top);
    std::vector<size_t> order(e.E.size());
    for (size_t i = 0; i < order.size(); ++i)
    {
      order[i] = i;
    }
    std::stable_sort(order.begin(),
      order.end(),
      [&](size_t a, size_t c) { return std::fabs(e.E[a]) > std::fabs(e.E[c]); });
    const double cut = std::fabs(e.E[order[budget - 1]]) - std::fabs(e.E[order[budget]]);
    std::vector<std::tuple<int, int, int>> best;
    for (size_t i = 0; i < budget; ++i)
    {
      best.push_back(e.Pos[order[i]]);
    }
    std::sort(best.begin(),
      best.end(),
      [](const auto& a, const auto& c)
      {
        return std::make_tuple(std::get<2>(a), std::get<1>(a), std::get<0>(a)) <
               std::make_tuple(std::get<2>(c), std::get<1>(c), std::get<0>(c));
      });
    Check(Positions(top) == best && cut > 1e-6,
      "point budget " + std::to_string(budget) + ": the largest errors (gap at the cut " +
        std::to_string(cut) + ")");
  }
}

void PlantedSpike()
{
  std::cout << "Planted spike in a constant volume (box filter, factor 4)\n";
  Volume s{ { 17, 16, 15 }, std::vector<float>(17 * 16 * 15, 2.0f) };
  s.V[(static_cast<size_t>(7) * 16 + 6) * 17 + 5] = 10.0f;
  strata::HybridVolumeBuilder b;
  Configure(b, s);
  b.SetFactor(4);
  b.SetFilter(Filter::Box);
  b.SetPointBudget(1);
  strata::HybridVolumeFile out;
  b.Build(out);
  Check(out.Points.size() == 1 && out.Points[0].Position[0] == 5 &&
          out.Points[0].Position[1] == 6 && out.Points[0].Position[2] == 7 &&
          out.Points[0].Value == 10.0f && out.Points[0].Error > 7.0f,
    "budget 1 gives the spike at (5, 6, 7)");
  b.SetPointBudget(0);
  b.SetThreshold(0.05); // the spike adds 8 / 64 = 0.125 to its box-filtered neighbours
  b.Build(out);
  const int one[3] = { 1, 1, 1 };
  Errors e = BruteErrors(s, out, one);
  std::vector<std::tuple<int, int, int>> expected;
  for (size_t i = 0; i < e.E.size(); ++i)
  {
    if (std::fabs(e.E[i]) > 0.05)
    {
      expected.push_back(e.Pos[i]);
    }
  }
  Check(Positions(out) == expected && !expected.empty(),
    "threshold 0.05: " + std::to_string(out.Points.size()) +
      " points, positions equal brute force");
  // The spike's +x neighbour has a gradient towards -x (the spike is at lower x).
  bool normal = false;
  b.SetThreshold(0); // every non-zero error, so the neighbour is a point
  b.Build(out);
  for (const auto& p : out.Points)
  {
    if (p.Position[0] == 6 && p.Position[1] == 6 && p.Position[2] == 7)
    {
      double n[3];
      strata::HybridVolumeFile::DecodeNormal(p.Normal, n);
      normal = n[0] < -0.999;
    }
  }
  Check(normal, "normal at (6, 6, 7) points to -x, towards the spike");
}

void OptimizedFilterBound(const Volume& v)
{
  std::cout << "Optimized filter: reconstruction - original <= bound at every original point\n";
  for (const double bound : { 0.0, 0.05, 0.3 })
  {
    for (const int f : { 2, 4 })
    {
      strata::HybridVolumeBuilder b;
      Configure(b, v);
      b.SetFactor(f);
      b.SetFilter(Filter::Optimized);
      b.SetOverestimationBound(bound);
      strata::HybridVolumeFile out;
      b.Build(out);
      double over = -1e9;
      for (int z = 0; z < v.N[2]; ++z)
        for (int y = 0; y < v.N[1]; ++y)
          for (int x = 0; x < v.N[0]; ++x)
          {
            over = std::max(over, out.Reconstruct(x, y, z) - v.At(x, y, z));
          }
      // 1e-12: the double rounding of the trilinear sum; the stored values round down.
      Check(out.LowResolution.size() > 0 && over <= bound + 1e-12,
        "bound " + std::to_string(bound) + ", factor " + std::to_string(f) +
          ": largest over-estimation " + std::to_string(over));
    }
  }
}

void ConstantVolume(const int factors[3])
{
  std::cout << "Constant volume: no error, no points\n";
  for (Filter filter : { Filter::Box, Filter::Linear, Filter::Cubic, Filter::Optimized })
  {
    Volume c{ { 10, 9, 7 }, std::vector<float>(630, 0.37f) };
    strata::HybridVolumeBuilder b;
    Configure(b, c);
    b.SetFactor(8, 4, 2);
    b.SetFilter(filter);
    strata::HybridVolumeFile out;
    const bool built = b.Build(out);
    Check(built && out.Points.empty() && out.LowDimensions[0] == 3,
      "filter " + std::to_string(static_cast<int>(filter)) +
        ", factors 8,4,2: " + std::to_string(out.Points.size()) + " points");
  }
}

void BoundedMemory()
{
  std::cout << "Bounded memory: a limit of a few slices gives the same output\n";
  const Volume big = Smooth(48, 40, 30, true); // 7680 bytes a slice, 230400 in all
  strata::HybridVolumeBuilder b;
  int reads = 0;
  Configure(b, big, &reads);
  b.SetFactor(4);
  b.SetThreshold(0.3);
  std::vector<double> progress;
  b.SetProgressCallback([&](double p) { progress.push_back(p); });
  strata::HybridVolumeFile whole, bounded;
  b.Build(whole);
  const size_t wholePeak = b.GetPeakSlicesHeld();
  bool monotone = !progress.empty() && progress.back() == 1.0;
  for (size_t i = 1; i < progress.size(); ++i)
  {
    monotone = monotone && progress[i] >= progress[i - 1];
  }
  b.SetMemoryLimit(0.045); // 47185 bytes: 6 slices, 3 for the differences, chunks of 3
  reads = 0;
  b.Build(bounded);
  Check(SameOutput(whole, bounded) && !whole.Points.empty(),
    "identical output (" + std::to_string(whole.Points.size()) + " points) at 0.045 MB");
  Check(b.GetPeakSlicesHeld() <= 6 && wholePeak >= 30,
    "peak slices held " + std::to_string(b.GetPeakSlicesHeld()) + " (unbounded: " +
      std::to_string(wholePeak) + "), slices read " + std::to_string(reads) + " (two passes)");
  Check(reads == 60, "each slice read exactly once per pass");
  Check(monotone, "progress non-decreasing, ends at 1");
  b.SetMemoryLimit(0.02);
  const bool refused = !b.Build(bounded);
  Check(refused, "too small a limit is refused: " + b.GetErrorMessage());
}

void NormalEncoding()
{
  std::cout << "Normal encoding (octahedral, 8+8 bits)\n";
  double worst = 0;
  uint32_t h = 99;
  for (int i = 0; i < 20000; ++i)
  {
    double d[3];
    for (double& c : d)
    {
      h = h * 1664525u + 1013904223u;
      c = (h >> 8) / 8388608.0 - 1.0;
    }
    const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double n[3];
    strata::HybridVolumeFile::DecodeNormal(
      strata::HybridVolumeFile::EncodeNormal(d[0], d[1], d[2]), n);
    const double dot = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / l;
    worst = std::max(worst, std::acos(std::min(1.0, dot)) * 180 / 3.14159265358979);
  }
  Check(worst < 1.2, "largest angular error " + std::to_string(worst) + " degrees");
}

void FileRoundTrip(const Volume& v, const strata_test::TestPaths& paths)
{
  std::cout << "File round trip and validation\n";
  strata::HybridVolumeBuilder b;
  Configure(b, v);
  b.SetFactor(2, 4, 2);
  b.SetFilter(Filter::Optimized);
  b.SetOverestimationBound(0.05);
  b.SetThreshold(0.1);
  strata::HybridVolumeFile out, back;
  b.Build(out);
  const std::string path = paths.Output + "/TestHybridVolumeBuilder.shv";
  const bool written = out.Write(path);
  const bool read = back.Read(path);
  bool same = read && SameOutput(out, back) && back.Filter == out.Filter &&
              back.OverestimationBound == out.OverestimationBound &&
              back.Threshold == out.Threshold;
  for (int a = 0; a < 3; ++a)
  {
    same = same && back.Dimensions[a] == out.Dimensions[a] && back.Factor[a] == out.Factor[a] &&
           back.Spacing[a] == out.Spacing[a] && back.Origin[a] == out.Origin[a] &&
           back.LowDimensions[a] == out.LowDimensions[a] &&
           back.ErrorGridStep[a] == out.ErrorGridStep[a];
  }
  Check(written && same,
    "read back bit-exact: " + std::to_string(back.Points.size()) + " points, " +
      std::to_string(back.LowResolution.size()) + " low-resolution values");
  Check(!std::ifstream(path + ".partial").good(), "no temporary file left behind");
  const std::string bytes = Slurp(path);
  Check(bytes.size() == 160 + 4 * out.LowResolution.size() + 16 * out.Points.size(),
    "file size = 160 + 4 * low values + 16 * points = " + std::to_string(bytes.size()));

  const std::string bad = path + ".bad";
  auto rejects = [&](const std::string& content, const std::string& what)
  {
    Spit(bad, content);
    strata::HybridVolumeFile f;
    const bool ok = f.Read(bad);
    Check(!ok && !f.GetErrorMessage().empty() && f.Points.empty(),
      what + ": " + f.GetErrorMessage().substr(f.GetErrorMessage().find(": ") + 2));
  };
  rejects(bytes.substr(0, 100), "truncated header");
  rejects(bytes.substr(0, bytes.size() - 5), "truncated points");
  std::string flipped = bytes;
  flipped[bytes.size() - 3] ^= 0x10;
  rejects(flipped, "flipped payload bit");
  std::string absurd = bytes;
  const int32_t huge = 2000000000;
  std::memcpy(&absurd[16], &huge, 4);
  rejects(absurd, "absurd dimension");
  std::string count = bytes;
  const uint64_t many = 1ull << 60;
  std::memcpy(&count[144], &many, 8);
  rejects(count, "absurd point count");
  std::string magic = bytes;
  magic[0] = 'X';
  rejects(magic, "bad magic");
  std::string version = bytes;
  version[8] = 7;
  rejects(version, "unknown version");
  rejects(std::string(), "empty file");
  strata::HybridVolumeFile missing;
  const bool missingRefused = !missing.Read(path + ".missing");
  Check(missingRefused, "missing file: " + missing.GetErrorMessage());
  std::remove(bad.c_str());
  std::remove(path.c_str());
}

void BadSettings(const Volume& v)
{
  std::cout << "Bad settings are refused\n";
  strata::HybridVolumeBuilder b;
  Configure(b, v);
  strata::HybridVolumeFile out;
  b.SetFactor(3);
  bool refused = !b.Build(out);
  Check(refused, b.GetErrorMessage());
  b.SetFactor(2);
  b.SetErrorGridStep(0);
  refused = !b.Build(out);
  Check(refused, b.GetErrorMessage());
}

}

int TestHybridVolumeBuilder(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  // 13 x 11 x 9 with factors 2, 4, 2: 12 / 4 is even but 10 / 4 is not.
  const Volume v = Smooth(13, 11, 9, true);
  const int factors[3] = { 2, 4, 2 };
  strata_test::RunSubTests(
    {
      { "LowResolutionVolume", [&] { LowResolutionVolume(v, factors); } },
      { "ErrorFieldAndPointCounts", [&] { ErrorFieldAndPointCounts(v, factors); } },
      { "PlantedSpike", PlantedSpike },
      { "OptimizedFilterBound", [&] { OptimizedFilterBound(v); } },
      { "ConstantVolume", [&] { ConstantVolume(factors); } },
      { "BoundedMemory", BoundedMemory },
      { "NormalEncoding", NormalEncoding },
      { "FileRoundTrip", [&] { FileRoundTrip(v, paths); } },
      { "BadSettings", [&] { BadSettings(v); } },
    },
    [] { return failures; });

  std::cout << (failures ? "FAILED: " + std::to_string(failures) + " checks\n" : "all passed\n");
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
