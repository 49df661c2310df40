// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Exact structure of the min-max quadtree and its interval lists on hand-made stacks.
#include "StrataHeightFieldStack.h"
#include "StrataMinMaxQuadtree.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const char* what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}
}

int TestMinMaxQuadtree(int, char*[])
{
  // 9 x 5 points = 8 x 4 cells; tiles of 2 cells -> 4 x 2 leaves, then 2 x 1, then 1 x 1.
  const int nx = 9, ny = 5;
  std::vector<float> a(nx * ny), b(nx * ny), c(nx * ny);
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      a[j * nx + i] = float(i);                                                       // ramp 0..8
      b[j * nx + i] = 10.0f;                                                          // flat
      c[j * nx + i] = i < 4 ? std::numeric_limits<float>::quiet_NaN() : float(3 + j); // holes left
    }
  }
  strata::HeightFieldStack stack;
  Check(stack.Initialize(nx, ny), "initialize");
  stack.AddLayer(a.data());
  stack.AddLayer(b.data());
  stack.AddLayer(c.data());
  Check(stack.HasHoles(), "stack has holes");
  Check(stack.GetNumberOfHoles(2) == 4u * ny, "hole count of layer 2");

  strata::MinMaxQuadtree tree;
  tree.Build(stack, 2);
  Check(tree.GetNumberOfLevels() == 3, "three levels");
  Check(tree.GetLevelNX(0) == 4 && tree.GetLevelNY(0) == 2, "4 x 2 leaves");
  Check(tree.GetLevelNX(1) == 2 && tree.GetLevelNY(1) == 1, "2 x 1 level 1");
  Check(tree.GetNodes().size() == 8u + 2u + 1u, "11 nodes");

  // Leaf (0,0): x in [0,2] -> a in [0,2], b = 10, c all holes (x < 4).
  const auto& n00 = tree.GetNode(0, 0, 0);
  Check(n00.Min == 0.0f && n00.Max == 10.0f, "leaf (0,0) range");
  Check(n00.IntervalCount == 2, "leaf (0,0) has two intervals");
  const auto& i0 = tree.GetIntervals()[n00.IntervalOffset];
  const auto& i1 = tree.GetIntervals()[n00.IntervalOffset + 1];
  Check(i0.ZMin == 0.0f && i0.ZMax == 2.0f && i0.LayerCount == 1 &&
          tree.GetLayerLists()[i0.LayerOffset] == 0,
    "leaf (0,0) interval [0,2] = {a}");
  Check(i1.ZMin == 10.0f && i1.ZMax == 10.0f && i1.LayerCount == 1 &&
          tree.GetLayerLists()[i1.LayerOffset] == 1,
    "leaf (0,0) interval [10,10] = {b}");

  // Leaf (2,0): x in [4,6], y in [0,2] -> a [4,6], b 10, c [3,5]. End points 3,4,5,6,10:
  // [3,4]{c} [4,5]{a,c} [5,6]{a} [6,10]{} [10,10]{b} -> 4 intervals.
  const auto& n20 = tree.GetNode(0, 2, 0);
  Check(n20.Min == 3.0f && n20.Max == 10.0f, "leaf (2,0) range");
  Check(n20.IntervalCount == 4, "leaf (2,0) has four intervals");
  const auto* iv = &tree.GetIntervals()[n20.IntervalOffset];
  Check(iv[0].ZMin == 3.0f && iv[0].ZMax == 4.0f && iv[0].LayerCount == 1, "[3,4] {c}");
  Check(iv[1].ZMin == 4.0f && iv[1].ZMax == 5.0f && iv[1].LayerCount == 2, "[4,5] {a,c}");
  Check(iv[2].ZMin == 5.0f && iv[2].ZMax == 6.0f && iv[2].LayerCount == 1 &&
          tree.GetLayerLists()[iv[2].LayerOffset] == 0,
    "[5,6] {a}");
  Check(iv[3].ZMin == 10.0f && iv[3].LayerCount == 1, "[10,10] {b}");
  for (int k = 0; k + 1 < n20.IntervalCount; ++k)
  {
    Check(iv[k].ZMax <= iv[k + 1].ZMin, "intervals sorted and disjoint");
  }

  // Root: union of everything: [0, 10].
  const auto& root = tree.GetNode(2, 0, 0);
  Check(root.Min == 0.0f && root.Max == 10.0f, "root range");

  // Every point of every layer lies in an interval of its leaf that lists its layer.
  for (int k = 0; k < 3; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        const float h = stack.GetHeight(k, i, j);
        if (std::isnan(h))
          continue;
        const int la = std::min(i / 2, 3), lb = std::min(j / 2, 1);
        const auto& n = tree.GetNode(0, la, lb);
        bool found = false;
        for (int q = 0; q < n.IntervalCount && !found; ++q)
        {
          const auto& in = tree.GetIntervals()[n.IntervalOffset + q];
          for (int r = 0; r < in.LayerCount; ++r)
          {
            found = found ||
                    (tree.GetLayerLists()[in.LayerOffset + r] == k && h >= in.ZMin && h <= in.ZMax);
          }
        }
        Check(found, "point covered by an interval of its layer");
      }
    }
  }

  // A 1 x N grid becomes a ribbon two points wide, offset by half a spacing.
  strata::HeightFieldStack ribbon;
  std::vector<float> line = { 1, 2, 3, 4 };
  ribbon.Initialize(1, 4);
  ribbon.AddLayer(line.data());
  Check(ribbon.GetNX() == 2 && ribbon.GetNY() == 4 && ribbon.GetIndexOffset(0) == -0.5 &&
          ribbon.GetHeight(0, 1, 3) == 4.0f,
    "1 x N ribbon expansion");
  // Null values become holes; absurd sizes are refused.
  strata::HeightFieldStack nulls;
  std::vector<double> withNull = { 1.0, -999.25, 3.0, 1e30 };
  nulls.Initialize(2, 2);
  nulls.AddLayer(withNull.data(), true, -999.25);
  Check(nulls.GetNumberOfHoles(0) == 2 && std::isnan(nulls.GetHeight(0, 1, 0)), "null values");
  strata::HeightFieldStack absurd;
  Check(
    !absurd.Initialize(100000, 100000) && !absurd.GetErrorMessage().empty(), "absurd size refused");
  Check(!absurd.Initialize(0, 5), "empty grid refused");

  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
