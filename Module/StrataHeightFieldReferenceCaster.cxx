// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataHeightFieldReferenceCaster.h"

#include "StrataHeightFieldStack.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace strata
{

HeightFieldReferenceCaster::HeightFieldReferenceCaster(const strata::HeightFieldStack& stack)
  : Stack(stack)
{
}

namespace
{
// The roots of a s^2 + b s + c in [lo, hi) (the stable quadratic formula; nearly linear when
// the quadratic term is 1e-14 of the others over [0, len]); none when all three vanish (the
// ray lies in the surface).
int Roots(double a, double b, double c, double len, double lo, double hi, double roots[2])
{
  const double scale = std::max({ std::abs(a) * len * len, std::abs(b) * len, std::abs(c) });
  if (scale == 0.0)
    return 0;
  double r[2];
  int n = 0;
  if (std::abs(a) * len * len <= 1e-14 * scale)
  {
    if (b != 0.0)
      r[n++] = -c / b;
  }
  else
  {
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0)
      return 0;
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    r[n++] = q / a;
    if (q != 0.0)
      r[n++] = c / q;
  }
  int kept = 0;
  for (int k = 0; k < n; ++k)
    if (r[k] >= lo && r[k] < hi && (kept == 0 || r[k] != roots[0]))
      roots[kept++] = r[k];
  return kept;
}

// Smallest root in [0, len], or -1; 0 when the ray lies in the surface. Tolerance 1e-12 of the
// segment so that a root exactly on a cell boundary is not lost.
double SmallestRoot(double a, double b, double c, double len)
{
  if (std::max({ std::abs(a) * len * len, std::abs(b) * len, std::abs(c) }) == 0.0)
    return 0.0;
  const double tol = 1e-12 * std::max(len, 1e-300);
  double roots[2];
  const int n = Roots(a, b, c, len, -tol, std::nextafter(len + tol, HUGE_VAL), roots);
  if (n == 0)
    return -1.0;
  const double best = n == 2 ? std::min(roots[0], roots[1]) : roots[0];
  return std::min(std::max(best, 0.0), len);
}

/**
 * The cells of the stack's lateral grid that origin + t d crosses for t in [tMin, tMax],
 * clipped to the stack's box, in ray order (a 2-D DDA): visit(i, j, t, tEnd, last) for the
 * cell (i, j) and its piece [t, tEnd] of the ray; a visit returning true stops the walk.
 */
template<typename Visit>
void WalkCells(const strata::HeightFieldStack& s,
  const double o[3],
  const double d[3],
  double tMin,
  double tMax,
  Visit&& visit)
{
  const int nx = s.GetNX(), ny = s.GetNY();
  double zr[2];
  s.GetZRange(zr);
  if (s.GetNumberOfLayers() == 0 || zr[0] > zr[1] || nx < 2 || ny < 2)
    return;
  const double lo[3] = { 0.0, 0.0, zr[0] };
  const double hi[3] = { double(nx - 1), double(ny - 1), zr[1] };
  double t0 = tMin, t1 = tMax;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      if (o[a] < lo[a] || o[a] > hi[a])
        return;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb)
      std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1))
    return;
  const double px = o[0] + t0 * d[0], py = o[1] + t0 * d[1];
  int i = std::min(std::max(static_cast<int>(std::floor(px)), 0), nx - 2);
  int j = std::min(std::max(static_cast<int>(std::floor(py)), 0), ny - 2);
  // On an exact boundary, start in the cell the ray moves into.
  if (d[0] < 0.0 && px == std::floor(px) && i > 0 && px <= i)
    i = std::max(i - 1, 0);
  if (d[1] < 0.0 && py == std::floor(py) && j > 0 && py <= j)
    j = std::max(j - 1, 0);
  const int stepX = d[0] > 0.0 ? 1 : -1, stepY = d[1] > 0.0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  auto nextT = [&](double p0, double dir, int cell) {
    return dir > 0.0 ? (cell + 1 - p0) / dir : dir < 0.0 ? (cell - p0) / dir : inf;
  };
  double tx = nextT(o[0], d[0], i), ty = nextT(o[1], d[1], j);
  double t = t0;
  while (t <= t1)
  {
    const double tEnd = std::min({ tx, ty, t1 });
    const bool last = tEnd >= t1;
    if (visit(i, j, t, tEnd, last) || last)
      return;
    if (tx < ty)
    {
      i += stepX;
      t = tx;
      tx += std::abs(1.0 / d[0]);
    }
    else
    {
      j += stepY;
      t = ty;
      ty += std::abs(1.0 / d[1]);
    }
    if (i < 0 || i > nx - 2 || j < 0 || j > ny - 2)
      return;
  }
}

/// f(s) = z0 + s dz - h(u0 + s du, v0 + s dv) = qa s^2 + qb s + qc on the piece of the ray from
/// t in cell (i, j) of layer k; false when a corner is a hole.
bool CellQuadratic(const strata::HeightFieldStack& s,
  int k,
  int i,
  int j,
  const double o[3],
  const double d[3],
  double t,
  double q[3])
{
  const double h00 = s.GetHeight(k, i, j), h10 = s.GetHeight(k, i + 1, j);
  const double h01 = s.GetHeight(k, i, j + 1), h11 = s.GetHeight(k, i + 1, j + 1);
  if (std::isnan(h00) || std::isnan(h10) || std::isnan(h01) || std::isnan(h11))
    return false;
  const double u0 = o[0] + t * d[0] - i, v0 = o[1] + t * d[1] - j, z0 = o[2] + t * d[2];
  const double ea = h10 - h00, eb = h01 - h00, ec = h00 - h10 - h01 + h11;
  q[0] = -ec * d[0] * d[1];
  q[1] = d[2] - ea * d[0] - eb * d[1] - ec * (u0 * d[1] + v0 * d[0]);
  q[2] = z0 - h00 - ea * u0 - eb * v0 - ec * u0 * v0;
  return true;
}

HeightFieldReferenceCaster::Hit MakeHit(int layer, double t, const double o[3], const double d[3])
{
  HeightFieldReferenceCaster::Hit hit;
  hit.Layer = layer;
  hit.T = t;
  for (int a = 0; a < 3; ++a)
    hit.Point[a] = o[a] + t * d[a];
  return hit;
}
}

HeightFieldReferenceCaster::Hit HeightFieldReferenceCaster::Cast(const double o[3],
  const double d[3],
  double tMin,
  double tMax) const
{
  Hit hit;
  const strata::HeightFieldStack& s = this->Stack;
  WalkCells(s,
    o,
    d,
    tMin,
    tMax,
    [&](int i, int j, double t, double tEnd, bool)
    {
      // The first cell with a root holds the first hit: the smallest root over the layers.
      double bestS = std::numeric_limits<double>::infinity();
      int bestLayer = -1;
      for (int k = 0; k < s.GetNumberOfLayers(); ++k)
      {
        double q[3];
        if (!CellQuadratic(s, k, i, j, o, d, t, q))
          continue;
        const double root = SmallestRoot(q[0], q[1], q[2], tEnd - t);
        if (root >= 0.0 && root < bestS)
        {
          bestS = root;
          bestLayer = k;
        }
      }
      if (bestLayer >= 0)
        hit = MakeHit(bestLayer, t + bestS, o, d);
      return bestLayer >= 0;
    });
  return hit;
}

std::vector<HeightFieldReferenceCaster::Hit> HeightFieldReferenceCaster::CastAll(const double o[3],
  const double d[3],
  double tMin,
  double tMax) const
{
  std::vector<Hit> hits;
  const strata::HeightFieldStack& s = this->Stack;
  bool first = true;
  WalkCells(s,
    o,
    d,
    tMin,
    tMax,
    [&](int i, int j, double t, double tEnd, bool last)
    {
      const double len = tEnd - t;
      const double tol = 1e-12 * std::max(len, 1e-300);
      for (int k = 0; k < s.GetNumberOfLayers(); ++k)
      {
        double q[3], roots[2];
        if (!CellQuadratic(s, k, i, j, o, d, t, q))
          continue;
        // [-tol, len - tol): a root on the boundary with the next cell is that cell's.
        const int n =
          Roots(q[0], q[1], q[2], len, first ? 0.0 : -tol, last ? len + tol : len - tol, roots);
        for (int r = 0; r < n; ++r)
          hits.push_back(MakeHit(k, t + std::min(std::max(roots[r], 0.0), len), o, d));
      }
      first = false;
      return false;
    });
  std::stable_sort(hits.begin(),
    hits.end(),
    [](const Hit& a, const Hit& b) { return a.T < b.T || (a.T == b.T && a.Layer < b.Layer); });
  return hits;
}

void HeightFieldReferenceCaster::CastImage(const double m[16],
  int width,
  int height,
  std::vector<int>& layers,
  std::vector<double>& points) const
{
  layers.assign(static_cast<size_t>(width) * height, -1);
  points.assign(static_cast<size_t>(width) * height * 3, std::nan(""));
  auto transform = [m](double x, double y, double z, double out[3])
  {
    double w = m[12] * x + m[13] * y + m[14] * z + m[15];
    for (int r = 0; r < 3; ++r)
    {
      out[r] = (m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3]) / w;
    }
  };
  auto work = [&](int rowBegin, int rowStep)
  {
    for (int py = rowBegin; py < height; py += rowStep)
    {
      for (int px = 0; px < width; ++px)
      {
        const double nx = (px + 0.5) / width * 2.0 - 1.0;
        const double ny = (py + 0.5) / height * 2.0 - 1.0;
        double nearP[3], farP[3], dir[3];
        transform(nx, ny, -1.0, nearP);
        transform(nx, ny, 1.0, farP);
        for (int a = 0; a < 3; ++a)
        {
          dir[a] = farP[a] - nearP[a];
        }
        const Hit hit = this->Cast(nearP, dir, 0.0, 1.0);
        const size_t idx = static_cast<size_t>(py) * width + px;
        if (hit.Layer >= 0)
        {
          layers[idx] = hit.Layer;
          std::copy(hit.Point, hit.Point + 3, points.begin() + 3 * idx);
        }
      }
    }
  };
  const int threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k)
  {
    pool.emplace_back(work, k, threads);
  }
  work(0, threads);
  for (auto& th : pool)
  {
    th.join();
  }
}
}
