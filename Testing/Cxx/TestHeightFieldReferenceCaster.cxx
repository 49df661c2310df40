// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The double-precision reference against closed-form hits: a tilted plane (bilinear patches
// of a plane are the plane), a saddle z = xy (exact bilinear), holes, and the nearer of two.
#include "StrataHeightFieldReferenceCaster.h"
#include "StrataHeightFieldStack.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

int TestHeightFieldReferenceCaster(int, char*[])
{
  int failures = 0;
  auto check = [&](bool ok, const char* what)
  {
    if (!ok)
    {
      std::cerr << "FAILED: " << what << "\n";
      ++failures;
    }
  };
  const int n = 33;
  std::vector<float> plane(n * n), saddle(n * n), holed(n * n);
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      plane[j * n + i] = 0.25f * i + 0.5f * j + 1.0f;
      saddle[j * n + i] = float((i - 16) * (j - 16)) / 16.0f + 20.0f;
      holed[j * n + i] = (i >= 10 && i < 20) ? std::numeric_limits<float>::quiet_NaN() : 30.0f;
    }
  }
  strata::HeightFieldStack stack;
  stack.Initialize(n, n);
  stack.AddLayer(plane.data());
  strata::HeightFieldReferenceCaster caster(stack);

  // Ray straight down onto the plane at (7.3, 11.6): z = 0.25*7.3 + 0.5*11.6 + 1.
  {
    const double o[3] = { 7.3, 11.6, 100.0 }, d[3] = { 0.0, 0.0, -1.0 };
    auto hit = caster.Cast(o, d, 0.0, 1000.0);
    const double z = 0.25 * 7.3 + 0.5 * 11.6 + 1.0;
    check(hit.Layer == 0 && std::abs(hit.Point[2] - z) < 1e-12, "vertical ray on plane");
  }
  // Oblique ray: o + t d with o = (0, 0, 30), d = (1, 0.5, -1): 30 - t = 0.25 t + 0.25 t + 1.
  {
    const double o[3] = { 0.0, 0.0, 30.0 }, d[3] = { 1.0, 0.5, -1.0 };
    auto hit = caster.Cast(o, d, 0.0, 1000.0);
    check(hit.Layer == 0 && std::abs(hit.T - 29.0 / 1.5) < 1e-12, "oblique ray on plane");
  }
  // Ray along a grid line (x = 5 exactly, parallel to y), descending slowly.
  {
    const double o[3] = { 5.0, 0.0, 20.0 }, d[3] = { 0.0, 1.0, -0.1 };
    auto hit = caster.Cast(o, d, 0.0, 1000.0);
    // 20 - 0.1 t = 1.25 + 1 + 0.5 t  ->  t = 17.75 / 0.6
    check(hit.Layer == 0 && std::abs(hit.T - 17.75 / 0.6) < 1e-11, "ray on a grid line");
  }

  // Saddle: z = (x-16)(y-16)/16 + 20 is exactly bilinear in every cell.
  strata::HeightFieldStack s2;
  s2.Initialize(n, n);
  s2.AddLayer(saddle.data());
  strata::HeightFieldReferenceCaster c2(s2);
  {
    // Ray o = (2, 3, 40), d = (1, 1, -1): 40 - t = (t-14)(t-13)/16 + 20 -> t^2 - 11 t - 138 = 0
    const double o[3] = { 2.0, 3.0, 40.0 }, d[3] = { 1.0, 1.0, -1.0 };
    auto hit = c2.Cast(o, d, 0.0, 1000.0);
    const double t = (11.0 + std::sqrt(121.0 + 4.0 * 138.0)) / 2.0;
    check(hit.Layer == 0 && std::abs(hit.T - t) < 1e-10, "saddle quadratic root");
  }

  // Holes and ordering: a holed layer above the plane; a ray through the hole hits the plane.
  strata::HeightFieldStack s3;
  s3.Initialize(n, n);
  s3.AddLayer(plane.data());
  s3.AddLayer(holed.data());
  strata::HeightFieldReferenceCaster c3(s3);
  {
    const double o[3] = { 15.0, 5.0, 100.0 }, d[3] = { 0.0, 0.0, -1.0 };
    auto hit = c3.Cast(o, d, 0.0, 1000.0);
    check(hit.Layer == 0, "through the hole to the plane");
    const double o2[3] = { 5.0, 5.0, 100.0 };
    hit = c3.Cast(o2, d, 0.0, 1000.0);
    check(hit.Layer == 1 && std::abs(hit.Point[2] - 30.0) < 1e-12, "upper layer outside the hole");
    const double o3[3] = { 5.0, 5.0, 10.0 }, up[3] = { 0.0, 0.0, 1.0 };
    hit = c3.Cast(o3, up, 0.0, 1000.0);
    check(hit.Layer == 1 && std::abs(hit.T - 20.0) < 1e-12, "camera between layers, looking up");
  }
  // Rays missing the grid or shorter than the first hit find nothing.
  {
    const double o[3] = { -5.0, -5.0, 100.0 }, d[3] = { 0.0, 0.0, -1.0 };
    check(c3.Cast(o, d, 0.0, 1000.0).Layer == -1, "miss outside the grid");
    const double o2[3] = { 5.0, 5.0, 100.0 };
    check(c3.Cast(o2, d, 0.0, 10.0).Layer == -1, "segment ends before the surface");
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
