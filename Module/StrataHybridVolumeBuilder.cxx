// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataHybridVolumeBuilder.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <queue>
#include <vector>

namespace strata
{

namespace
{
// Taps of the normalised 1-D filter: weight w[d + radius] for offsets d in [-radius, radius].
struct Taps
{
  int Radius = 0;
  std::vector<double> W;
};

double CatmullRom(double d)
{
  d = std::fabs(d);
  if (d < 1)
  {
    return 1.5 * d * d * d - 2.5 * d * d + 1;
  }
  if (d < 2)
  {
    return -0.5 * d * d * d + 2.5 * d * d - 4 * d + 2;
  }
  return 0;
}

Taps MakeTaps(strata::HybridVolumeFile::FilterType filter, int f)
{
  Taps taps;
  taps.Radius = 2 * f;
  double sum = 0;
  for (int d = -taps.Radius; d <= taps.Radius; ++d)
  {
    const double ad = std::abs(d);
    double w = 0;
    switch (filter)
    {
      case strata::HybridVolumeFile::FilterType::Box:
        w = 2 * ad < f ? 1.0 : (2 * ad == f ? 0.5 : 0.0);
        break;
      case strata::HybridVolumeFile::FilterType::Linear:
        w = ad < f ? 1 - ad / f : 0.0;
        break;
      case strata::HybridVolumeFile::FilterType::Cubic:
      case strata::HybridVolumeFile::FilterType::Optimized:
        w = CatmullRom(ad / f);
        break;
    }
    taps.W.push_back(w);
    sum += w;
  }
  for (double& w : taps.W)
  {
    w /= sum;
  }
  // Trim zero weights at both ends.
  while (taps.Radius > 0 && taps.W.front() == 0 && taps.W.back() == 0)
  {
    taps.W.erase(taps.W.begin());
    taps.W.pop_back();
    --taps.Radius;
  }
  return taps;
}

int Clamp(int v, int n)
{
  return std::min(std::max(v, 0), n - 1);
}

// Filters one original slice (n0 x n1) to the low-resolution x-y grid (l0 x l1), and, when
// `mins` is given, the minimum over each low-resolution point's footprint |x - c| < f.
void ReduceSlice(const float* s,
  const int n[2],
  const int l[2],
  const int f[2],
  const Taps t[2],
  std::vector<double>& sum,
  std::vector<double>* mins)
{
  std::vector<double> rowSum(static_cast<size_t>(l[0]) * n[1]);
  std::vector<double> rowMin(mins ? rowSum.size() : 0);
  for (int y = 0; y < n[1]; ++y)
  {
    const float* row = s + static_cast<size_t>(y) * n[0];
    for (int L = 0; L < l[0]; ++L)
    {
      const int c = L * f[0];
      double acc = 0;
      for (int d = -t[0].Radius; d <= t[0].Radius; ++d)
      {
        acc += t[0].W[d + t[0].Radius] * row[Clamp(c + d, n[0])];
      }
      rowSum[static_cast<size_t>(y) * l[0] + L] = acc;
      if (mins)
      {
        double m = std::numeric_limits<double>::infinity();
        for (int d = 1 - f[0]; d <= f[0] - 1; ++d)
        {
          m = std::min(m, static_cast<double>(row[Clamp(c + d, n[0])]));
        }
        rowMin[static_cast<size_t>(y) * l[0] + L] = m;
      }
    }
  }
  sum.assign(static_cast<size_t>(l[0]) * l[1], 0.0);
  if (mins)
  {
    mins->assign(sum.size(), std::numeric_limits<double>::infinity());
  }
  for (int L1 = 0; L1 < l[1]; ++L1)
  {
    const int c = L1 * f[1];
    for (int d = -t[1].Radius; d <= t[1].Radius; ++d)
    {
      const double w = t[1].W[d + t[1].Radius];
      const double* src = &rowSum[static_cast<size_t>(Clamp(c + d, n[1])) * l[0]];
      double* dst = &sum[static_cast<size_t>(L1) * l[0]];
      for (int L0 = 0; L0 < l[0]; ++L0)
      {
        dst[L0] += w * src[L0];
      }
    }
    if (mins)
    {
      for (int d = 1 - f[1]; d <= f[1] - 1; ++d)
      {
        const double* src = &rowMin[static_cast<size_t>(Clamp(c + d, n[1])) * l[0]];
        double* dst = &(*mins)[static_cast<size_t>(L1) * l[0]];
        for (int L0 = 0; L0 < l[0]; ++L0)
        {
          dst[L0] = std::min(dst[L0], src[L0]);
        }
      }
    }
  }
}

// Trilinear position of original index x along an axis: low-resolution cell and weight.
void CellOf(int x, int f, int l, int& cell, double& t)
{
  if (l < 2)
  {
    cell = 0;
    t = 0;
    return;
  }
  cell = std::min(x / f, l - 2);
  t = static_cast<double>(x - cell * f) / f;
}

struct Candidate
{
  double Magnitude;
  uint64_t Index;
  strata::HybridVolumeFile::Point Point;
};

// True when a ranks before b: larger |error|, then smaller linear index.
bool RanksBefore(const Candidate& a, const Candidate& b)
{
  return a.Magnitude > b.Magnitude || (a.Magnitude == b.Magnitude && a.Index < b.Index);
}
}

// Hands out original slices in increasing z, reading chunks through the source and keeping
// only the slices still asked for.
class HybridVolumeBuilder::SliceReader
{
public:
  SliceReader(const SlabSource& source, int nz, size_t sliceValues, int chunk)
    : Source(source)
    , Nz(nz)
    , SliceValues(sliceValues)
    , Chunk(chunk)
  {
  }

  // Makes slices [lo, hi] available (lo never decreases); false on a read error.
  bool Require(int lo, int hi)
  {
    while (!this->Slices.empty() && this->First < lo)
    {
      this->Slices.pop_front();
      ++this->First;
    }
    if (this->Slices.empty())
    {
      this->First = std::max(this->Next, lo);
      // Slices below lo are never asked for again: skip reading them.
      this->Next = std::max(this->Next, lo);
    }
    while (this->Next <= hi)
    {
      const int count = std::min(this->Chunk, this->Nz - this->Next);
      this->Buffer.resize(static_cast<size_t>(count) * this->SliceValues);
      this->Peak = std::max(this->Peak, this->Slices.size() + static_cast<size_t>(this->Chunk));
      if (!this->Source(this->Next, count, this->Buffer.data()))
      {
        return false;
      }
      for (int i = 0; i < count; ++i)
      {
        const float* b = this->Buffer.data() + static_cast<size_t>(i) * this->SliceValues;
        this->Slices.emplace_back(b, b + this->SliceValues);
      }
      this->Next += count;
      this->Buffer.clear();
      this->Buffer.shrink_to_fit();
      while (!this->Slices.empty() && this->First < lo)
      {
        this->Slices.pop_front();
        ++this->First;
      }
    }
    return true;
  }

  const float* Slice(int z) const { return this->Slices[z - this->First].data(); }
  size_t GetPeak() const { return this->Peak; }

private:
  const SlabSource& Source;
  int Nz;
  size_t SliceValues;
  int Chunk;
  int Next = 0;
  int First = 0;
  std::deque<std::vector<float>> Slices;
  std::vector<float> Buffer;
  size_t Peak = 0;
};

void HybridVolumeBuilder::SetInput(const int dims[3],
  const double spacing[3],
  const double origin[3],
  SlabSource source)
{
  for (int a = 0; a < 3; ++a)
  {
    this->Dimensions[a] = dims[a];
    this->Spacing[a] = spacing[a];
    this->Origin[a] = origin[a];
  }
  this->Source = std::move(source);
}

void HybridVolumeBuilder::SetFactor(int fx, int fy, int fz)
{
  this->Factor[0] = fx;
  this->Factor[1] = fy;
  this->Factor[2] = fz;
}

void HybridVolumeBuilder::SetErrorGridStep(int sx, int sy, int sz)
{
  this->ErrorGridStep[0] = sx;
  this->ErrorGridStep[1] = sy;
  this->ErrorGridStep[2] = sz;
}

bool HybridVolumeBuilder::Build(strata::HybridVolumeFile& out)
{
  out = strata::HybridVolumeFile();
  this->ErrorMessage.clear();
  this->PeakSlicesHeld = 0;
  for (int a = 0; a < 3; ++a)
  {
    out.Dimensions[a] = this->Dimensions[a];
    out.Spacing[a] = this->Spacing[a];
    out.Origin[a] = this->Origin[a];
    out.Factor[a] = this->Factor[a];
    out.ErrorGridStep[a] = this->ErrorGridStep[a];
    out.LowDimensions[a] =
      strata::HybridVolumeFile::GetLowResolutionDimension(this->Dimensions[a], this->Factor[a]);
  }
  out.Filter = this->Filter;
  out.OverestimationBound = this->Filter == FilterType::Optimized ? this->OverestimationBound : 0;
  out.Threshold = this->Threshold;
  out.PointBudget = this->PointBudget;
  // The file's own checks cover dimensions, factors, steps, spacing and origin.
  std::string invalid = out.Validate();
  if (invalid.empty() && !this->Source)
  {
    invalid = "no slab source";
  }
  if (invalid.empty() && (!(this->Threshold >= 0) || !(this->OverestimationBound >= 0)))
  {
    invalid = "threshold and over-estimation bound must be >= 0";
  }
  const size_t sliceValues = static_cast<size_t>(this->Dimensions[0]) * this->Dimensions[1];
  // Pass 2 holds 3 slices for the central differences besides the chunk being read.
  const double sliceBytes = static_cast<double>(sliceValues) * sizeof(float);
  const double slicesAllowed = std::floor(this->MemoryLimit * 1048576.0 / sliceBytes);
  if (invalid.empty() && !(slicesAllowed >= 4))
  {
    invalid = "memory limit of " + std::to_string(this->MemoryLimit) +
              " MB holds fewer than the 4 slices of " + std::to_string(sliceBytes / 1048576.0) +
              " MB needed";
  }
  if (!invalid.empty())
  {
    this->ErrorMessage = "HybridVolumeBuilder: " + invalid;
    out = strata::HybridVolumeFile();
    return false;
  }
  const int chunk =
    static_cast<int>(std::min(slicesAllowed - 3, static_cast<double>(this->Dimensions[2])));
  bool ok;
  {
    SliceReader reader(this->Source, this->Dimensions[2], sliceValues, chunk);
    ok = this->BuildLowResolution(out, reader);
    this->PeakSlicesHeld = reader.GetPeak();
  }
  if (ok)
  {
    SliceReader reader(this->Source, this->Dimensions[2], sliceValues, chunk);
    ok = this->BuildPoints(out, reader);
    this->PeakSlicesHeld = std::max(this->PeakSlicesHeld, reader.GetPeak());
  }
  if (!ok)
  {
    this->ErrorMessage = "HybridVolumeBuilder: " + this->ErrorMessage;
    out = strata::HybridVolumeFile();
    return false;
  }
  if (this->Progress)
  {
    this->Progress(1.0);
  }
  return true;
}

bool HybridVolumeBuilder::BuildLowResolution(strata::HybridVolumeFile& out, SliceReader& reader)
{
  const int* n = this->Dimensions;
  const int* l = out.LowDimensions;
  const int* f = this->Factor;
  const bool optimized = this->Filter == FilterType::Optimized;
  const Taps taps[3] = {
    MakeTaps(this->Filter, f[0]), MakeTaps(this->Filter, f[1]), MakeTaps(this->Filter, f[2])
  };
  const size_t planeValues = static_cast<size_t>(l[0]) * l[1];
  out.LowResolution.assign(planeValues * l[2], 0.0f);

  // Filtered x-y planes of original slices [planeFirst, planeFirst + planes.size()).
  std::deque<std::vector<double>> sums, mins;
  int planeFirst = 0;
  int next = 0;
  for (int L2 = 0; L2 < l[2]; ++L2)
  {
    const int c = L2 * f[2];
    const int lo = Clamp(c - std::max(taps[2].Radius, f[2] - 1), n[2]);
    const int hi = Clamp(c + std::max(taps[2].Radius, f[2] - 1), n[2]);
    while (planeFirst < lo && !sums.empty())
    {
      sums.pop_front();
      if (optimized)
      {
        mins.pop_front();
      }
      ++planeFirst;
    }
    for (; next <= hi; ++next)
    {
      if (!reader.Require(next, next))
      {
        this->ErrorMessage = "slab source failed at slice " + std::to_string(next);
        return false;
      }
      sums.emplace_back();
      if (optimized)
      {
        mins.emplace_back();
      }
      ReduceSlice(
        reader.Slice(next), n, l, f, taps, sums.back(), optimized ? &mins.back() : nullptr);
    }
    std::vector<double> sum(planeValues, 0.0);
    for (int d = -taps[2].Radius; d <= taps[2].Radius; ++d)
    {
      const double w = taps[2].W[d + taps[2].Radius];
      const std::vector<double>& src = sums[Clamp(c + d, n[2]) - planeFirst];
      for (size_t i = 0; i < planeValues; ++i)
      {
        sum[i] += w * src[i];
      }
    }
    float* dst = out.LowResolution.data() + planeValues * L2;
    for (size_t i = 0; i < planeValues; ++i)
    {
      double v = sum[i];
      if (optimized)
      {
        double m = std::numeric_limits<double>::infinity();
        for (int d = 1 - f[2]; d <= f[2] - 1; ++d)
        {
          m = std::min(m, mins[Clamp(c + d, n[2]) - planeFirst][i]);
        }
        v = std::min(v, m + this->OverestimationBound);
        float fv = static_cast<float>(v);
        // Round down so that the stored value still honours the cap.
        dst[i] = fv > v ? std::nextafter(fv, -std::numeric_limits<float>::infinity()) : fv;
      }
      else
      {
        dst[i] = static_cast<float>(v);
      }
    }
    if (this->Progress)
    {
      this->Progress(0.5 * (L2 + 1) / l[2]);
    }
  }
  return true;
}

bool HybridVolumeBuilder::BuildPoints(strata::HybridVolumeFile& out, SliceReader& reader)
{
  const int* n = this->Dimensions;
  const int* l = out.LowDimensions;
  const int* f = this->Factor;
  const int* s = this->ErrorGridStep;
  const int e[3] = { (n[0] - 1) / s[0] + 1, (n[1] - 1) / s[1] + 1, (n[2] - 1) / s[2] + 1 };
  std::vector<int> cell[3];
  std::vector<double> weight[3];
  for (int a = 0; a < 3; ++a)
  {
    cell[a].resize(e[a]);
    weight[a].resize(e[a]);
    for (int i = 0; i < e[a]; ++i)
    {
      CellOf(i * s[a], f[a], l[a], cell[a][i], weight[a][i]);
    }
  }
  auto low = [&](int i, int j, int k) -> double
  {
    return out
      .LowResolution[(static_cast<size_t>(std::min(k, l[2] - 1)) * l[1] + std::min(j, l[1] - 1)) *
                       l[0] +
                     std::min(i, l[0] - 1)];
  };
  const bool budget = this->PointBudget > 0;
  // Budget: min-heap on rank, the worst kept candidate on top.
  auto worseOnTop = [](const Candidate& a, const Candidate& b) { return RanksBefore(a, b); };
  std::priority_queue<Candidate, std::vector<Candidate>, decltype(worseOnTop)> heap(worseOnTop);
  std::vector<strata::HybridVolumeFile::Point> points;

  for (int k = 0; k < e[2]; ++k)
  {
    const int z = k * s[2];
    const int zlo = std::max(z - 1, 0), zhi = std::min(z + 1, n[2] - 1);
    if (!reader.Require(zlo, zhi))
    {
      this->ErrorMessage =
        "slab source failed reading slices " + std::to_string(zlo) + " to " + std::to_string(zhi);
      return false;
    }
    const float* sz = reader.Slice(z);
    const float* szlo = reader.Slice(zlo);
    const float* szhi = reader.Slice(zhi);
    const double tz = weight[2][k];
    const int cz = cell[2][k];
    for (int j = 0; j < e[1]; ++j)
    {
      const int y = j * s[1];
      const double ty = weight[1][j];
      const int cy = cell[1][j];
      for (int i = 0; i < e[0]; ++i)
      {
        const int x = i * s[0];
        const double tx = weight[0][i];
        const int cx = cell[0][i];
        double r = 0;
        for (int dz = 0; dz < 2; ++dz)
        {
          for (int dy = 0; dy < 2; ++dy)
          {
            for (int dx = 0; dx < 2; ++dx)
            {
              const double w = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty) * (dz ? tz : 1 - tz);
              if (w != 0)
              {
                r += w * low(cx + dx, cy + dy, cz + dz);
              }
            }
          }
        }
        const size_t at = static_cast<size_t>(y) * n[0] + x;
        const double value = sz[at];
        const double error = value - r;
        const double magnitude =
          this->ImportanceFunction ? this->ImportanceFunction(value, r) : std::fabs(error);
        if (!(magnitude > this->Threshold))
        {
          continue;
        }
        const uint64_t index = (static_cast<uint64_t>(z) * n[1] + y) * n[0] + x;
        if (budget && heap.size() == this->PointBudget &&
            !RanksBefore(Candidate{ magnitude, index, {} }, heap.top()))
        {
          continue;
        }
        // Central differences in world units, one-sided at the border.
        const int xlo = std::max(x - 1, 0), xhi = std::min(x + 1, n[0] - 1);
        const int ylo = std::max(y - 1, 0), yhi = std::min(y + 1, n[1] - 1);
        double g[3] = { 0, 0, 0 };
        if (xhi > xlo)
        {
          g[0] =
            (sz[static_cast<size_t>(y) * n[0] + xhi] - sz[static_cast<size_t>(y) * n[0] + xlo]) /
            ((xhi - xlo) * this->Spacing[0]);
        }
        if (yhi > ylo)
        {
          g[1] =
            (sz[static_cast<size_t>(yhi) * n[0] + x] - sz[static_cast<size_t>(ylo) * n[0] + x]) /
            ((yhi - ylo) * this->Spacing[1]);
        }
        if (zhi > zlo)
        {
          g[2] = (szhi[at] - szlo[at]) / ((zhi - zlo) * this->Spacing[2]);
        }
        strata::HybridVolumeFile::Point p;
        p.Position[0] = static_cast<uint16_t>(x);
        p.Position[1] = static_cast<uint16_t>(y);
        p.Position[2] = static_cast<uint16_t>(z);
        p.Normal = strata::HybridVolumeFile::EncodeNormal(g[0], g[1], g[2]);
        p.Value = static_cast<float>(value);
        p.Error = static_cast<float>(error);
        if (budget)
        {
          if (heap.size() == this->PointBudget)
          {
            heap.pop();
          }
          heap.push(Candidate{ magnitude, index, p });
        }
        else
        {
          points.push_back(p);
        }
      }
    }
    if (this->Progress)
    {
      this->Progress(0.5 + 0.5 * (k + 1) / e[2]);
    }
  }
  if (budget)
  {
    std::vector<Candidate> kept;
    kept.reserve(heap.size());
    for (; !heap.empty(); heap.pop())
    {
      kept.push_back(heap.top());
    }
    std::sort(kept.begin(),
      kept.end(),
      [](const Candidate& a, const Candidate& b) { return a.Index < b.Index; });
    for (const Candidate& c : kept)
    {
      points.push_back(c.Point);
    }
  }
  out.Points = std::move(points);
  return true;
}
}
