// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataVolumeBrickTree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace strata
{

namespace
{
constexpr float Inf = std::numeric_limits<float>::infinity();

int BricksAlong(int n, int stride)
{
  return n <= 1 ? 1 : static_cast<int>((static_cast<int64_t>(n) - 1 + stride - 1) / stride);
}

// Calls f(T{}) with T the C++ type of `type`.
template<typename F>
void Dispatch(VolumeBrickTree::ScalarType type, F&& f)
{
  switch (type)
  {
    case VolumeBrickTree::ScalarType::UInt8:
      f(uint8_t{});
      break;
    case VolumeBrickTree::ScalarType::UInt16:
      f(uint16_t{});
      break;
    case VolumeBrickTree::ScalarType::Int16:
      f(int16_t{});
      break;
    case VolumeBrickTree::ScalarType::Float32:
      f(float{});
      break;
  }
}

template<typename T>
T FromDouble(double v)
{
  if constexpr (std::is_floating_point<T>::value)
  {
    return static_cast<T>(v);
  }
  else
  {
    // Round half up; v is a convex combination of T values, so it stays in T's range.
    return static_cast<T>(std::floor(v + 0.5));
  }
}
}

int VolumeBrickTree::GetScalarSize(ScalarType type)
{
  switch (type)
  {
    case ScalarType::UInt8:
      return 1;
    case ScalarType::UInt16:
    case ScalarType::Int16:
      return 2;
    case ScalarType::Float32:
      return 4;
  }
  return 0;
}

bool VolumeBrickTree::Build(const uint8_t* scalars, const int dims[3], int brickSize)
{
  return this->Build(scalars, ScalarType::UInt8, dims, brickSize);
}

bool VolumeBrickTree::Build(const uint16_t* scalars, const int dims[3], int brickSize)
{
  return this->Build(scalars, ScalarType::UInt16, dims, brickSize);
}

bool VolumeBrickTree::Build(const int16_t* scalars, const int dims[3], int brickSize)
{
  return this->Build(scalars, ScalarType::Int16, dims, brickSize);
}

bool VolumeBrickTree::Build(const float* scalars, const int dims[3], int brickSize)
{
  return this->Build(scalars, ScalarType::Float32, dims, brickSize);
}

bool VolumeBrickTree::Build(const void* scalars, ScalarType type, const int dims[3], int brickSize)
{
  this->Levels.clear();
  this->Nodes.clear();
  this->ErrorMessage.clear();
  this->Input = nullptr;
  this->BrickSize = 0;
  if (!scalars)
  {
    this->ErrorMessage = "no scalars";
    return false;
  }
  if (!this->BuildLevels(dims, brickSize))
  {
    return false;
  }
  this->Type = type;
  this->Input = scalars;
  for (int l = 0; l < this->GetNumberOfLevels(); ++l)
  {
    if (l > 0)
    {
      Dispatch(type, [&](auto t) { this->Downsample<decltype(t)>(l); });
    }
    Dispatch(type, [&](auto t) { this->ComputeRanges<decltype(t)>(l); });
  }
  return true;
}

bool VolumeBrickTree::BuildLevels(const int dims[3], int brickSize)
{
  // 2^40 voxels (a terabyte of bytes) is beyond any volume held in memory.
  const double voxels = static_cast<double>(dims[0]) * dims[1] * dims[2];
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || voxels > 1099511627776.0)
  {
    this->ErrorMessage = "volume of " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) +
                         " x " + std::to_string(dims[2]) + " voxels is empty, absent or too large";
    return false;
  }
  // Above 1024 a brick (1G voxels) would exceed any 3-D texture.
  if (brickSize < 2 || brickSize > 1024)
  {
    this->ErrorMessage = "brick size " + std::to_string(brickSize) + " is not in [2, 1024]";
    return false;
  }
  this->BrickSize = brickSize;
  const int stride = brickSize - 1;

  int n[3] = { dims[0], dims[1], dims[2] };
  int64_t offset = 0;
  for (;;)
  {
    Level level;
    for (int a = 0; a < 3; ++a)
    {
      level.Dims[a] = n[a];
      level.Bricks[a] = BricksAlong(n[a], stride);
    }
    level.Offset = static_cast<int>(offset);
    offset += static_cast<int64_t>(level.Bricks[0]) * level.Bricks[1] * level.Bricks[2];
    this->Levels.push_back(std::move(level));
    // Node ids are ints (and GPU-friendly); only tiny bricks on huge volumes get here.
    if (offset > std::numeric_limits<int>::max())
    {
      this->ErrorMessage = "brick size " + std::to_string(brickSize) +
                           " makes more than 2^31 bricks; use larger bricks";
      this->Levels.clear();
      this->Input = nullptr;
      this->BrickSize = 0;
      return false;
    }
    if (offset == this->Levels.back().Offset + 1)
    {
      break; // one brick holds the level: the root
    }
    for (int a = 0; a < 3; ++a)
    {
      n[a] = n[a] > 1 ? n[a] / 2 + 1 : 1;
    }
  }

  this->Nodes.resize(static_cast<size_t>(offset));
  for (int l = 0; l < this->GetNumberOfLevels(); ++l)
  {
    const int* b = this->Levels[l].Bricks;
    for (int k = 0; k < b[2]; ++k)
      for (int j = 0; j < b[1]; ++j)
        for (int i = 0; i < b[0]; ++i)
        {
          Node& node = this->Nodes[this->GetNodeId(l, i, j, k)];
          node.Level = l;
          node.Index[0] = i;
          node.Index[1] = j;
          node.Index[2] = k;
        }
  }
  return true;
}

bool VolumeBrickTree::BuildStructure(const int dims[3],
  int brickSize,
  const float* minima,
  const float* maxima,
  ScalarType type)
{
  this->Levels.clear();
  this->Nodes.clear();
  this->ErrorMessage.clear();
  this->Input = nullptr;
  this->BrickSize = 0;
  if (!minima || !maxima || !this->BuildLevels(dims, brickSize))
  {
    if (this->ErrorMessage.empty())
      this->ErrorMessage = "no brick ranges";
    return false;
  }
  this->Type = type;
  // Finest level first, so every child's subtree range is known before its parent's.
  for (size_t id = 0; id < this->Nodes.size(); ++id)
  {
    Node& node = this->Nodes[id];
    node.Min = node.SubtreeMin = minima[id];
    node.Max = node.SubtreeMax = maxima[id];
    int children[8];
    const int count = this->GetChildren(static_cast<int>(id), children);
    for (int c = 0; c < count; ++c)
    {
      node.SubtreeMin = std::min(node.SubtreeMin, this->Nodes[children[c]].SubtreeMin);
      node.SubtreeMax = std::max(node.SubtreeMax, this->Nodes[children[c]].SubtreeMax);
    }
  }
  return true;
}

const void* VolumeBrickTree::GetLevelData(int l) const
{
  return l == 0 ? this->Input : static_cast<const void*>(this->Levels[l].Storage.data());
}

double VolumeBrickTree::GetVoxel(int l, int i, int j, int k) const
{
  const int* d = this->Levels[l].Dims;
  const size_t idx =
    (static_cast<size_t>(std::clamp(k, 0, d[2] - 1)) * d[1] + std::clamp(j, 0, d[1] - 1)) * d[0] +
    std::clamp(i, 0, d[0] - 1);
  double v = 0.0;
  Dispatch(
    this->Type, [&](auto t) { v = static_cast<const decltype(t)*>(this->GetLevelData(l))[idx]; });
  return v;
}

template<typename T>
void VolumeBrickTree::Downsample(int l)
{
  const T* in = static_cast<const T*>(this->GetLevelData(l - 1));
  const int* fd = this->Levels[l - 1].Dims;
  const int* cd = this->Levels[l].Dims;
  Level& coarse = this->Levels[l];
  coarse.Storage.resize(static_cast<size_t>(cd[0]) * cd[1] * cd[2] * sizeof(T));
  T* out = reinterpret_cast<T*>(coarse.Storage.data());

  // Separable [1 2 1] taps around fine 2v, clamped to the level; weights sum to 4 per axis.
  // Sums of integer inputs times these weights are exact in double, so integer types round
  // exactly once, at the end. NaN taps take no part (the weighted mean of the others; NaN only
  // where every tap is NaN), as strata::PagePoolWriter builds a pool's levels.
  constexpr bool holes = std::numeric_limits<T>::has_quiet_NaN;
  auto tap = [](int v, int d, int n) { return std::clamp(2 * v + d, 0, n - 1); };
  std::vector<double> filteredX(static_cast<size_t>(cd[0]) * fd[1]); // x done, y and z not
  std::vector<double> filteredW(holes ? filteredX.size() : 0);
  std::vector<double> acc(static_cast<size_t>(cd[0]) * cd[1]);
  std::vector<double> accW(holes ? acc.size() : 0);
  for (int cz = 0; cz < cd[2]; ++cz)
  {
    std::fill(acc.begin(), acc.end(), 0.0);
    std::fill(accW.begin(), accW.end(), 0.0);
    for (int dz = -1; dz <= 1; ++dz)
    {
      const double wz = dz == 0 ? 2.0 : 1.0;
      const T* slice = in + static_cast<size_t>(tap(cz, dz, fd[2])) * fd[0] * fd[1];
      for (int y = 0; y < fd[1]; ++y)
      {
        const T* row = slice + static_cast<size_t>(y) * fd[0];
        double* fx = filteredX.data() + static_cast<size_t>(y) * cd[0];
        for (int cx = 0; cx < cd[0]; ++cx)
        {
          if constexpr (holes)
          {
            fx[cx] = FilterTaps(
              row,
              cx,
              fd[0],
              [](T t) { return std::isnan(static_cast<double>(t)); },
              filteredW[static_cast<size_t>(y) * cd[0] + cx]);
          }
          else
          {
            fx[cx] = static_cast<double>(row[tap(cx, -1, fd[0])]) +
                     2.0 * static_cast<double>(row[tap(cx, 0, fd[0])]) +
                     static_cast<double>(row[tap(cx, 1, fd[0])]);
          }
        }
      }
      auto accumulate = [&](const std::vector<double>& filtered, std::vector<double>& sums)
      {
        for (int cy = 0; cy < cd[1]; ++cy)
        {
          const double* r0 = filtered.data() + static_cast<size_t>(tap(cy, -1, fd[1])) * cd[0];
          const double* r1 = filtered.data() + static_cast<size_t>(tap(cy, 0, fd[1])) * cd[0];
          const double* r2 = filtered.data() + static_cast<size_t>(tap(cy, 1, fd[1])) * cd[0];
          double* a = sums.data() + static_cast<size_t>(cy) * cd[0];
          for (int cx = 0; cx < cd[0]; ++cx)
          {
            a[cx] += wz * (r0[cx] + 2.0 * r1[cx] + r2[cx]);
          }
        }
      };
      accumulate(filteredX, acc);
      if (holes)
        accumulate(filteredW, accW);
    }
    T* o = out + static_cast<size_t>(cz) * cd[0] * cd[1];
    for (size_t q = 0; q < acc.size(); ++q)
    {
      if constexpr (holes)
        o[q] =
          accW[q] > 0.0 ? FromDouble<T>(acc[q] / accW[q]) : std::numeric_limits<T>::quiet_NaN();
      else
        o[q] = FromDouble<T>(acc[q] / 64.0);
    }
  }
}

template<typename T>
void VolumeBrickTree::ComputeRanges(int l)
{
  const T* data = static_cast<const T*>(this->GetLevelData(l));
  const Level& level = this->Levels[l];
  const int* d = level.Dims;
  const int s = this->GetBrickStride();
  for (int id = level.Offset;
       id < level.Offset + level.Bricks[0] * level.Bricks[1] * level.Bricks[2];
       ++id)
  {
    Node& node = this->Nodes[id];
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = node.Index[a] * s;
      hi[a] = std::min(lo[a] + s, d[a] - 1); // padding repeats these voxels: no new values
    }
    // NaN fails both comparisons and is ignored.
    float mn = Inf, mx = -Inf;
    for (int z = lo[2]; z <= hi[2]; ++z)
    {
      for (int y = lo[1]; y <= hi[1]; ++y)
      {
        const T* row = data + (static_cast<size_t>(z) * d[1] + y) * d[0];
        for (int x = lo[0]; x <= hi[0]; ++x)
        {
          const float v = static_cast<float>(row[x]);
          mn = v < mn ? v : mn;
          mx = v > mx ? v : mx;
        }
      }
    }
    node.Min = node.SubtreeMin = mn;
    node.Max = node.SubtreeMax = mx;
    int children[8];
    const int count = this->GetChildren(id, children);
    for (int c = 0; c < count; ++c)
    {
      node.SubtreeMin = std::min(node.SubtreeMin, this->Nodes[children[c]].SubtreeMin);
      node.SubtreeMax = std::max(node.SubtreeMax, this->Nodes[children[c]].SubtreeMax);
    }
  }
}

int VolumeBrickTree::GetParent(int id) const
{
  const Node& node = this->Nodes[id];
  if (node.Level + 1 >= this->GetNumberOfLevels())
  {
    return -1;
  }
  return this->GetNodeId(node.Level + 1, node.Index[0] / 2, node.Index[1] / 2, node.Index[2] / 2);
}

int VolumeBrickTree::GetChildren(int id, int children[8]) const
{
  const Node& node = this->Nodes[id];
  if (node.Level == 0)
  {
    return 0;
  }
  const int l = node.Level - 1;
  const int* b = this->Levels[l].Bricks;
  int count = 0;
  for (int k = 2 * node.Index[2]; k < std::min(2 * node.Index[2] + 2, b[2]); ++k)
  {
    for (int j = 2 * node.Index[1]; j < std::min(2 * node.Index[1] + 2, b[1]); ++j)
    {
      for (int i = 2 * node.Index[0]; i < std::min(2 * node.Index[0] + 2, b[0]); ++i)
      {
        children[count++] = this->GetNodeId(l, i, j, k);
      }
    }
  }
  return count;
}

void VolumeBrickTree::GetNodeBounds(int id, double bounds[6]) const
{
  const Node& node = this->Nodes[id];
  const double extent = static_cast<double>(this->GetBrickStride()) * (1 << node.Level);
  for (int a = 0; a < 3; ++a)
  {
    const double last = this->Levels[0].Dims[a] - 1;
    bounds[2 * a] = std::min(node.Index[a] * extent, last);
    bounds[2 * a + 1] = std::min((node.Index[a] + 1) * extent, last);
  }
}

template<typename T, typename O>
void VolumeBrickTree::Extract(int id, O* out) const
{
  const T* data = static_cast<const T*>(this->GetLevelData(this->Nodes[id].Level));
  const int* d = this->Levels[this->Nodes[id].Level].Dims;
  const int* index = this->Nodes[id].Index;
  const int B = this->BrickSize;
  const int s = this->GetBrickStride();
  for (int c = 0; c < B; ++c)
  {
    const int z = std::min(index[2] * s + c, d[2] - 1);
    for (int b = 0; b < B; ++b)
    {
      const int y = std::min(index[1] * s + b, d[1] - 1);
      const T* row = data + (static_cast<size_t>(z) * d[1] + y) * d[0];
      for (int a = 0; a < B; ++a)
      {
        *out++ = static_cast<O>(row[std::min(index[0] * s + a, d[0] - 1)]);
      }
    }
  }
}

void VolumeBrickTree::ExtractBrick(int id, float* out) const
{
  Dispatch(this->Type, [&](auto t) { this->Extract<decltype(t)>(id, out); });
}

void VolumeBrickTree::ExtractBrickNative(int id, void* out) const
{
  Dispatch(this->Type,
    [&](auto t)
    {
      using T = decltype(t);
      this->Extract<T>(id, static_cast<T*>(out));
    });
}

size_t VolumeBrickTree::GetMemorySize() const
{
  size_t bytes = this->Nodes.size() * sizeof(Node);
  for (const Level& level : this->Levels)
  {
    bytes += level.Storage.size();
  }
  return bytes;
}
}
