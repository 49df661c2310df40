// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataVolumeCut.h"

#include "StrataBrickAtlasAllocator.h"
#include "StrataVolumeBrickTree.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <set>
#include <tuple>

namespace strata
{

namespace
{
enum : uint8_t
{
  Outside = 0, ///< not in the cut: above it (split) is Inner, below it Outside
  Leaf = 1,
  Inner = 2
};

// (priority, volume, node): ordered sets give the highest split and the lowest collapse, and
// ties fall back to ids, so results do not depend on hash or heap order.
using Entry = std::tuple<double, int, int>;
}

class VolumeCut::vtkInternals
{
public:
  struct Volume
  {
    const strata::VolumeBrickTree* Tree = nullptr;
    double Matrix[16];
    OpacityRangeFunction Opacity;
    AvailabilityFunction Available;
    PriorityFunction Rank;
    bool Halo = false;
    double VoxelSize = 1.0; ///< world length of the longest level-0 voxel edge
    std::vector<uint8_t> State;
    std::vector<uint8_t> Empty;
    std::vector<double> Priority;
    std::vector<int> Slot;
  };
  std::vector<Volume> Volumes;

  // Candidates of the running Update().
  std::set<Entry> Splits;
  std::set<Entry> Collapses;
  double Threshold = 0.0;

  Entry Key(int v, int n) const { return Entry(this->Volumes[v].Priority[n], v, n); }

  // Empty by its own subtree range and, with a halo, by those of its level's 26 neighbours.
  void Classify(int v, const VolumeCut::Camera& camera)
  {
    this->ClassifyOpacity(v);
    if (camera.Region.IsSet())
      this->ClassifyRegion(v, camera);
  }

  // Nodes outside the camera's region are empty for this renderer.
  void ClassifyRegion(int v, const VolumeCut::Camera& camera)
  {
    Volume& vol = this->Volumes[v];
    for (int n = 0; n < vol.Tree->GetNumberOfNodes(); ++n)
    {
      double b[6];
      vol.Tree->GetNodeBounds(n, b);
      const double margin =
        camera.RegionMargin + vol.VoxelSize * static_cast<double>(1 << vol.Tree->GetNode(n).Level);
      double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
      for (int c = 0; c < 8; ++c)
      {
        const double p[3] = { b[c & 1], b[2 + ((c >> 1) & 1)], b[4 + ((c >> 2) & 1)] };
        for (int r = 0; r < 3; ++r)
        {
          const double* m = vol.Matrix + 4 * r;
          const double w = m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3];
          lo[r] = std::min(lo[r], w);
          hi[r] = std::max(hi[r], w);
        }
      }
      for (int r = 0; r < 3; ++r)
      {
        if (hi[r] < camera.Region[2 * r] - margin || lo[r] > camera.Region[2 * r + 1] + margin)
          vol.Empty[n] = 1;
      }
    }
  }

  void ClassifyOpacity(int v)
  {
    Volume& vol = this->Volumes[v];
    const strata::VolumeBrickTree& tree = *vol.Tree;
    std::vector<uint8_t> own(tree.GetNumberOfNodes(), 0);
    for (int n = 0; n < tree.GetNumberOfNodes(); ++n)
    {
      const auto& node = tree.GetNode(n);
      // Min > Max only for all-NaN bricks: nothing to show.
      const double opacity = !vol.Opacity ? 1.0
                             : node.SubtreeMin <= node.SubtreeMax
                               ? vol.Opacity(node.SubtreeMin, node.SubtreeMax)
                               : 0.0;
      own[n] = opacity <= 0.0;
    }
    if (!vol.Halo)
    {
      vol.Empty.swap(own);
      return;
    }
    for (int n = 0; n < tree.GetNumberOfNodes(); ++n)
    {
      const auto& node = tree.GetNode(n);
      const int* bricks = tree.GetLevelBricks(node.Level);
      bool empty = true;
      for (int dk = -1; dk <= 1 && empty; ++dk)
        for (int dj = -1; dj <= 1 && empty; ++dj)
          for (int di = -1; di <= 1 && empty; ++di)
          {
            const int i = node.Index[0] + di, j = node.Index[1] + dj, k = node.Index[2] + dk;
            if (i >= 0 && j >= 0 && k >= 0 && i < bricks[0] && j < bricks[1] && k < bricks[2])
              empty = own[tree.GetNodeId(node.Level, i, j, k)] != 0;
          }
      vol.Empty[n] = empty;
    }
  }

  int VisibleChildren(int v, int n) const
  {
    int children[8];
    const int count = this->Volumes[v].Tree->GetChildren(n, children);
    int visible = 0;
    for (int c = 0; c < count; ++c)
    {
      visible += this->Volumes[v].Empty[children[c]] ? 0 : 1;
    }
    return visible;
  }

  /// Pages a split of n adds to those held (a collapse frees as many): its visible children,
  /// in a volume whose pages are held (one with an availability function).
  int HeldChildren(int v, int n) const
  {
    return this->Volumes[v].Available ? this->VisibleChildren(v, n) : 0;
  }

  // Asks for every visible child (so all missing ones get queued), true if all are there.
  bool ChildrenAvailable(int v, int n) const
  {
    const Volume& vol = this->Volumes[v];
    if (!vol.Available)
      return true;
    int children[8];
    const int count = vol.Tree->GetChildren(n, children);
    bool all = true;
    for (int c = 0; c < count; ++c)
    {
      if (!vol.Empty[children[c]])
        all = vol.Available(children[c], vol.Priority[n]) && all;
    }
    return all;
  }

  bool Splittable(int v, int n) const
  {
    const Volume& vol = this->Volumes[v];
    return vol.State[n] == Leaf && !vol.Empty[n] && vol.Tree->GetNode(n).Level > 0 &&
           vol.Priority[n] > this->Threshold;
  }

  bool Collapsible(int v, int n) const
  {
    const Volume& vol = this->Volumes[v];
    if (n < 0 || vol.State[n] != Inner)
    {
      return false;
    }
    int children[8];
    const int count = vol.Tree->GetChildren(n, children);
    for (int c = 0; c < count; ++c)
    {
      if (vol.State[children[c]] != Leaf)
      {
        return false;
      }
    }
    return true;
  }

  void Split(int v, int n)
  {
    Volume& vol = this->Volumes[v];
    this->Splits.erase(this->Key(v, n));
    const int parent = vol.Tree->GetParent(n);
    if (parent >= 0)
    {
      this->Collapses.erase(this->Key(v, parent));
    }
    vol.State[n] = Inner;
    int children[8];
    const int count = vol.Tree->GetChildren(n, children);
    for (int c = 0; c < count; ++c)
    {
      vol.State[children[c]] = Leaf;
      if (this->Splittable(v, children[c]))
      {
        this->Splits.insert(this->Key(v, children[c]));
      }
    }
    this->Collapses.insert(this->Key(v, n));
  }

  void Collapse(int v, int n)
  {
    Volume& vol = this->Volumes[v];
    this->Collapses.erase(this->Key(v, n));
    int children[8];
    const int count = vol.Tree->GetChildren(n, children);
    for (int c = 0; c < count; ++c)
    {
      this->Splits.erase(this->Key(v, children[c]));
      vol.State[children[c]] = Outside;
    }
    vol.State[n] = Leaf;
    if (this->Splittable(v, n))
    {
      this->Splits.insert(this->Key(v, n));
    }
    const int parent = vol.Tree->GetParent(n);
    if (this->Collapsible(v, parent))
    {
      this->Collapses.insert(this->Key(v, parent));
    }
  }

  // Turns an empty inner node back into a leaf: nothing below it is visible.
  void Prune(int v, int n)
  {
    Volume& vol = this->Volumes[v];
    if (vol.State[n] != Inner)
    {
      return;
    }
    int children[8];
    const int count = vol.Tree->GetChildren(n, children);
    for (int c = 0; c < count; ++c)
    {
      if (vol.Empty[n])
      {
        this->Clear(v, children[c]);
      }
      else
      {
        this->Prune(v, children[c]);
      }
    }
    if (vol.Empty[n])
    {
      vol.State[n] = Leaf;
    }
  }

  void Clear(int v, int n)
  {
    Volume& vol = this->Volumes[v];
    if (vol.State[n] == Inner)
    {
      int children[8];
      const int count = vol.Tree->GetChildren(n, children);
      for (int c = 0; c < count; ++c)
      {
        this->Clear(v, children[c]);
      }
    }
    vol.State[n] = Outside;
  }
};

VolumeCut::VolumeCut()
  : Internals(new vtkInternals)
{
}

VolumeCut::~VolumeCut() = default;

double VolumeCut::PixelsPerRadian(int heightPixels, double viewAngleDegrees)
{
  const double halfAngle = 0.5 * viewAngleDegrees * 3.14159265358979323846 / 180.0;
  return heightPixels / (2.0 * std::tan(halfAngle));
}

int VolumeCut::AddVolume(const strata::VolumeBrickTree* tree, const double indexToWorld[16])
{
  vtkInternals::Volume vol;
  vol.Tree = tree;
  const size_t nodes = static_cast<size_t>(tree->GetNumberOfNodes());
  vol.State.assign(nodes, Outside);
  vol.State[tree->GetRootId()] = Leaf;
  vol.Empty.assign(nodes, 0);
  vol.Priority.assign(nodes, 0.0);
  vol.Slot.assign(nodes, -1);
  this->Internals->Volumes.push_back(std::move(vol));
  const int id = static_cast<int>(this->Internals->Volumes.size()) - 1;
  this->SetVolumeMatrix(id, indexToWorld);
  return id;
}

void VolumeCut::SetVolumeMatrix(int volume, const double indexToWorld[16])
{
  vtkInternals::Volume& vol = this->Internals->Volumes[volume];
  std::copy(indexToWorld, indexToWorld + 16, vol.Matrix);
  // The longest edge of a voxel over the axes that have voxels: a flat axis (one point) has
  // no spacing that the viewer could resolve.
  const int* dims = vol.Tree->GetLevelDimensions(0);
  double longest = 0.0, any = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double m = indexToWorld[a], n = indexToWorld[4 + a], o = indexToWorld[8 + a];
    const double edge = std::sqrt(m * m + n * n + o * o);
    any = std::max(any, edge);
    longest = dims[a] > 1 ? std::max(longest, edge) : longest;
  }
  vol.VoxelSize = longest > 0.0 ? longest : (any > 0.0 ? any : 1.0);
}

void VolumeCut::SetVolumeAvailability(int volume, AvailabilityFunction available)
{
  this->Internals->Volumes[volume].Available = std::move(available);
}

void VolumeCut::SetVolumePriority(int volume, PriorityFunction priority)
{
  this->Internals->Volumes[volume].Rank = std::move(priority);
}

void VolumeCut::SetVolumeOpacity(int volume, OpacityRangeFunction maxOpacity)
{
  this->Internals->Volumes[volume].Opacity = std::move(maxOpacity);
}

void VolumeCut::SetVolumeHalo(int volume, bool halo)
{
  this->Internals->Volumes[volume].Halo = halo;
}

void VolumeCut::RemoveAllVolumes()
{
  this->Internals->Volumes.clear();
}

int VolumeCut::GetNumberOfVolumes() const
{
  return static_cast<int>(this->Internals->Volumes.size());
}

const strata::VolumeBrickTree* VolumeCut::GetTree(int volume) const
{
  return this->Internals->Volumes[volume].Tree;
}

void VolumeCut::Reset()
{
  for (auto& vol : this->Internals->Volumes)
  {
    std::fill(vol.State.begin(), vol.State.end(), Outside);
    vol.State[vol.Tree->GetRootId()] = Leaf;
    std::fill(vol.Slot.begin(), vol.Slot.end(), -1);
  }
}

double VolumeCut::ComputeScreenSpaceError(int volume, int node, const Camera& camera) const
{
  const vtkInternals::Volume& vol = this->Internals->Volumes[volume];
  double b[6];
  vol.Tree->GetNodeBounds(node, b);
  const double* m = vol.Matrix;
  double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
  double corners[8][3];
  for (int c = 0; c < 8; ++c)
  {
    const double p[3] = { b[c & 1], b[2 + ((c >> 1) & 1)], b[4 + ((c >> 2) & 1)] };
    for (int r = 0; r < 3; ++r)
    {
      corners[c][r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
      lo[r] = std::min(lo[r], corners[c][r]);
      hi[r] = std::max(hi[r], corners[c][r]);
    }
  }
  if (camera.UseFrustum)
  {
    for (int q = 0; q < 6; ++q)
    {
      const double* pl = camera.FrustumPlanes + 4 * q;
      bool outside = true;
      for (int c = 0; c < 8 && outside; ++c)
      {
        outside =
          pl[0] * corners[c][0] + pl[1] * corners[c][1] + pl[2] * corners[c][2] + pl[3] < 0.0;
      }
      if (outside)
      {
        return 0.0;
      }
    }
  }
  const double voxel = vol.VoxelSize * static_cast<double>(1 << vol.Tree->GetNode(node).Level);
  if (camera.PixelsPerUnit > 0.0)
  {
    return voxel * camera.PixelsPerUnit;
  }
  // Distance to the world box of the node: its nearest voxel sets the detail it needs. It is
  // clamped to one level-0 voxel so that the node holding the eye gets a large, finite error.
  double d2 = 0.0;
  for (int r = 0; r < 3; ++r)
  {
    const double e = camera.Position[r];
    const double g = e < lo[r] ? lo[r] - e : (e > hi[r] ? e - hi[r] : 0.0);
    d2 += g * g;
  }
  const double distance = std::max(std::sqrt(d2), vol.VoxelSize);
  return voxel / distance * camera.PixelsPerRadian;
}

int VolumeCut::Update(const Camera& camera)
{
  vtkInternals& in = *this->Internals;
  in.Threshold = this->ErrorThreshold;

  // Classify and prioritise every node: a few thousand per volume, cheaper than tracking
  // which ones a camera or transfer function change affects.
  for (int v = 0; v < this->GetNumberOfVolumes(); ++v)
  {
    vtkInternals::Volume& vol = in.Volumes[v];
    in.Classify(v, camera);
    for (int n = 0; n < vol.Tree->GetNumberOfNodes(); ++n)
    {
      double opacity = 1.0;
      if (vol.Opacity && this->OpacityWeighting)
      {
        const auto& node = vol.Tree->GetNode(n);
        opacity =
          node.SubtreeMin <= node.SubtreeMax ? vol.Opacity(node.SubtreeMin, node.SubtreeMax) : 0.0;
      }
      double priority = vol.Empty[n] ? 0.0 : this->ComputeScreenSpaceError(v, n, camera);
      if (vol.Rank && !vol.Empty[n])
      {
        priority = vol.Rank(n, priority);
      }
      if (this->OpacityWeighting)
      {
        priority *= std::min(1.0, opacity);
      }
      vol.Priority[n] = priority;
    }
    in.Prune(v, vol.Tree->GetRootId());
  }

  in.Splits.clear();
  in.Collapses.clear();
  int cost = 0;
  for (int v = 0; v < this->GetNumberOfVolumes(); ++v)
  {
    const vtkInternals::Volume& vol = in.Volumes[v];
    for (int n = 0; n < vol.Tree->GetNumberOfNodes(); ++n)
    {
      cost += vol.State[n] == Leaf && !vol.Empty[n] ? 1 : 0;
      if (in.Splittable(v, n))
      {
        in.Splits.insert(in.Key(v, n));
      }
      else if (in.Collapsible(v, n))
      {
        in.Collapses.insert(in.Key(v, n));
      }
    }
  }

  // Over budget (the budget shrank, the camera moved, a transfer function revealed bricks):
  // give back the least important detail first. Collapses upload at most the parent, which is
  // needed now whatever the upload bound says.
  int added = 0;
  int held = this->GetHeldPages();
  const int pageBudget = this->PageBudget > 0 ? this->PageBudget : INT_MAX;
  while ((cost > this->Budget || held > pageBudget) && !in.Collapses.empty())
  {
    const auto [p, v, n] = *in.Collapses.begin();
    (void)p;
    cost -= in.VisibleChildren(v, n) - 1;
    held -= in.HeldChildren(v, n);
    in.Collapse(v, n);
    ++added;
  }

  // Refine: the highest-priority split first. A split that does not fit may be paid for by
  // collapsing parents of strictly lower priority (strictly, so two nodes of equal priority
  // cannot trade places forever); if even that is not enough it waits for the next Update,
  // and cheaper splits behind it still get their chance.
  const int bound = this->MaxNewBricksPerUpdate;
  std::vector<int> payers;
  while (!in.Splits.empty())
  {
    const auto [priority, v, n] = *in.Splits.rbegin();
    const int children = in.VisibleChildren(v, n);
    // The bound stops refinement after the first split that reaches it: a split larger than
    // the bound must still happen, or the cut would never refine past it.
    if (bound > 0 && added > 0 && added + children > bound)
    {
      break;
    }
    const int need = cost + children - 1 - this->Budget;
    const int needPages = this->PageBudget > 0 ? held + in.HeldChildren(v, n) - pageBudget : 0;
    int freed = 0, freedPages = 0;
    payers.clear();
    if (need > 0 || needPages > 0)
    {
      const int parent = in.Volumes[v].Tree->GetParent(n);
      for (const auto& [cp, cv, cn] : in.Collapses)
      {
        if (cp >= priority || (freed >= need && freedPages >= needPages))
        {
          break;
        }
        const int gain = in.VisibleChildren(cv, cn) - 1;
        const int gainPages = in.HeldChildren(cv, cn);
        if ((cv == v && cn == parent) || (gain <= 0 && (needPages <= 0 || gainPages <= 0)))
        {
          continue;
        }
        payers.push_back(cv);
        payers.push_back(cn);
        freed += gain;
        freedPages += gainPages;
      }
    }
    const int moves = static_cast<int>(payers.size()) / 2;
    // Data last: only a split that fits asks for its children's pages, so a paging renderer
    // never loads what the budget would not let it show.
    if (freed < need || freedPages < needPages ||
        (bound > 0 && added > 0 && added + children + moves > bound) || !in.ChildrenAvailable(v, n))
    {
      in.Splits.erase(in.Splits.find(Entry(priority, v, n)));
      continue;
    }
    for (size_t q = 0; q < payers.size(); q += 2)
    {
      in.Collapse(payers[q], payers[q + 1]);
    }
    in.Split(v, n);
    cost += children - 1 - freed;
    held += in.HeldChildren(v, n) - freedPages;
    added += children + moves;
  }
  in.Splits.clear();
  in.Collapses.clear();
  return added;
}

bool VolumeCut::IsInCut(int volume, int node) const
{
  return this->Internals->Volumes[volume].State[node] == Leaf;
}

bool VolumeCut::IsEmpty(int volume, int node) const
{
  return this->Internals->Volumes[volume].Empty[node] != 0;
}

std::vector<int> VolumeCut::GetCutNodes(int volume) const
{
  const auto& vol = this->Internals->Volumes[volume];
  std::vector<int> nodes;
  for (int n = 0; n < static_cast<int>(vol.State.size()); ++n)
  {
    if (vol.State[n] == Leaf)
    {
      nodes.push_back(n);
    }
  }
  return nodes;
}

int VolumeCut::GetVolumeCost(int volume) const
{
  const auto& vol = this->Internals->Volumes[volume];
  int cost = 0;
  for (size_t n = 0; n < vol.State.size(); ++n)
  {
    cost += vol.State[n] == Leaf && !vol.Empty[n] ? 1 : 0;
  }
  return cost;
}

int VolumeCut::GetCost() const
{
  int cost = 0;
  for (int v = 0; v < this->GetNumberOfVolumes(); ++v)
  {
    cost += this->GetVolumeCost(v);
  }
  return cost;
}

int VolumeCut::GetHeldPages() const
{
  int held = 0;
  for (const auto& vol : this->Internals->Volumes)
  {
    if (!vol.Available)
    {
      continue;
    }
    for (size_t n = 0; n < vol.State.size(); ++n)
    {
      held += (vol.State[n] == Leaf && !vol.Empty[n]) || vol.State[n] == Inner ? 1 : 0;
    }
  }
  return held;
}

double VolumeCut::GetPriority(int volume, int node) const
{
  return this->Internals->Volumes[volume].Priority[node];
}

int VolumeCut::AssignSlots(strata::BrickAtlasAllocator& atlas, std::vector<Upload>& uploads)
{
  uploads.clear();
  std::vector<std::pair<int, int>> misses;
  for (int v = 0; v < this->GetNumberOfVolumes(); ++v)
  {
    auto& vol = this->Internals->Volumes[v];
    std::fill(vol.Slot.begin(), vol.Slot.end(), -1);
    for (int n = 0; n < vol.Tree->GetNumberOfNodes(); ++n)
    {
      if (vol.State[n] != Leaf || vol.Empty[n])
      {
        continue;
      }
      strata::BrickAtlasAllocator::Key key;
      key.Volume = v;
      key.Level = vol.Tree->GetNode(n).Level;
      key.Brick = n - vol.Tree->GetLevelOffset(key.Level);
      if (atlas.Find(key) >= 0)
      {
        vol.Slot[n] = atlas.Request(key).Slot; // pin before any miss can evict it
      }
      else
      {
        misses.emplace_back(v, n);
      }
    }
  }
  int failed = 0;
  for (const auto& [v, n] : misses)
  {
    auto& vol = this->Internals->Volumes[v];
    strata::BrickAtlasAllocator::Key key;
    key.Volume = v;
    key.Level = vol.Tree->GetNode(n).Level;
    key.Brick = n - vol.Tree->GetLevelOffset(key.Level);
    const auto result = atlas.Request(key);
    vol.Slot[n] = result.Slot;
    if (result.Slot < 0)
    {
      ++failed;
    }
    else
    {
      uploads.push_back({ v, n, result.Slot });
    }
  }
  return failed;
}

int VolumeCut::GetSlot(int volume, int node) const
{
  return this->Internals->Volumes[volume].Slot[node];
}

int VolumeCut::BuildIndexTable(int volume,
  const strata::BrickAtlasAllocator& atlas,
  std::vector<uint16_t>& table) const
{
  const auto& vol = this->Internals->Volumes[volume];
  const int* nb = vol.Tree->GetLevelBricks(0);
  table.assign(static_cast<size_t>(nb[0]) * nb[1] * nb[2] * 4, 0);
  int missing = 0;
  // Each cut node fills the level-0 bricks below it: (I 2^l .. (I+1) 2^l - 1) per axis.
  for (int n = 0; n < vol.Tree->GetNumberOfNodes(); ++n)
  {
    if (vol.State[n] != Leaf)
    {
      continue;
    }
    const auto& node = vol.Tree->GetNode(n);
    uint16_t entry[4] = { 0, 0, 0, EmptyLevel };
    if (!vol.Empty[n])
    {
      if (vol.Slot[n] < 0)
      {
        entry[3] = MissingLevel;
      }
      else
      {
        const auto s = atlas.GetSlotPosition(vol.Slot[n]);
        entry[0] = static_cast<uint16_t>(s[0]);
        entry[1] = static_cast<uint16_t>(s[1]);
        entry[2] = static_cast<uint16_t>(s[2]);
        entry[3] = static_cast<uint16_t>(node.Level);
      }
    }
    const int span = 1 << node.Level;
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = node.Index[a] * span;
      hi[a] = std::min(lo[a] + span, nb[a]);
    }
    for (int k = lo[2]; k < hi[2]; ++k)
    {
      for (int j = lo[1]; j < hi[1]; ++j)
      {
        for (int i = lo[0]; i < hi[0]; ++i)
        {
          std::copy(entry,
            entry + 4,
            table.begin() + 4 * ((static_cast<size_t>(k) * nb[1] + j) * nb[0] + i));
          missing += entry[3] == MissingLevel ? 1 : 0;
        }
      }
    }
  }
  return missing;
}

bool VolumeCut::MapToAtlas(const uint16_t* table,
  const int tableDims[3],
  int brickSize,
  const double index[3],
  double atlasTexel[3],
  int& level)
{
  const int stride = brickSize - 1;
  double x[3];
  int b[3];
  for (int a = 0; a < 3; ++a)
  {
    x[a] = std::clamp(index[a], 0.0, static_cast<double>(tableDims[a]) * stride);
    b[a] = std::min(static_cast<int>(std::floor(x[a] / stride)), tableDims[a] - 1);
  }
  const uint16_t* e =
    table + 4 * ((static_cast<size_t>(b[2]) * tableDims[1] + b[1]) * tableDims[0] + b[0]);
  if (e[3] == EmptyLevel || e[3] == MissingLevel)
  {
    level = -1;
    return false;
  }
  level = e[3];
  const double scale = 1.0 / static_cast<double>(1 << level);
  for (int a = 0; a < 3; ++a)
  {
    atlasTexel[a] =
      e[a] * static_cast<double>(brickSize) + x[a] * scale - (b[a] >> level) * stride + 0.5;
  }
  return true;
}

double VolumeCut::MaxOfPiecewiseLinear(const double* xy, int count, double lo, double hi)
{
  if (count < 1)
  {
    return 0.0;
  }
  auto at = [&](double x)
  {
    if (x <= xy[0])
    {
      return xy[1];
    }
    for (int q = 1; q < count; ++q)
    {
      if (x <= xy[2 * q])
      {
        const double x0 = xy[2 * q - 2], x1 = xy[2 * q];
        const double t = x1 > x0 ? (x - x0) / (x1 - x0) : 1.0;
        return xy[2 * q - 1] + t * (xy[2 * q + 1] - xy[2 * q - 1]);
      }
    }
    return xy[2 * count - 1];
  };
  // A linear piece peaks at an end: the range ends and the nodes inside are all candidates.
  double best = std::max(at(lo), at(hi));
  for (int q = 0; q < count; ++q)
  {
    if (xy[2 * q] > lo && xy[2 * q] < hi)
    {
      best = std::max(best, xy[2 * q + 1]);
    }
  }
  return best;
}
}
