// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataVolumeSkipGrid.h"

#include <algorithm>
#include <array>
#include <limits>

namespace strata
{

namespace
{
using Dims = std::array<long long, 3>;

// Ranges along one axis: `in` (dims d, x fastest) reduced to cells [c C, (c + 1) C] of that
// axis, clamped to its last point; the other axes keep their size. NaN fails both comparisons
// and is left out.
void ReduceAxis(const float* inMin,
  const float* inMax,
  Dims& d,
  int axis,
  int cells,
  int C,
  std::vector<float>& outMin,
  std::vector<float>& outMax)
{
  Dims o = d;
  o[axis] = cells;
  outMin.assign(o[0] * o[1] * o[2], std::numeric_limits<float>::infinity());
  outMax.assign(outMin.size(), -std::numeric_limits<float>::infinity());
  const Dims stride = { 1, d[0], d[0] * d[1] };
  for (long long z = 0; z < o[2]; ++z)
    for (long long y = 0; y < o[1]; ++y)
      for (long long x = 0; x < o[0]; ++x)
      {
        const Dims p = { x, y, z };
        const long long c = p[axis];
        const long long first = c * C, last = std::min((c + 1) * C, d[axis] - 1);
        long long at = 0;
        for (int a = 0; a < 3; ++a)
          at += (a == axis ? first : p[a]) * stride[a];
        float lo = outMin[x + o[0] * (y + o[1] * z)], hi = -lo;
        for (long long v = first; v <= last; ++v, at += stride[axis])
        {
          lo = inMin[at] < lo ? inMin[at] : lo;
          hi = inMax[at] > hi ? inMax[at] : hi;
        }
        outMin[x + o[0] * (y + o[1] * z)] = lo;
        outMax[x + o[0] * (y + o[1] * z)] = hi;
      }
  d = o;
}
}

void VolumeSkipGrid::Build(const float* scalars, const int dims[3], int cellSize)
{
  this->CellSize = std::max(cellSize, 1);
  const int C = this->CellSize;
  for (int a = 0; a < 3; ++a)
    this->CellDims[a] = std::max(1, (dims[a] - 1 + C - 1) / C);
  // Separable: x ranges of every row, then y, then z.
  Dims d = { dims[0], dims[1], dims[2] };
  std::vector<float> minA, maxA, minB, maxB;
  ReduceAxis(scalars, scalars, d, 0, this->CellDims[0], C, minA, maxA);
  ReduceAxis(minA.data(), maxA.data(), d, 1, this->CellDims[1], C, minB, maxB);
  ReduceAxis(minB.data(), maxB.data(), d, 2, this->CellDims[2], C, this->Min, this->Max);
  this->Distance.assign(this->Min.size(), 255);
}

void VolumeSkipGrid::BuildFromRanges(const int cellDims[3],
  int cellSize,
  const float* minima,
  const float* maxima)
{
  this->CellSize = std::max(cellSize, 1);
  for (int a = 0; a < 3; ++a)
    this->CellDims[a] = std::max(cellDims[a], 1);
  const size_t n = size_t(this->CellDims[0]) * this->CellDims[1] * this->CellDims[2];
  this->Min.assign(minima, minima + n);
  this->Max.assign(maxima, maxima + n);
  this->Distance.assign(n, 255);
}

long long VolumeSkipGrid::Classify(const OpacityRange& opacity)
{
  const int cx = this->CellDims[0], cy = this->CellDims[1], cz = this->CellDims[2];
  std::vector<int> dist(this->Min.size());
  long long visible = 0;
  for (size_t i = 0; i < dist.size(); ++i)
  {
    const bool seen = this->Min[i] <= this->Max[i] && opacity(this->Min[i], this->Max[i]) > 0.0;
    dist[i] = seen ? 0 : 255;
    visible += seen ? 1 : 0;
  }
  // Chessboard distance transform: two raster passes with the 26-neighbourhood, unit weights
  // (exact for this metric). The forward pass looks at the 13 neighbours already visited.
  auto pass = [&](int sign)
  {
    const int z0 = sign > 0 ? 0 : cz - 1, y0 = sign > 0 ? 0 : cy - 1, x0 = sign > 0 ? 0 : cx - 1;
    for (int z = z0; z >= 0 && z < cz; z += sign)
      for (int y = y0; y >= 0 && y < cy; y += sign)
        for (int x = x0; x >= 0 && x < cx; x += sign)
        {
          int& here = dist[x + cx * (y + cy * z)];
          for (int dz = -1; dz <= 0; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx)
              {
                // Only neighbours earlier in this pass's order.
                const bool earlier = dz < 0 || dy < 0 || (dy == 0 && dx < 0);
                if (!earlier)
                  continue;
                const int nx = x + sign * dx, ny = y + sign * dy, nz = z + sign * dz;
                if (nx < 0 || ny < 0 || nz < 0 || nx >= cx || ny >= cy || nz >= cz)
                  continue;
                here = std::min(here, dist[nx + cx * (ny + cy * nz)] + 1);
              }
        }
  };
  pass(+1);
  pass(-1);
  for (size_t i = 0; i < dist.size(); ++i)
    this->Distance[i] = static_cast<uint8_t>(std::min(dist[i], 255));
  return visible;
}
}
