// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The shared-budget cut through several brick octrees: exact coverage, the budget, the
// limits (all finest, all roots), the paper's Fig. 2 (the nearer volume takes the atlas),
// empty-space skipping, incremental updates, and the index table checked against the tree
// and end to end through a CPU copy of the atlas.
#include "StrataSubTests.h"

#include "StrataBrickAtlasAllocator.h"
#include "StrataVolumeBrickTree.h"
#include "StrataVolumeCut.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
#include <set>
#include <sstream>
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

std::string Num(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

// 121 points per axis with bricks of 16 (stride 15): 8^3 level-0 bricks, then 4^3, 2^3, 1.
constexpr int N = 121;
constexpr int B = 16;
constexpr int S = B - 1;

void Translation(double x, double y, double z, double m[16])
{
  const double t[16] = { 1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z, 0, 0, 0, 1 };
  std::copy(t, t + 16, m);
}

// Every level-0 brick has exactly one node of the cut on its path to the root.
bool CoversOnce(const strata::VolumeCut& cut, int v)
{
  const strata::VolumeBrickTree* tree = cut.GetTree(v);
  const int* nb = tree->GetLevelBricks(0);
  for (int id = 0; id < nb[0] * nb[1] * nb[2]; ++id)
  {
    int inCut = 0;
    for (int n = id; n >= 0; n = tree->GetParent(n))
      inCut += cut.IsInCut(v, n) ? 1 : 0;
    if (inCut != 1)
      return false;
  }
  return true;
}

bool AllCoverOnce(const strata::VolumeCut& cut)
{
  bool ok = true;
  for (int v = 0; v < cut.GetNumberOfVolumes(); ++v)
    ok = ok && CoversOnce(cut, v);
  return ok;
}

// Mean level of a volume's resident cut nodes.
double MeanLevel(const strata::VolumeCut& cut, int v)
{
  double sum = 0;
  int count = 0;
  for (int n : cut.GetCutNodes(v))
  {
    if (!cut.IsEmpty(v, n))
    {
      sum += cut.GetTree(v)->GetNode(n).Level;
      ++count;
    }
  }
  return count ? sum / count : -1;
}

// Converged greedy: no node left unsplit is worth more than any node that was split.
bool Ordered(const strata::VolumeCut& cut, double& lowestSplit, double& highestLeaf)
{
  lowestSplit = 1e300;
  highestLeaf = 0;
  for (int v = 0; v < cut.GetNumberOfVolumes(); ++v)
  {
    const strata::VolumeBrickTree* tree = cut.GetTree(v);
    for (int n = 0; n < tree->GetNumberOfNodes(); ++n)
    {
      bool onOrBelow = false; // the node or an ancestor is in the cut
      for (int m = n; m >= 0; m = tree->GetParent(m))
        onOrBelow = onOrBelow || cut.IsInCut(v, m);
      if (!onOrBelow)
        lowestSplit = std::min(lowestSplit, cut.GetPriority(v, n));
      else if (cut.IsInCut(v, n) && !cut.IsEmpty(v, n) && tree->GetNode(n).Level > 0)
        highestLeaf = std::max(highestLeaf, cut.GetPriority(v, n));
    }
  }
  return lowestSplit >= highestLeaf;
}

std::set<std::pair<int, int>> CutSet(const strata::VolumeCut& cut)
{
  std::set<std::pair<int, int>> s;
  for (int v = 0; v < cut.GetNumberOfVolumes(); ++v)
    for (int n : cut.GetCutNodes(v))
      s.insert({ v, n });
  return s;
}

// Trilinear sample of a float array of dims d at continuous voxel coordinates u (voxel
// centres at integers), clamped.
double Trilinear(const std::vector<float>& data, const int d[3], const double u[3])
{
  int i0[3];
  double f[3];
  for (int a = 0; a < 3; ++a)
  {
    const double x = std::clamp(u[a], 0.0, static_cast<double>(d[a] - 1));
    i0[a] = std::min(static_cast<int>(std::floor(x)), std::max(d[a] - 2, 0));
    f[a] = x - i0[a];
  }
  double sum = 0;
  for (int c = 0; c < 8; ++c)
  {
    int p[3];
    double w = 1;
    for (int a = 0; a < 3; ++a)
    {
      const int bit = (c >> a) & 1;
      p[a] = std::min(i0[a] + bit, d[a] - 1);
      w *= bit ? f[a] : 1 - f[a];
    }
    sum += w * data[(static_cast<size_t>(p[2]) * d[1] + p[1]) * d[0] + p[0]];
  }
  return sum;
}

// The same sample read from a tree level through GetVoxel.
double TrilinearLevel(const strata::VolumeBrickTree& tree, int l, const double u[3])
{
  const int* d = tree.GetLevelDimensions(l);
  int i0[3];
  double f[3];
  for (int a = 0; a < 3; ++a)
  {
    const double x = std::clamp(u[a], 0.0, static_cast<double>(d[a] - 1));
    i0[a] = std::min(static_cast<int>(std::floor(x)), std::max(d[a] - 2, 0));
    f[a] = x - i0[a];
  }
  double sum = 0;
  for (int c = 0; c < 8; ++c)
  {
    double w = 1;
    int p[3];
    for (int a = 0; a < 3; ++a)
    {
      const int bit = (c >> a) & 1;
      p[a] = i0[a] + bit;
      w *= bit ? f[a] : 1 - f[a];
    }
    sum += w * tree.GetVoxel(l, p[0], p[1], p[2]);
  }
  return sum;
}
}

namespace
{
void Limits(const strata::VolumeBrickTree& tree,
  int finest,
  const strata::VolumeCut::Camera& camera,
  const double identity[16],
  const double far[16])
{
  std::cout << "Limits\n";
  strata::VolumeCut cut;
  cut.AddVolume(&tree, identity);
  cut.SetBudget(finest);
  cut.Update(camera);
  bool allFinest = cut.GetCost() == finest;
  for (int n : cut.GetCutNodes(0))
    allFinest = allFinest && tree.GetNode(n).Level == 0;
  Check(allFinest && CoversOnce(cut, 0),
    "budget = all " + std::to_string(finest) + " level-0 bricks: the cut is level 0 everywhere");
  cut.SetBudget(1);
  cut.Update(camera);
  Check(cut.GetCutNodes(0) == std::vector<int>{ tree.GetRootId() } && !cut.IsOverBudget(),
    "budget 1: the root alone (over-budget cut collapsed back in one Update)");
  cut.SetBudget(7);
  cut.Update(camera);
  Check(cut.GetCutNodes(0).size() == 1,
    "budget 7: still the root (its split costs 8 - 1 = 7 more bricks)");
  cut.SetBudget(8);
  cut.Update(camera);
  Check(cut.GetCost() == 8 && CoversOnce(cut, 0), "budget 8: the root's eight children");

  strata::VolumeCut two;
  two.AddVolume(&tree, identity);
  two.AddVolume(&tree, far);
  two.SetBudget(2 * finest);
  two.Update(camera);
  Check(two.GetCost() == 2 * finest && MeanLevel(two, 0) == 0 && MeanLevel(two, 1) == 0,
    "two volumes, budget = both finest: both at level 0, near and far alike");
  two.SetBudget(0);
  two.Update(camera);
  Check(two.GetCost() == 2 && two.IsOverBudget() && two.GetCutNodes(1).size() == 1,
    "budget 0: both roots stay (reported over budget)");
}

void SharedBudget(const strata::VolumeBrickTree& tree,
  strata::VolumeCut::Camera& camera,
  const double identity[16])
{
  std::cout << "Shared budget between a near and a far volume (paper Fig. 2)\n";
  // Side by side as in the figure: the eye 150 in front of the first, 250 from the second.
  double side[16];
  Translation(260, 0, 0, side);
  strata::VolumeCut cut;
  cut.AddVolume(&tree, identity);
  cut.AddVolume(&tree, side);
  const int budget = 150;
  cut.SetBudget(budget);
  cut.Update(camera);
  double lowSplit = 0, highLeaf = 0;
  const bool ordered = Ordered(cut, lowSplit, highLeaf);
  Check(cut.GetCost() <= budget && AllCoverOnce(cut),
    "budget " + std::to_string(budget) + ": cost " + std::to_string(cut.GetCost()) +
      ", each volume covered exactly once");
  Check(cut.GetVolumeCost(0) > cut.GetVolumeCost(1) && MeanLevel(cut, 0) < MeanLevel(cut, 1),
    "near volume: " + std::to_string(cut.GetVolumeCost(0)) + " bricks, mean level " +
      Num(MeanLevel(cut, 0)) + "; far: " + std::to_string(cut.GetVolumeCost(1)) +
      " bricks, mean level " + Num(MeanLevel(cut, 1)));
  Check(ordered,
    "one order for both volumes: every split node's error (>= " + Num(lowSplit) +
      " px) >= every unsplit one's (<= " + Num(highLeaf) + " px)");
  Check(cut.Update(camera) == 0 && cut.GetCost() <= budget, "a second Update changes nothing");

  // The eye moves over to the second volume; at most 24 new bricks per Update.
  camera.Position[0] += 260;
  cut.SetMaxNewBricksPerUpdate(24);
  bool bounded = true, within = true, covered = true;
  int updates = 0;
  for (int added = 1; added > 0 && updates < 100; ++updates)
  {
    added = cut.Update(camera);
    bounded = bounded && added <= 24;
    within = within && cut.GetCost() <= budget;
    covered = covered && AllCoverOnce(cut);
  }
  const bool orderedAfter = Ordered(cut, lowSplit, highLeaf);
  Check(bounded && within && covered && updates < 100,
    "eye moved to the other volume: converged in " + std::to_string(updates) +
      " Updates of <= 24 new bricks, within budget and covering after each");
  Check(cut.GetVolumeCost(1) > cut.GetVolumeCost(0) && MeanLevel(cut, 1) < MeanLevel(cut, 0) &&
          orderedAfter,
    "the atlas moved with it: near " + std::to_string(cut.GetVolumeCost(1)) +
      " bricks, mean level " + Num(MeanLevel(cut, 1)) + "; far " +
      std::to_string(cut.GetVolumeCost(0)) + ", mean level " + Num(MeanLevel(cut, 0)));

  // The incremental result is the greedy one: same cut as one unbounded Update from roots.
  const auto incremental = CutSet(cut);
  cut.SetMaxNewBricksPerUpdate(0);
  cut.Reset();
  cut.Update(camera);
  Check(CutSet(cut) == incremental, "bounded incremental Updates reach the unbounded cut");
  camera.Position[0] -= 260;
}

void RandomCamerasAndBudgets(const strata::VolumeBrickTree& tree,
  const strata::VolumeCut::Camera& camera,
  const double identity[16],
  const double far[16])
{
  std::cout << "Random cameras and budgets\n";
  strata::VolumeCut cut;
  cut.AddVolume(&tree, identity);
  cut.AddVolume(&tree, far);
  double scaled[16];
  Translation(300, 200, 0, scaled);
  scaled[0] = scaled[5] = 0.5;
  scaled[10] = 3.0; // anisotropic spacing
  cut.AddVolume(&tree, scaled);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-500, 1500);
  bool within = true, covered = true, orderedAll = true;
  for (int step = 0; step < 60; ++step)
  {
    strata::VolumeCut::Camera c = camera;
    c.Position[0] = pos(rng);
    c.Position[1] = pos(rng) * 0.3;
    c.Position[2] = pos(rng) * 0.3 - 200;
    cut.SetBudget(3 + static_cast<int>(rng() % 1200));
    cut.SetMaxNewBricksPerUpdate(step % 3 == 0 ? 0 : 40);
    cut.Update(c);
    within = within && cut.GetCost() <= cut.GetBudget();
    covered = covered && AllCoverOnce(cut);
    if (cut.GetMaxNewBricksPerUpdate() == 0)
    {
      double lo, hi;
      orderedAll = orderedAll && Ordered(cut, lo, hi);
    }
  }
  Check(within, "60 random cameras and budgets (3 volumes, one anisotropic): never over budget");
  Check(covered, "every volume covered exactly once after every Update");
  Check(orderedAll, "unbounded Updates always end ordered by screen-space error");
}

void EmptySpaceSkipping(const std::vector<uint8_t>& field,
  const int dims[3],
  int finest,
  const strata::VolumeCut::Camera& camera,
  const double identity[16])
{
  std::cout << "Empty-space skipping\n";
  // Zero left of x = 60, 100..199 from there; opacity 0 below 50, 1 from 100.
  std::vector<uint8_t> half(field.size());
  for (int z = 0; z < N; ++z)
    for (int y = 0; y < N; ++y)
      for (int x = 0; x < N; ++x)
        half[(static_cast<size_t>(z) * N + y) * N + x] =
          static_cast<uint8_t>(x < 60 ? 0 : 100 + (x + y + z) % 100);
  strata::VolumeBrickTree halfTree;
  halfTree.Build(half.data(), dims, B);
  const double tf[8] = { 0, 0, 50, 0, 100, 1, 255, 1 };
  auto opacity = [&tf](double lo, double hi)
  { return strata::VolumeCut::MaxOfPiecewiseLinear(tf, 4, lo, hi); };
  Check(opacity(0, 49) == 0 && opacity(0, 50) == 0 && opacity(0, 75) == 0.5 &&
          opacity(60, 80) == 0.6 && opacity(120, 130) == 1 && opacity(-5, 300) == 1,
    "max of the piecewise-linear opacity over value ranges is exact");

  // Brute force: level-0 bricks holding a visible voxel.
  int visibleBricks = 0;
  for (int id = 0; id < finest; ++id)
  {
    double b[6];
    halfTree.GetNodeBounds(id, b);
    visibleBricks += b[1] >= 60 ? 1 : 0;
  }
  strata::VolumeCut cut;
  cut.AddVolume(&halfTree, identity);
  cut.SetVolumeOpacity(0, opacity);
  cut.SetBudget(visibleBricks);
  cut.Update(camera);
  int emptyNodes = 0, coarseEmpty = 0;
  bool transparent = true;
  for (int n : cut.GetCutNodes(0))
  {
    if (!cut.IsEmpty(0, n))
      continue;
    ++emptyNodes;
    coarseEmpty += halfTree.GetNode(n).Level > 0 ? 1 : 0;
    double b[6];
    halfTree.GetNodeBounds(n, b);
    for (int z = static_cast<int>(b[4]); z <= b[5]; ++z)
      for (int y = static_cast<int>(b[2]); y <= b[3]; ++y)
        for (int x = static_cast<int>(b[0]); x <= b[1]; ++x)
          transparent = transparent && opacity(half[(static_cast<size_t>(z) * N + y) * N + x],
                                         half[(static_cast<size_t>(z) * N + y) * N + x]) == 0;
  }
  bool emptyNeverSplit = true;
  for (int n = 0; n < halfTree.GetNumberOfNodes(); ++n)
  {
    int children[8];
    if (halfTree.GetChildren(n, children) > 0 && cut.IsInCut(0, children[0]))
      emptyNeverSplit = emptyNeverSplit && !cut.IsEmpty(0, n);
  }
  bool visibleFinest = true;
  for (int n : cut.GetCutNodes(0))
    visibleFinest = visibleFinest && (cut.IsEmpty(0, n) || halfTree.GetNode(n).Level == 0);
  Check(cut.GetCost() == visibleBricks && visibleFinest && CoversOnce(cut, 0),
    "budget = the " + std::to_string(visibleBricks) +
      " visible level-0 bricks: all at level 0, the empty ones cost nothing");
  Check(emptyNodes > 0 && coarseEmpty > 0 && transparent && emptyNeverSplit,
    std::to_string(emptyNodes) + " empty cut nodes (" + std::to_string(coarseEmpty) +
      " coarser than level 0, never split), every voxel under them transparent");

  strata::BrickAtlasAllocator atlas;
  atlas.Initialize(8, 8, 8, B);
  atlas.BeginFrame();
  std::vector<strata::VolumeCut::Upload> uploads;
  const int failed = cut.AssignSlots(atlas, uploads);
  bool emptyNoSlot = true;
  for (int n : cut.GetCutNodes(0))
    emptyNoSlot = emptyNoSlot && (cut.GetSlot(0, n) < 0) == cut.IsEmpty(0, n);
  std::vector<uint16_t> table;
  cut.BuildIndexTable(0, atlas, table);
  bool emptyCodes = true;
  for (int id = 0; id < finest; ++id)
  {
    double b[6];
    halfTree.GetNodeBounds(id, b);
    emptyCodes = emptyCodes && (table[4 * id + 3] == strata::VolumeCut::EmptyLevel) == (b[1] < 60);
  }
  Check(failed == 0 && static_cast<int>(uploads.size()) == visibleBricks &&
          atlas.GetNumberOfUsedSlots() == visibleBricks && emptyNoSlot && emptyCodes,
    "empty nodes get no slot; their level-0 bricks read EmptyLevel in the index table");

  // A transfer function that hides everything collapses the cut to one empty root.
  cut.SetVolumeOpacity(0, [](double, double) { return 0.0; });
  cut.Update(camera);
  Check(
    cut.GetCost() == 0 && cut.GetCutNodes(0).size() == 1 && cut.IsEmpty(0, halfTree.GetRootId()),
    "all transparent: the cut is the empty root, cost 0");
}

void FrustumAndParallelProjection(const strata::VolumeBrickTree& tree,
  int finest,
  const strata::VolumeCut::Camera& camera,
  const double identity[16],
  const double far[16])
{
  std::cout << "Frustum and parallel projection\n";
  strata::VolumeCut cut;
  cut.AddVolume(&tree, identity);
  cut.SetBudget(finest);
  strata::VolumeCut::Camera c = camera;
  c.UseFrustum = true;
  for (int q = 0; q < 6; ++q) // all planes pass; the first keeps x <= 50 only
  {
    c.FrustumPlanes[4 * q + 3] = 1.0;
  }
  c.FrustumPlanes[0] = -1.0;
  c.FrustumPlanes[3] = 50.0;
  cut.Update(c);
  bool culledKept = true;
  int culled = 0;
  for (int n = 0; n < tree.GetNumberOfNodes(); ++n)
  {
    double b[6];
    tree.GetNodeBounds(n, b);
    if (b[0] > 50)
    {
      ++culled;
      int children[8];
      culledKept = culledKept && cut.GetPriority(0, n) == 0 &&
                   !(tree.GetChildren(n, children) > 0 && cut.IsInCut(0, children[0]));
    }
  }
  Check(culled > 0 && culledKept && cut.GetCost() < finest && CoversOnce(cut, 0),
    "nodes wholly outside the frustum get priority 0 and are never split (cost " +
      std::to_string(cut.GetCost()) + " of " + std::to_string(finest) + ")");

  strata::VolumeCut parallel;
  parallel.AddVolume(&tree, identity);
  parallel.AddVolume(&tree, far);
  strata::VolumeCut::Camera p = camera;
  p.PixelsPerUnit = 2.0;
  parallel.SetBudget(2 + 7 * 18); // both roots and all 16 level-2 nodes split
  parallel.Update(p);
  Check(parallel.GetVolumeCost(0) == 64 && parallel.GetVolumeCost(1) == 64,
    "parallel projection: distance does not matter, 64 bricks each");
}

/// Copies the bricks of `uploads` into `texels`, a CPU copy of the atlas texture (size `tex`).
void Upload(const strata::VolumeCut& cut,
  const strata::BrickAtlasAllocator& atlas,
  const std::vector<strata::VolumeCut::Upload>& uploads,
  const std::array<int, 3>& tex,
  std::vector<float>& texels)
{
  std::vector<float> brick(static_cast<size_t>(B) * B * B);
  for (const auto& u : uploads)
  {
    cut.GetTree(u.Volume)->ExtractBrick(u.Node, brick.data());
    const auto s = atlas.GetSlotPosition(u.Slot);
    for (int z = 0; z < B; ++z)
      for (int y = 0; y < B; ++y)
        std::copy_n(brick.begin() + (z * B + y) * B,
          B,
          texels.begin() +
            ((static_cast<size_t>(s[2] * B + z) * tex[1] + s[1] * B + y) * tex[0] + s[0] * B));
  }
}

/// The index tables of both volumes of `cut` against the tree (every level-0 brick's entry is its
/// cut node's slot and level, no slot shared) and end to end through `texels`; `inside` says
/// whether every lookup stayed within its slot's texel centres.
bool CheckTables(const strata::VolumeCut& cut,
  const strata::BrickAtlasAllocator& atlas,
  const strata::VolumeBrickTree& tree,
  int finest,
  const std::vector<float>& texels,
  const std::array<int, 3>& tex,
  bool& inside,
  int& levelsSeen,
  double& maxError)
{
  bool entries = true, unique = true;
  inside = true;
  std::set<int> slots, levels;
  maxError = 0;
  for (int v = 0; v < 2; ++v)
  {
    std::vector<uint16_t> table;
    entries = entries && cut.BuildIndexTable(v, atlas, table) == 0;
    // Every level-0 brick: walk up to the cut node and compare its entry.
    for (int id = 0; id < finest; ++id)
    {
      int n = id;
      while (!cut.IsInCut(v, n))
        n = tree.GetParent(n);
      const auto s = atlas.GetSlotPosition(cut.GetSlot(v, n));
      const uint16_t* e = &table[4 * id];
      entries = entries && cut.GetSlot(v, n) >= 0 && e[0] == s[0] && e[1] == s[1] && e[2] == s[2] &&
                e[3] == tree.GetNode(n).Level;
      levels.insert(e[3]);
    }
    for (int n : cut.GetCutNodes(v))
      unique = unique && slots.insert(cut.GetSlot(v, n)).second;
    // End to end: a sample through table and atlas equals trilinear on the node's level.
    // Same eight voxels, same weights: only double rounding of the coordinate differs.
    std::mt19937 rng(5 + v);
    std::uniform_real_distribution<double> u(0.0, N - 1.0);
    for (int q = 0; q < 3000; ++q)
    {
      double p[3] = { u(rng), u(rng), u(rng) };
      if (q % 3 == 0) // brick faces and corners of every level
        for (double& x : p)
          x = std::round(x / S) * S;
      double at[3];
      int level = -1;
      const int* nb = tree.GetLevelBricks(0);
      if (!strata::VolumeCut::MapToAtlas(table.data(), nb, B, p, at, level))
      {
        entries = false;
        continue;
      }
      // Inside the slot's texel centres, so linear filtering never reads a neighbour.
      int bi[3];
      for (int a = 0; a < 3; ++a)
        bi[a] = std::min(static_cast<int>(p[a] / S), nb[a] - 1);
      const uint16_t* e = &table[4 * ((bi[2] * nb[1] + bi[1]) * nb[0] + bi[0])];
      for (int a = 0; a < 3; ++a)
        inside = inside && at[a] >= e[a] * B + 0.5 && at[a] <= e[a] * B + B - 0.5;
      const double atlasCoord[3] = { at[0] - 0.5, at[1] - 0.5, at[2] - 0.5 };
      const double levelCoord[3] = {
        p[0] / (1 << level), p[1] / (1 << level), p[2] / (1 << level)
      };
      const double got = Trilinear(texels, tex.data(), atlasCoord);
      const double want = TrilinearLevel(tree, level, levelCoord);
      maxError = std::max(maxError, std::abs(got - want));
    }
    // Positions half a voxel outside the volume still land inside their slot.
    for (int q = 0; q < 200; ++q)
    {
      double p[3] = { u(rng), u(rng), u(rng) };
      p[q % 3] = q % 2 ? -0.5 : N - 0.5;
      double at[3];
      int level = -1;
      strata::VolumeCut::MapToAtlas(table.data(), tree.GetLevelBricks(0), B, p, at, level);
      const double clamped[3] = { std::clamp(p[0], 0.0, N - 1.0),
        std::clamp(p[1], 0.0, N - 1.0),
        std::clamp(p[2], 0.0, N - 1.0) };
      double at2[3];
      strata::VolumeCut::MapToAtlas(table.data(), tree.GetLevelBricks(0), B, clamped, at2, level);
      inside = inside && at[0] == at2[0] && at[1] == at2[1] && at[2] == at2[2];
    }
  }
  levelsSeen = static_cast<int>(levels.size());
  return entries && unique;
}

void IndexTableAndAtlasLookup(const strata::VolumeBrickTree& tree,
  int finest,
  const strata::VolumeCut::Camera& camera,
  const double identity[16],
  const double far[16])
{
  std::cout << "Index table and atlas lookup\n";
  strata::VolumeCut cut;
  cut.AddVolume(&tree, identity);
  cut.AddVolume(&tree, far);
  strata::BrickAtlasAllocator atlas;
  atlas.Initialize(8, 8, 4, B); // 256 slots
  cut.SetBudget(atlas.GetNumberOfSlots());
  strata::VolumeCut::Camera c = camera;
  c.Position[2] = -20.7; // close: several levels in the near volume
  cut.Update(c);
  const auto tex = atlas.GetTextureSize();
  std::vector<float> texels(static_cast<size_t>(tex[0]) * tex[1] * tex[2], -1.0f);
  std::vector<strata::VolumeCut::Upload> uploads;
  atlas.BeginFrame();
  const int failed = cut.AssignSlots(atlas, uploads);
  Upload(cut, atlas, uploads, tex, texels);

  bool inside = true;
  int levelsSeen = 0;
  double maxError = 0;
  const bool tables =
    CheckTables(cut, atlas, tree, finest, texels, tex, inside, levelsSeen, maxError);
  Check(
    failed == 0 && static_cast<int>(uploads.size()) == cut.GetCost() && tables && levelsSeen >= 3,
    "index entries = (slot, level) of the cut node found by walking up from every level-0 "
    "brick; " +
      std::to_string(levelsSeen) + " levels; no slot shared");
  Check(inside, "lookups stay within the texel centres of their slot, also half a voxel outside");
  Check(maxError < 1e-9,
    "6000 samples through index table + atlas == trilinear on the node's level (max error " +
      Num(maxError) + ", bound 1e-9)");

  // Next frame: the camera moves; only bricks new to the atlas are uploaded.
  c.Position[0] += 40;
  cut.Update(c);
  atlas.BeginFrame();
  atlas.ResetStatistics();
  cut.AssignSlots(atlas, uploads);
  Upload(cut, atlas, uploads, tex, texels);
  const auto& st = atlas.GetStatistics();
  const bool tables2 =
    CheckTables(cut, atlas, tree, finest, texels, tex, inside, levelsSeen, maxError);
  Check(st.Misses == static_cast<int64_t>(uploads.size()) && st.Hits + st.Misses == cut.GetCost() &&
          st.Hits > 0 && tables2 && maxError < 1e-9,
    "after a camera move: " + std::to_string(st.Hits) + " hits, " + std::to_string(uploads.size()) +
      " uploads, " + std::to_string(st.Evictions) + " evictions; tables and samples still exact");
}

void PriorityFunction(const strata::VolumeBrickTree& tree,
  const strata::VolumeCut::Camera& camera,
  const double identity[16])
{
  // --- A priority function (what a renderer with level-of-detail feedback gives): rays asked
  // for the level-0 bricks of the slab i == 0 only; a node's priority is the number of asked
  // bricks strictly below it. Exactly the nodes with demand are split, nothing else.
  strata::VolumeCut cut;
  cut.AddVolume(&tree, identity);
  cut.SetBudget(tree.GetNumberOfNodes());
  std::vector<double> demand(tree.GetNumberOfNodes(), 0.0);
  const int* nb = tree.GetLevelBricks(0);
  std::vector<int> asked;
  for (int k = 0; k < nb[2]; ++k)
    for (int j = 0; j < nb[1]; ++j)
    {
      asked.push_back(tree.GetNodeId(0, 0, j, k));
      for (int n = tree.GetParent(asked.back()); n >= 0; n = tree.GetParent(n))
        demand[n] += 1.0;
    }
  cut.SetVolumePriority(0, [&demand](int n, double) { return demand[n]; });
  int updates = 0;
  while (cut.Update(camera) > 0 && updates < 100)
    ++updates;
  bool askedFinest = true;
  for (int id : asked)
    askedFinest = askedFinest && cut.IsInCut(0, id);
  bool exact = true; // a cut node has no demand of its own, and its parent had some
  for (int n : cut.GetCutNodes(0))
  {
    const int parent = tree.GetParent(n);
    exact = exact && demand[n] == 0.0 && (parent < 0 || demand[parent] > 0.0);
  }
  // The slab's 64 bricks and their 64 siblings (i == 1) at level 0, then 16 level-1 and 4
  // level-2 nodes beside them.
  std::cout << "Priority function: " << asked.size() << " bricks asked for, cut of "
            << cut.GetCost() << " bricks after " << updates << " updates\n";
  Check(askedFinest && exact && CoversOnce(cut, 0) && cut.GetCost() == 2 * 64 + 16 + 4,
    "a priority function: only nodes with demand split; the asked bricks finest, the rest "
    "coarse");
  cut.SetVolumePriority(0, nullptr);
  cut.Update(camera);
  Check(
    cut.GetCost() > 2 * 64 + 16 + 4, "without it the screen-space error refines the rest again");
}

}

// The halo of pre-integration: one visible spot inside level-0 brick (3, 3, 3); with the
// halo exactly its 3 x 3 x 3 block of bricks is non-empty, without it the brick alone.
void Halo(const int dims[3], const strata::VolumeCut::Camera& camera, const double identity[16])
{
  std::cout << "Halo\n";
  std::vector<uint8_t> spot(static_cast<size_t>(N) * N * N, 0);
  for (int z = 50; z <= 54; ++z)
    for (int y = 50; y <= 54; ++y)
      for (int x = 50; x <= 54; ++x)
        spot[(static_cast<size_t>(z) * N + y) * N + x] = 200;
  strata::VolumeBrickTree spotTree;
  spotTree.Build(spot.data(), dims, B);
  const double tf[6] = { 0, 0, 100, 0, 200, 1 };
  strata::VolumeCut cut;
  cut.AddVolume(&spotTree, identity);
  cut.SetVolumeOpacity(0,
    [&tf](double lo, double hi) { return strata::VolumeCut::MaxOfPiecewiseLinear(tf, 3, lo, hi); });
  cut.SetBudget(1000);
  const int* bricks = spotTree.GetLevelBricks(0);
  for (bool halo : { false, true })
  {
    cut.SetVolumeHalo(0, halo);
    cut.Update(camera);
    int visible = 0, expected = 0;
    for (int k = 0; k < bricks[2]; ++k)
      for (int j = 0; j < bricks[1]; ++j)
        for (int i = 0; i < bricks[0]; ++i)
        {
          const bool near = std::abs(i - 3) <= 1 && std::abs(j - 3) <= 1 && std::abs(k - 3) <= 1;
          const bool wanted = halo ? near : (i == 3 && j == 3 && k == 3);
          const bool shown = !cut.IsEmpty(0, spotTree.GetNodeId(0, i, j, k));
          visible += shown ? 1 : 0;
          expected += shown == wanted ? 1 : 0;
        }
    std::cout << "  halo " << (halo ? "on" : "off") << ": " << visible
              << " non-empty level-0 bricks; cut of " << cut.GetCost() << " bricks\n";
    Check(expected == bricks[0] * bricks[1] * bricks[2] && visible == (halo ? 27 : 1),
      halo ? "with the halo the spot's brick and its 26 neighbours are kept"
           : "without it the spot's brick alone");
    Check(AllCoverOnce(cut), "the cut covers the volume once");
  }
}

// The page budget bounds the pages a pager holds for the cut (resident cut nodes and their
// ancestors) in the volumes with an availability function only; an in-core volume beside them
// counts against the slots alone.
void PageBudget(const strata::VolumeBrickTree& tree,
  const strata::VolumeCut::Camera& camera,
  const double identity[16],
  const double far[16])
{
  std::cout << "Page budget\n";
  strata::VolumeCut cut;
  cut.AddVolume(&tree, identity);
  cut.AddVolume(&tree, far);
  cut.SetVolumeAvailability(0, [](int, double) { return true; });
  cut.SetBudget(400);
  cut.Update(camera);
  const int unbounded = cut.GetHeldPages();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-500, 1500);
  bool within = true, covered = true, bound = false;
  for (int step = 0; step < 40; ++step)
  {
    strata::VolumeCut::Camera c = camera;
    c.Position[0] = pos(rng);
    c.Position[2] = pos(rng) * 0.3 - 200;
    cut.SetPageBudget(9 + static_cast<int>(rng() % 200));
    cut.SetMaxNewBricksPerUpdate(step % 2 == 0 ? 0 : 40);
    cut.Update(c);
    within = within && cut.GetHeldPages() <= cut.GetPageBudget() && !cut.IsOverBudget();
    covered = covered && AllCoverOnce(cut);
    bound = bound || cut.GetHeldPages() < cut.GetVolumeCost(0) + cut.GetVolumeCost(1);
  }
  std::cout << "  held pages without a page budget: " << unbounded << "\n";
  Check(unbounded > 209, "without a page budget the cut holds more pages than any budget below");
  Check(within, "40 random cameras and page budgets: held pages and cost within their budgets");
  Check(covered, "every volume covered exactly once after every Update");
  Check(bound, "the in-core volume's bricks are not counted as held pages");
  cut.SetPageBudget(0);
  cut.SetMaxNewBricksPerUpdate(0);
  cut.Reset();
  cut.Update(camera);
  Check(cut.GetHeldPages() == unbounded, "page budget 0 bounds nothing");
}

// A renderer drawing one box of the scene (sort-last parallel rendering): nodes the box, grown
// by the margin and one voxel of their level, misses are empty, so the cut holds only the
// box's share. 121^3 voxels in bricks of 16 (stride 15): 8 columns of level-0 bricks along x,
// column i over x in [15 i, 15 i + 15].
void Region(const strata::VolumeBrickTree& tree,
  const strata::VolumeCut::Camera& camera,
  const double identity[16],
  const double far[16])
{
  std::cout << "Region\n";
  auto levelZeroInside = [&](const strata::VolumeCut& cut, int v, double hiX)
  {
    int count = 0;
    bool within = true;
    for (int n : cut.GetCutNodes(v))
    {
      if (cut.IsEmpty(v, n))
        continue; // (outside nodes stay in the cut as empty stand-ins, at any level)
      double b[6];
      tree.GetNodeBounds(n, b);
      within = within && tree.GetNode(n).Level == 0 && b[0] <= hiX;
      ++count;
    }
    return within ? count : -1;
  };
  strata::VolumeCut::Camera boxed = camera;
  const double region[6] = { -1e3, 60.0, -1e3, 1e3, -1e3, 1e3 };
  boxed.Region.Set(region);
  strata::VolumeCut cut;
  cut.AddVolume(&tree, identity);
  cut.SetBudget(512);
  cut.Update(boxed);
  // Columns 0-4 (column 4 starts at 60, within one voxel); 5 of 8 columns of 64 bricks.
  Check(cut.GetCost() == 5 * 64 && levelZeroInside(cut, 0, 61.0) == 5 * 64,
    "region x <= 60: the cut is the 320 level-0 bricks of the 5 columns it touches (cost " +
      std::to_string(cut.GetCost()) + ")");
  boxed.RegionMargin = 20.0;
  cut.Update(boxed);
  Check(cut.GetCost() == 6 * 64, "a margin of 20 adds column 5 (x from 75 <= 81): 384 bricks");
  // The far volume (moved by 1000 along x) from x = 62 on.
  const double farBox[6] = { 1000.0 + 62.0, 1e4, -1e3, 1e3, -1e3, 1e3 };
  boxed.Region.Set(farBox);
  boxed.RegionMargin = 0.0;
  strata::VolumeCut two;
  two.AddVolume(&tree, identity);
  two.AddVolume(&tree, far);
  two.SetBudget(1024);
  two.Update(boxed);
  Check(two.GetVolumeCost(0) == 0 && two.GetVolumeCost(1) == 4 * 64,
    "a region over the far volume's x >= 62 only: nothing of the near one, its columns 4-7 (3 "
    "ends at 60, more than a voxel away; cost " +
      std::to_string(two.GetVolumeCost(0)) + " and " + std::to_string(two.GetVolumeCost(1)) + ")");
  cut.Update(camera);
  Check(cut.GetCost() == 512, "without the region: all 512 level-0 bricks again");
}

int TestVolumeCut(int, char*[])
{
  const int dims[3] = { N, N, N };
  std::vector<uint8_t> field(static_cast<size_t>(N) * N * N);
  for (int z = 0; z < N; ++z)
    for (int y = 0; y < N; ++y)
      for (int x = 0; x < N; ++x)
        field[(static_cast<size_t>(z) * N + y) * N + x] =
          static_cast<uint8_t>((x * 7 + y * 13 + z * 29 + (x * y) % 17) % 256);
  strata::VolumeBrickTree tree;
  tree.Build(field.data(), dims, B);
  const int finest =
    tree.GetLevelBricks(0)[0] * tree.GetLevelBricks(0)[1] * tree.GetLevelBricks(0)[2];
  std::cout << "Volumes of 121^3 voxels, B=16: " << finest << " level-0 bricks, "
            << tree.GetNumberOfNodes() << " nodes, " << tree.GetNumberOfLevels() << " levels\n";

  strata::VolumeCut::Camera camera;
  camera.PixelsPerRadian = strata::VolumeCut::PixelsPerRadian(1000, 30.0);
  // Generic positions: no two nodes at exactly the same distance, so no ties in priority.
  camera.Position[0] = 57.3;
  camera.Position[1] = 61.9;
  camera.Position[2] = -150.7;
  double identity[16], far[16];
  Translation(0, 0, 0, identity);
  Translation(1000, 0, 0, far);
  return strata_test::RunSubTests(
    {
      { "Limits", [&] { Limits(tree, finest, camera, identity, far); } },
      { "SharedBudget", [&] { SharedBudget(tree, camera, identity); } },
      { "RandomCamerasAndBudgets", [&] { RandomCamerasAndBudgets(tree, camera, identity, far); } },
      { "EmptySpaceSkipping", [&] { EmptySpaceSkipping(field, dims, finest, camera, identity); } },
      { "FrustumAndParallelProjection",
        [&] { FrustumAndParallelProjection(tree, finest, camera, identity, far); } },
      { "IndexTableAndAtlasLookup",
        [&] { IndexTableAndAtlasLookup(tree, finest, camera, identity, far); } },
      { "PriorityFunction", [&] { PriorityFunction(tree, camera, identity); } },
      { "Halo", [&] { Halo(dims, camera, identity); } },
      { "PageBudget", [&] { PageBudget(tree, camera, identity, far); } },
      { "Region", [&] { Region(tree, camera, identity, far); } },
    },
    [] { return failures; });
}
