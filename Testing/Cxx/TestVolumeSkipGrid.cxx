// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The skip grid against brute force: every cell's range over voxels c C .. (c + 1) C, the
// visible-cell count for an opacity function, and every cell's chessboard distance to the
// nearest visible cell; also a NaN cell, a one-point-thick axis and a grid with nothing visible.
#include "StrataVolumeSkipGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "  ok   " : "  FAIL ") << what << "\n";
  failures += ok ? 0 : 1;
}

// Visible where the range reaches above `level` (opacity 0 below it, 1 above).
double Step(double level, double, double hi)
{
  return hi > level ? 1.0 : 0.0;
}

void CheckGrid(const std::vector<float>& v,
  const int dims[3],
  int C,
  double level,
  const std::string& name)
{
  strata::VolumeSkipGrid grid;
  grid.Build(v.data(), dims, C);
  const long long visible =
    grid.Classify([level](double lo, double hi) { return Step(level, lo, hi); });
  const int* cd = grid.GetCellDimensions();
  int expected[3];
  for (int a = 0; a < 3; ++a)
    expected[a] = std::max(1, (dims[a] - 1 + C - 1) / C);
  Check(cd[0] == expected[0] && cd[1] == expected[1] && cd[2] == expected[2],
    name + ": cells " + std::to_string(cd[0]) + "x" + std::to_string(cd[1]) + "x" +
      std::to_string(cd[2]));
  // Brute-force ranges and visibility.
  std::vector<char> seen(size_t(cd[0]) * cd[1] * cd[2]);
  long long rangeErrors = 0, bruteVisible = 0;
  for (int k = 0; k < cd[2]; ++k)
    for (int j = 0; j < cd[1]; ++j)
      for (int i = 0; i < cd[0]; ++i)
      {
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        for (int z = k * C; z <= std::min((k + 1) * C, dims[2] - 1); ++z)
          for (int y = j * C; y <= std::min((j + 1) * C, dims[1] - 1); ++y)
            for (int x = i * C; x <= std::min((i + 1) * C, dims[0] - 1); ++x)
            {
              const float s = v[x + size_t(dims[0]) * (y + size_t(dims[1]) * z)];
              if (!std::isnan(s))
              {
                lo = std::min(lo, s);
                hi = std::max(hi, s);
              }
            }
        const size_t c = i + size_t(cd[0]) * (j + size_t(cd[1]) * k);
        rangeErrors += (grid.GetMinima()[c] != lo || grid.GetMaxima()[c] != hi) ? 1 : 0;
        seen[c] = lo <= hi && hi > level;
        bruteVisible += seen[c];
      }
  Check(rangeErrors == 0,
    name + ": cell ranges equal brute force (" + std::to_string(rangeErrors) + " differ)");
  Check(visible == bruteVisible,
    name + ": visible cells " + std::to_string(visible) + " (brute force " +
      std::to_string(bruteVisible) + ")");
  long long distErrors = 0;
  int maxDist = 0;
  for (int k = 0; k < cd[2]; ++k)
    for (int j = 0; j < cd[1]; ++j)
      for (int i = 0; i < cd[0]; ++i)
      {
        int best = 255;
        for (int z = 0; z < cd[2]; ++z)
          for (int y = 0; y < cd[1]; ++y)
            for (int x = 0; x < cd[0]; ++x)
              if (seen[x + size_t(cd[0]) * (y + size_t(cd[1]) * z)])
                best =
                  std::min(best, std::max({ std::abs(x - i), std::abs(y - j), std::abs(z - k) }));
        const int got = grid.GetDistances()[i + size_t(cd[0]) * (j + size_t(cd[1]) * k)];
        distErrors += got != best ? 1 : 0;
        maxDist = std::max(maxDist, got);
      }
  Check(distErrors == 0,
    name + ": chessboard distances equal brute force (" + std::to_string(distErrors) +
      " differ, largest " + std::to_string(maxDist) + ")");
}
}

int TestVolumeSkipGrid(int, char*[])
{
  // A sparse field: two small blobs in noise-free air, dims not multiples of the cell size.
  const int dims[3] = { 45, 38, 29 };
  std::vector<float> v(size_t(dims[0]) * dims[1] * dims[2]);
  unsigned state = 12345u;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
      {
        state = state * 1664525u + 1013904223u;
        const double r1 = std::hypot(std::hypot(x - 8.0, y - 30.0), z - 5.0);
        const double r2 = std::hypot(std::hypot(x - 40.0, y - 4.0), z - 25.0);
        v[x + size_t(dims[0]) * (y + size_t(dims[1]) * z)] =
          float(std::max(0.0, 3.0 - std::min(r1, r2)) + 0.1 * (state >> 8) / 16777216.0);
      }
  CheckGrid(v, dims, 8, 0.5, "two blobs, C=8");
  CheckGrid(v, dims, 4, 0.5, "two blobs, C=4");
  CheckGrid(v, dims, 1, 0.5, "two blobs, C=1");
  // A NaN voxel does not make its cell's range NaN; a cell of NaN only is invisible.
  std::vector<float> n = v;
  n[3 + size_t(dims[0]) * (3 + size_t(dims[1]) * 3)] = std::numeric_limits<float>::quiet_NaN();
  CheckGrid(n, dims, 8, 0.5, "one NaN voxel");
  const int thin[3] = { 20, 1, 9 };
  std::vector<float> t(size_t(thin[0]) * thin[2], std::numeric_limits<float>::quiet_NaN());
  t[17 + size_t(thin[0]) * 8] = 1.0f;
  CheckGrid(t, thin, 4, 0.5, "one point thick, NaN elsewhere");
  CheckGrid(v, dims, 8, 100.0, "nothing visible");
  std::cout << (failures ? "FAILED" : "passed") << "\n";
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
