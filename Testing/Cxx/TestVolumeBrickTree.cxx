// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Exact structure of the brick octree: brick counts per level, the shared voxel layer, brick
// ranges against brute force, the [1 2 1]/4 down-sampling on known fields, and parent/child
// relations that tile every level exactly once.
#include "StrataSubTests.h"

#include "StrataVolumeBrickTree.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
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

// In unsigned arithmetic: the products wrap (in int they overflow, which is undefined).
uint16_t Hash(int x, int y, int z)
{
  const uint32_t h =
    (uint32_t(x) * 73856093u) ^ (uint32_t(y) * 19349663u) ^ (uint32_t(z) * 83492791u);
  return static_cast<uint16_t>(h & 0xFFFF);
}

std::string Dims(const int* d)
{
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
}

// Brick counts of every level, coarsest last, as "4x2x1 2x1x1 1x1x1".
std::string BrickCounts(const strata::VolumeBrickTree& tree)
{
  std::string s;
  for (int l = 0; l < tree.GetNumberOfLevels(); ++l)
  {
    s += (l ? " " : "") + Dims(tree.GetLevelBricks(l));
  }
  return s;
}

void CheckCounts(int nx, int ny, int nz, int B, const std::string& expected)
{
  std::vector<uint8_t> v(static_cast<size_t>(nx) * ny * nz, 1);
  const int dims[3] = { nx, ny, nz };
  strata::VolumeBrickTree tree;
  const bool built = tree.Build(v.data(), dims, B);
  const std::string got = built ? BrickCounts(tree) : "(build failed)";
  // Coarser levels have ceil(half) the bricks of the finer one: the octree is exact.
  bool halves = built;
  for (int l = 1; built && l < tree.GetNumberOfLevels(); ++l)
  {
    for (int a = 0; a < 3; ++a)
    {
      halves = halves && tree.GetLevelBricks(l)[a] == (tree.GetLevelBricks(l - 1)[a] + 1) / 2;
    }
  }
  Check(got == expected && halves,
    "bricks per level of " + Dims(dims) + ", B=" + std::to_string(B) + ": " + got);
}
}

namespace
{
/// The brick size of the hashed tree and its stride.
constexpr int B = 16;
constexpr int S = B - 1;

/// The tree over a hashed field on odd-sized axes (padding, the shared layer, the ranges), and
/// every node's brick extracted.
struct HashedTree
{
  int Dims[3] = { 70, 50, 41 };
  std::vector<uint16_t> Field;
  strata::VolumeBrickTree Tree;
  std::vector<std::vector<float>> Bricks;
};

void CountsPerLevel()
{
  std::cout << "Brick counts (stride B-1; level n -> n/2+1 points until one brick holds it)\n";
  // 64 points, stride 31: bricks start at 0, 31, 62 -> 3; level 1 has 33 points -> 2.
  CheckCounts(64, 64, 64, 32, "3x3x3 2x2x2 1x1x1");
  CheckCounts(64, 64, 64, 64, "1x1x1");
  // 100 -> 51 -> 26 points; 60 -> 31 -> 16; 1 stays 1.
  CheckCounts(100, 60, 1, 32, "4x2x1 2x1x1 1x1x1");
  // 65 points, stride 32: exactly two bricks, the last ending on the last point.
  CheckCounts(65, 65, 65, 33, "2x2x2 1x1x1");
  CheckCounts(1, 1, 1, 4, "1x1x1");
  // 200 -> 101 -> 51 -> 26 -> 14 points, stride 15.
  CheckCounts(200, 1, 1, 16, "14x1x1 7x1x1 4x1x1 2x1x1 1x1x1");
}

void BuildHashedTree(HashedTree& h)
{
  const int* dims = h.Dims;
  std::vector<uint16_t>& field = h.Field;
  strata::VolumeBrickTree& tree = h.Tree;
  field.assign(static_cast<size_t>(dims[0]) * dims[1] * dims[2], 0);
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
        field[(static_cast<size_t>(z) * dims[1] + y) * dims[0] + x] = Hash(x, y, z);
  Check(tree.Build(field.data(), dims, B), "build 70x50x41 uint16, B=16");
  std::cout << "Tree over 70x50x41, B=16: " << BrickCounts(tree) << ", " << tree.GetNumberOfNodes()
            << " nodes\n";

  h.Bricks.assign(tree.GetNumberOfNodes(), std::vector<float>(static_cast<size_t>(B) * B * B));
  for (int id = 0; id < tree.GetNumberOfNodes(); ++id)
  {
    tree.ExtractBrick(id, h.Bricks[id].data());
  }
}

void Extraction(const HashedTree& h)
{
  const strata::VolumeBrickTree& tree = h.Tree;
  const std::vector<std::vector<float>>& bricks = h.Bricks;
  const size_t B3 = static_cast<size_t>(B) * B * B;
  auto at = [&](int id, int a, int b, int c) { return bricks[id][(c * B + b) * B + a]; };
  // Extraction: voxel (a, b, c) of brick I is voxel I S + (a, b, c) of its level, clamped.
  bool extracted = true;
  bool native = true;
  std::vector<uint16_t> raw(B3);
  for (int id = 0; id < tree.GetNumberOfNodes(); ++id)
  {
    const auto& n = tree.GetNode(id);
    tree.ExtractBrickNative(id, raw.data());
    for (int c = 0; c < B; ++c)
      for (int b = 0; b < B; ++b)
        for (int a = 0; a < B; ++a)
        {
          const float v = at(id, a, b, c);
          extracted = extracted &&
                      v == static_cast<float>(tree.GetVoxel(
                             n.Level, n.Index[0] * S + a, n.Index[1] * S + b, n.Index[2] * S + c));
          native = native && raw[(c * B + b) * B + a] == v;
        }
  }
  Check(extracted, "every brick voxel is its level's voxel at I*S + local (clamped padding)");
  Check(native, "native (uint16) extraction equals the float extraction");
  Check(tree.GetVoxel(0, 69, 49, 40) == Hash(69, 49, 40) &&
          tree.GetVoxel(0, 80, -3, 40) == Hash(69, 0, 40),
    "level 0 is the input; indices clamp");
}

void SharedLayer(const HashedTree& h)
{
  const strata::VolumeBrickTree& tree = h.Tree;
  const std::vector<std::vector<float>>& bricks = h.Bricks;
  auto at = [&](int id, int a, int b, int c) { return bricks[id][(c * B + b) * B + a]; };
  // Shared layer: the last layer of a brick is the first of its neighbour, on every level.
  bool shared = true;
  int sharedPairs = 0;
  for (int id = 0; id < tree.GetNumberOfNodes(); ++id)
  {
    const auto& n = tree.GetNode(id);
    for (int axis = 0; axis < 3; ++axis)
    {
      int next[3] = { n.Index[0], n.Index[1], n.Index[2] };
      if (++next[axis] >= tree.GetLevelBricks(n.Level)[axis])
        continue;
      const int nb = tree.GetNodeId(n.Level, next[0], next[1], next[2]);
      ++sharedPairs;
      for (int u = 0; u < B; ++u)
        for (int w = 0; w < B; ++w)
        {
          int p[3], q[3];
          p[axis] = B - 1;
          q[axis] = 0;
          p[(axis + 1) % 3] = q[(axis + 1) % 3] = u;
          p[(axis + 2) % 3] = q[(axis + 2) % 3] = w;
          shared = shared && at(id, p[0], p[1], p[2]) == at(nb, q[0], q[1], q[2]);
        }
    }
  }
  Check(shared && sharedPairs > 0,
    "last voxel layer of a brick == first layer of its neighbour (" + std::to_string(sharedPairs) +
      " neighbour pairs, all levels)");
}

void Ranges(const HashedTree& h)
{
  const strata::VolumeBrickTree& tree = h.Tree;
  const std::vector<std::vector<float>>& bricks = h.Bricks;
  // Ranges against brute force over the extracted B^3 voxels; subtree ranges by recursion.
  bool ranges = true;
  for (int id = 0; id < tree.GetNumberOfNodes(); ++id)
  {
    const auto mm = std::minmax_element(bricks[id].begin(), bricks[id].end());
    ranges = ranges && tree.GetNode(id).Min == *mm.first && tree.GetNode(id).Max == *mm.second;
  }
  Check(ranges, "brick min/max == brute force over its B^3 voxels, every node");
  bool subtree = true;
  for (int id = 0; id < tree.GetNumberOfNodes(); ++id)
  {
    float mn = tree.GetNode(id).Min, mx = tree.GetNode(id).Max;
    std::vector<int> stack = { id };
    while (!stack.empty())
    {
      const int n = stack.back();
      stack.pop_back();
      mn = std::min(mn, tree.GetNode(n).Min);
      mx = std::max(mx, tree.GetNode(n).Max);
      int children[8];
      const int count = tree.GetChildren(n, children);
      stack.insert(stack.end(), children, children + count);
    }
    subtree = subtree && tree.GetNode(id).SubtreeMin == mn && tree.GetNode(id).SubtreeMax == mx;
  }
  Check(subtree, "subtree min/max == union over the node and all its descendants");
}

void ParentsAndChildren(const HashedTree& h)
{
  const int* dims = h.Dims;
  const strata::VolumeBrickTree& tree = h.Tree;
  const std::vector<std::vector<float>>& bricks = h.Bricks;
  // Parent/child: every brick of level l-1 is a child of exactly one brick of level l, its
  // parent; each level's bricks own every voxel exactly once ([I S, (I+1) S), the last brick
  // also its end); children's level-0 boxes tile their parent's box exactly.
  bool family = true;
  bool once = true;
  bool nested = true;
  for (int l = 0; l < tree.GetNumberOfLevels(); ++l)
  {
    const int* nb = tree.GetLevelBricks(l);
    const int count = nb[0] * nb[1] * nb[2];
    if (l > 0)
    {
      std::vector<int> seen(tree.GetLevelBricks(l - 1)[0] * tree.GetLevelBricks(l - 1)[1] *
                              tree.GetLevelBricks(l - 1)[2],
        0);
      for (int id = tree.GetLevelOffset(l); id < tree.GetLevelOffset(l) + count; ++id)
      {
        int children[8];
        const int cc = tree.GetChildren(id, children);
        double pb[6], cb[6];
        tree.GetNodeBounds(id, pb);
        double lo[3] = { 1e30, 1e30, 1e30 }, hi[3] = { -1e30, -1e30, -1e30 };
        for (int c = 0; c < cc; ++c)
        {
          family =
            family && tree.GetParent(children[c]) == id && tree.GetNode(children[c]).Level == l - 1;
          ++seen[children[c] - tree.GetLevelOffset(l - 1)];
          tree.GetNodeBounds(children[c], cb);
          for (int a = 0; a < 3; ++a)
          {
            lo[a] = std::min(lo[a], cb[2 * a]);
            hi[a] = std::max(hi[a], cb[2 * a + 1]);
          }
        }
        for (int a = 0; a < 3; ++a)
        {
          nested = nested && lo[a] == pb[2 * a] && hi[a] == pb[2 * a + 1];
        }
      }
      family = family && std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; });
    }
    const int* d = tree.GetLevelDimensions(l);
    std::vector<int> owned(static_cast<size_t>(d[0]) * d[1] * d[2], 0);
    for (int id = tree.GetLevelOffset(l); id < tree.GetLevelOffset(l) + count; ++id)
    {
      const auto& n = tree.GetNode(id);
      int lo[3], hi[3];
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = n.Index[a] * S;
        hi[a] = n.Index[a] + 1 == nb[a] ? d[a] : std::min((n.Index[a] + 1) * S, d[a]);
      }
      for (int z = lo[2]; z < hi[2]; ++z)
        for (int y = lo[1]; y < hi[1]; ++y)
          for (int x = lo[0]; x < hi[0]; ++x)
            ++owned[(static_cast<size_t>(z) * d[1] + y) * d[0] + x];
    }
    once = once && std::all_of(owned.begin(), owned.end(), [](int c) { return c == 1; });
  }
  // The ancestors of the level-0 brick owning a point all contain that point.
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
      {
        const int p[3] = { x, y, z };
        int idx[3];
        for (int a = 0; a < 3; ++a)
          idx[a] = std::min(p[a] / S, tree.GetLevelBricks(0)[a] - 1);
        for (int id = tree.GetNodeId(0, idx[0], idx[1], idx[2]); id >= 0; id = tree.GetParent(id))
        {
          double nb[6];
          tree.GetNodeBounds(id, nb);
          for (int a = 0; a < 3; ++a)
            nested = nested && nb[2 * a] <= p[a] && p[a] <= nb[2 * a + 1];
        }
      }
  Check(family, "each brick is the child of exactly one brick of the next level, its parent");
  Check(once, "the bricks of every level own each of its voxels exactly once");
  Check(nested,
    "children's level-0 boxes span their parent's; every ancestor of a point's brick holds it");
  double rb[6];
  tree.GetNodeBounds(tree.GetRootId(), rb);
  Check(tree.GetParent(tree.GetRootId()) == -1 && rb[0] == 0 && rb[1] == 69 && rb[2] == 0 &&
          rb[3] == 49 && rb[4] == 0 && rb[5] == 40,
    "root has no parent and covers [0,69]x[0,49]x[0,40]");
}

void DownSampling(const HashedTree& h)
{
  const std::vector<uint16_t>& field = h.Field;
  std::cout << "Down-sampling ([1 2 1]/4 per axis around fine point 2v, clamped)\n";
  // A linear field is reproduced exactly wherever no tap is clamped: coarse v == f(2v).
  const int ld[3] = { 33, 17, 9 };
  std::vector<float> lin(static_cast<size_t>(ld[0]) * ld[1] * ld[2]);
  auto f = [](double x, double y, double z) { return 2 * x + 3 * y + 5 * z + 7; };
  for (int z = 0; z < ld[2]; ++z)
    for (int y = 0; y < ld[1]; ++y)
      for (int x = 0; x < ld[0]; ++x)
        lin[(static_cast<size_t>(z) * ld[1] + y) * ld[0] + x] = static_cast<float>(f(x, y, z));
  strata::VolumeBrickTree linear;
  linear.Build(lin.data(), ld, 8);
  const int* cd = linear.GetLevelDimensions(1);
  bool exact = cd[0] == 17 && cd[1] == 9 && cd[2] == 5;
  for (int z = 1; z + 1 < cd[2]; ++z)
    for (int y = 1; y + 1 < cd[1]; ++y)
      for (int x = 1; x + 1 < cd[0]; ++x)
        exact = exact && linear.GetVoxel(1, x, y, z) == f(2 * x, 2 * y, 2 * z);
  Check(exact, "33x17x9 -> 17x9x5; linear field: interior coarse voxel v == f(2v) exactly");
  // Level 2 keeps every fourth level-0 point.
  exact = true;
  const int* c2 = linear.GetLevelDimensions(2);
  for (int z = 1; z + 1 < c2[2]; ++z)
    for (int y = 1; y + 1 < c2[1]; ++y)
      for (int x = 1; x + 1 < c2[0]; ++x)
        exact = exact && linear.GetVoxel(2, x, y, z) == f(4 * x, 4 * y, 4 * z);
  Check(exact, "level 2 interior voxel v == f(4v): level l samples level-0 point 2^l v");

  // Impulses give the filter weights: 64 at an even point lands on one coarse voxel with
  // weight 2*2*2/64; 64 at an odd x is shared by two coarse voxels with 1*2*2/64.
  const int id[3] = { 12, 12, 12 };
  std::vector<uint8_t> imp(static_cast<size_t>(id[0]) * id[1] * id[2], 0);
  imp[(4 * 12 + 4) * 12 + 4] = 64;
  strata::VolumeBrickTree even;
  even.Build(imp.data(), id, 4);
  double sum = 0;
  for (int z = 0; z < 7; ++z)
    for (int y = 0; y < 7; ++y)
      for (int x = 0; x < 7; ++x)
        sum += even.GetVoxel(1, x, y, z);
  Check(even.GetVoxel(1, 2, 2, 2) == 8 && sum == 8, "impulse 64 at (4,4,4) -> 8 at (2,2,2) only");
  imp[(4 * 12 + 4) * 12 + 4] = 0;
  imp[(4 * 12 + 4) * 12 + 5] = 64;
  strata::VolumeBrickTree odd;
  odd.Build(imp.data(), id, 4);
  Check(
    odd.GetVoxel(1, 2, 2, 2) == 4 && odd.GetVoxel(1, 3, 2, 2) == 4 && odd.GetVoxel(1, 1, 2, 2) == 0,
    "impulse 64 at (5,4,4) -> 4 at (2,2,2) and (3,2,2)");
  // Integer types round half up: 8 at an odd point gives 0.5 -> 1; 1 gives 1/16 -> 0.
  imp[(4 * 12 + 4) * 12 + 5] = 8;
  odd.Build(imp.data(), id, 4);
  const bool half = odd.GetVoxel(1, 2, 2, 2) == 1;
  imp[(4 * 12 + 4) * 12 + 5] = 1;
  odd.Build(imp.data(), id, 4);
  Check(
    half && odd.GetVoxel(1, 2, 2, 2) == 0, "uint8 averages round half up (0.5 -> 1, 1/16 -> 0)");

  // A negative int16 constant stays exact; a flat axis stays one point.
  const int fd[3] = { 40, 30, 1 };
  std::vector<int16_t> neg(static_cast<size_t>(fd[0]) * fd[1], -7);
  strata::VolumeBrickTree flat;
  flat.Build(neg.data(), fd, 8);
  bool constant = true;
  for (int l = 0; l < flat.GetNumberOfLevels(); ++l)
  {
    constant = constant && flat.GetLevelDimensions(l)[2] == 1 &&
               flat.GetNode(flat.GetLevelOffset(l)).Min == -7 &&
               flat.GetNode(flat.GetLevelOffset(l)).Max == -7;
  }
  Check(constant && flat.GetNumberOfLevels() == 4 && flat.GetLevelDimensions(3)[0] == 6,
    "int16 constant -7 stays -7 on 40x30x1 -> 21x16x1 -> 11x9x1 -> 6x5x1");
}

void InputChecks(const HashedTree& h)
{
  const int* dims = h.Dims;
  const std::vector<uint16_t>& field = h.Field;
  std::cout << "Input checks\n";
  const int bad[3] = { 4, 0, 4 };
  strata::VolumeBrickTree refused;
  Check(!refused.Build(field.data(), bad, 8) && !refused.GetErrorMessage().empty() &&
          !refused.Build(field.data(), dims, 1) &&
          !refused.Build(static_cast<const float*>(nullptr), dims, 8),
    "empty dims, brick size 1 and null scalars are refused with a message");
}

}

int TestVolumeBrickTree(int, char*[])
{
  HashedTree h;
  strata_test::RunSubTests(
    {
      { "CountsPerLevel", CountsPerLevel },
      { "BuildHashedTree", [&] { BuildHashedTree(h); } },
      { "Extraction", [&] { Extraction(h); } },
      { "SharedLayer", [&] { SharedLayer(h); } },
      { "Ranges", [&] { Ranges(h); } },
      { "ParentsAndChildren", [&] { ParentsAndChildren(h); } },
      { "DownSampling", [&] { DownSampling(h); } },
      { "InputChecks", [&] { InputChecks(h); } },
    },
    [] { return failures; });
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
