// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataHeightFieldPager.h"

#include "StrataBrickAtlasAllocator.h"
#include "StrataCutPages.h"
#include "StrataFeedbackReduction.h"
#include "StrataMinMaxQuadtree.h"
#include "StrataPageCache.h"
#include "StrataPagePoolFile.h"
#include "StrataPagedPools.h"
#include "StrataVolumeBrickTree.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <sstream>
#include <unordered_map>

namespace strata
{

namespace
{
constexpr float Inf = std::numeric_limits<float>::infinity();
}

class HeightFieldPager::vtkInternals
{
public:
  struct Pool
  {
    std::shared_ptr<strata::PagePoolFile> File;
    std::string Name;
    strata::VolumeBrickTree Tree; ///< structure only: the pool's quadtree of tiles
  };
  /// A page kept in RAM for the cut (or an ancestor of it), with its leaf ranges once needed.
  struct Held
  {
    strata::PageCache::Page Data;
    size_t Offset = 0; ///< first value of the horizon's layer in Data (floats)
    std::vector<float> LeafMin, LeafMax;
    /// Stitched border texels (x = 0 column, x = B - 1 column, y = 0 row, y = B - 1 row, B
    /// each), empty where the page's own border stands (see Stitch()).
    std::vector<float> Border;
    /// While the page blends in from its parent (see Morph()): the B x B heights shown, the
    /// parent's surface at its points when it entered, and the frames since.
    std::vector<float> Display, From;
    int MorphStep = 0;
    /// What the stitched border texels span while the pages they follow blend (equal to
    /// Border where those do not): what the leaf ranges bound, so that a blend does not
    /// rebuild the quadtree every frame.
    std::vector<float> BorderLo, BorderHi;
  };
  struct Horizon
  {
    int PoolIndex = 0;
    int Layer = 0;
    std::map<int, Held> Pages; ///< by tree node id
  };

  std::vector<std::unique_ptr<Pool>> Pools;
  std::vector<Horizon> Horizons;
  std::vector<std::pair<std::string, int>> OpenedSources;
  strata::PagedPools Paging; ///< the pools (by index in Pools), RAM cache, requests and roots
  int MorphFrames = 0;
  static constexpr int MaxMorphingPages = 64;
  std::vector<std::vector<char>> WasInCut; ///< per horizon and node, after the last Update()
  strata::PageCache Cache;
  strata::VolumeCut Cut;
  strata::BrickAtlasAllocator Atlas;
  strata::MinMaxQuadtree Tree;
  std::vector<uint16_t> Table;
  std::vector<uint16_t> TableLevels; ///< the level column of Table, what the quadtree depends on
  std::string Error;
  bool Open = false;
  int NX = 0, NY = 0, B = 0, S = 0;
  int Tiles[2] = { 0, 0 };
  int AtlasSlots = 512;
  int InitializedSlots = -1;
  int PagesPerFrame = 64;
  int TileSize = 64;
  int Leaf = 64;
  double ValueRange[2] = { 0.0, -1.0 };
  bool Holes = false;
  bool HasNoData = false;
  double NoData = 0.0;
  strata::PagePoolFile::Header Header;
  HeightFieldPager::Statistics Stats;

  // Feedback: page id -> (coverage, frame last asked for); per horizon, the requests summed
  // over each node's subtree.
  bool UseFeedback = false;
  int64_t FeedbackFrame = 0;
  int FeedbackCycle = 1;
  int64_t CycleStart = 0;
  std::unordered_map<uint32_t, std::pair<uint32_t, int64_t>> Requests;
  std::vector<std::vector<double>> SubtreeRequests;
  /// Per horizon and node: the most pixels that asked at or below it since the view last
  /// changed, what the priority of a split node (a collapse candidate) reads. Requests stop
  /// once the rays get their detail, so without this memory a refined node would rank 0 and
  /// be the first collapse paid for another split; under a budget too small for every
  /// request the cut then traded tiles forever (issue 14). With it a split node keeps the
  /// claim its pixels made, a split pays only with strictly lower claims, and the cut
  /// settles. Tiles of the cut still split only for live requests, so a claim made by rays
  /// that hit a coarser surface elsewhere refines nothing once they stop; a view change
  /// forgets the claims (the live requests stay).
  std::vector<std::vector<double>> Demand;

  void UpdateDemand(bool viewChanged)
  {
    if (this->Demand.size() != this->SubtreeRequests.size())
    {
      this->Demand = this->SubtreeRequests;
      return;
    }
    for (size_t h = 0; h < this->Demand.size(); ++h)
    {
      std::vector<double>& d = this->Demand[h];
      const std::vector<double>& asked = this->SubtreeRequests[h];
      if (d.size() != asked.size())
      {
        d = asked;
        continue;
      }
      for (size_t n = 0; n < d.size(); ++n)
        d[n] = viewChanged ? asked[n] : std::max(d[n], asked[n]);
    }
  }

  void SumRequests()
  {
    this->SubtreeRequests.assign(this->Horizons.size(), std::vector<double>());
    for (size_t h = 0; h < this->Horizons.size(); ++h)
      this->SubtreeRequests[h].assign(
        this->Pools[this->Horizons[h].PoolIndex]->Tree.GetNumberOfNodes(), 0.0);
    for (const auto& r : this->Requests)
    {
      const int h = strata::FeedbackReduction::GetDataSet(r.first);
      const int level = strata::FeedbackReduction::GetLevel(r.first);
      if (h < 0 || h >= static_cast<int>(this->Horizons.size()))
        continue;
      const strata::VolumeBrickTree& tree = this->Pools[this->Horizons[h].PoolIndex]->Tree;
      if (level >= tree.GetNumberOfLevels())
        continue;
      const int* bricks = tree.GetLevelBricks(level);
      const int64_t index = strata::FeedbackReduction::GetPageIndex(r.first);
      if (index >= static_cast<int64_t>(bricks[0]) * bricks[1])
        continue;
      for (int n = tree.GetLevelOffset(level) + static_cast<int>(index); n >= 0;
           n = tree.GetParent(n))
        this->SubtreeRequests[h][n] += r.second.first;
    }
  }

  bool IsHole(float v) const
  {
    return std::isnan(v) || (this->HasNoData && v == static_cast<float>(this->NoData));
  }

  void ComputeLeaves(int h, int node, Held& held) const
  {
    const Horizon& hz = this->Horizons[h];
    const strata::VolumeBrickTree& tree = this->Pools[hz.PoolIndex]->Tree;
    const auto& n = tree.GetNode(node);
    const int l = n.Level;
    const int R = this->S / this->Leaf;
    const auto leaves = strata::MinMaxQuadtree::GetLeafCount(this->NX, this->NY, this->Leaf);
    int a0[2], a1[2];
    for (int axis = 0; axis < 2; ++axis)
    {
      a0[axis] = std::min((n.Index[axis] << l) * R, leaves[axis]);
      a1[axis] = std::min(((n.Index[axis] + 1) << l) * R, leaves[axis]);
    }
    const int na = a1[0] - a0[0];
    const int nb = a1[1] - a0[1];
    held.LeafMin.assign(static_cast<size_t>(std::max(0, na)) * std::max(0, nb), Inf);
    held.LeafMax.assign(held.LeafMin.size(), -Inf);
    const float* values = reinterpret_cast<const float*>(held.Data->data()) + held.Offset;
    const int last[2] = { this->NX - 1, this->NY - 1 };
    const int step = (1 << l) - 1;
    for (int b = a0[1]; b < a1[1]; ++b)
    {
      const int y0 = b * this->Leaf, y1 = std::min((b + 1) * this->Leaf, last[1]);
      const int qy0 = std::max(0, (y0 >> l) - n.Index[1] * this->S);
      const int qy1 = std::min(this->B - 1, ((y1 + step) >> l) - n.Index[1] * this->S);
      for (int a = a0[0]; a < a1[0]; ++a)
      {
        const int x0 = a * this->Leaf, x1 = std::min((a + 1) * this->Leaf, last[0]);
        const int qx0 = std::max(0, (x0 >> l) - n.Index[0] * this->S);
        const int qx1 = std::min(this->B - 1, ((x1 + step) >> l) - n.Index[0] * this->S);
        float lo = Inf, hi = -Inf;
        for (int qy = qy0; qy <= qy1; ++qy)
        {
          for (int qx = qx0; qx <= qx1; ++qx)
          {
            // What the texel spans until the blends under way end (its value if none).
            float vlo, vhi;
            this->TexelRange(held, values, qx, qy, vlo, vhi);
            if (!std::isnan(vlo))
            {
              lo = std::min(lo, vlo);
              hi = std::max(hi, vhi);
            }
          }
        }
        const size_t k = static_cast<size_t>(b - a0[1]) * na + (a - a0[0]);
        held.LeafMin[k] = lo;
        held.LeafMax[k] = hi;
      }
    }
  }

  /// The cut node covering level-0 tile (tx, ty) of horizon h per the table, -1 when none.
  int NodeOfTile(int h, int tx, int ty, int& level) const
  {
    const size_t e = ((static_cast<size_t>(h) * this->Tiles[1] + ty) * this->Tiles[0] + tx) * 4;
    level = this->Table[e + 3];
    if (level >= strata::VolumeCut::MissingLevel)
      return -1;
    const strata::VolumeBrickTree& tree = this->Pools[this->Horizons[h].PoolIndex]->Tree;
    const int* bricks = tree.GetLevelBricks(level);
    return tree.GetLevelOffset(level) + (ty >> level) * bricks[0] + (tx >> level);
  }

  // The lookup of vtkStackedHeightFieldPagedLookup.glsl, operation for operation: per level-0
  // tile the page of the cut covering it (values, level, first point in its level's
  // coordinates); texels on a page's border come from its stitched border when it has one.
  struct PageRef
  {
    const float* Values = nullptr;
    const Held* Page = nullptr;
    int Node = -1;
    int Level = -1;
    int Base[2] = { 0, 0 };
    /// The level it shows: a tile blending in from its parent counts as strictly between the
    /// two (Level + 1 - (k + 1/2) / n at step k of n), so it owns the borders it shares with tiles
    /// of its own level and yields those it shares with its parent's, and only tiles that show
    /// the same (siblings, or cousins that entered together) ever tie (see Stitch()).
    float Effective = -1.0f;
  };
  static constexpr float Big = 3.0e38f;
  std::vector<PageRef> TilePages; ///< per horizon and level-0 tile, refreshed by Update()

  PageRef TilePage(int h, int tx, int ty) const
  {
    const size_t k = (static_cast<size_t>(h) * this->Tiles[1] + ty) * this->Tiles[0] + tx;
    return k < this->TilePages.size() ? this->TilePages[k] : PageRef();
  }

  void RefreshTilePages()
  {
    this->TilePages.assign(this->Horizons.size() * this->Tiles[0] * this->Tiles[1], PageRef());
    for (int h = 0; h < static_cast<int>(this->Horizons.size()); ++h)
      for (int ty = 0; ty < this->Tiles[1]; ++ty)
        for (int tx = 0; tx < this->Tiles[0]; ++tx)
        {
          PageRef& page =
            this->TilePages[(static_cast<size_t>(h) * this->Tiles[1] + ty) * this->Tiles[0] + tx];
          int level = 0;
          const int node = this->NodeOfTile(h, tx, ty, level);
          const auto& pages = this->Horizons[h].Pages;
          auto it = node >= 0 ? pages.find(node) : pages.end();
          if (it != pages.end())
            page = this->RefOf(h, node, it->second);
        }
  }

  float EffectiveLevel(int level, const Held& held) const
  {
    return held.Display.empty() || this->MorphFrames <= 0
             ? static_cast<float>(level)
             : static_cast<float>(level) + 1.0f -
                 (static_cast<float>(held.MorphStep) + 0.5f) /
                   static_cast<float>(this->MorphFrames);
  }

  /// Index of page texel (qx, qy) in a stitched border (Held::Border's layout), -1 inside.
  int BorderIndex(int qx, int qy) const
  {
    const int B = this->B;
    return qx == 0       ? qy
           : qx == B - 1 ? B + qy
           : qy == 0     ? 2 * B + qx
           : qy == B - 1 ? 3 * B + qx
                         : -1;
  }

  /// Texel (qx, qy) of a page as the atlas holds it: stitched on the border, NaN for holes.
  float Texel(const Held& held, const float* values, int qx, int qy) const
  {
    float v;
    const int b = held.Border.empty() ? -1 : this->BorderIndex(qx, qy);
    if (b >= 0)
      v = held.Border[b];
    else
      v = (held.Display.empty() ? values
                                : held.Display.data())[static_cast<size_t>(qy) * this->B + qx];
    return this->IsHole(v) ? std::numeric_limits<float>::quiet_NaN() : v;
  }

  static float Mix(float a, float b, float t) { return a * (1.0f - t) + b * t; }

  /// The range texel (qx, qy) of a page spans over the blends under way: a blending page's
  /// texel lies between its parent's and its own height, a stitched border texel inside its
  /// envelope; otherwise the texel itself. NaN for a hole.
  void TexelRange(const Held& held, const float* values, int qx, int qy, float& lo, float& hi) const
  {
    const int b = held.Border.empty() ? -1 : this->BorderIndex(qx, qy);
    if (b >= 0)
    {
      lo = held.BorderLo[b];
      hi = held.BorderHi[b];
      if (this->IsHole(lo) || this->IsHole(hi))
        lo = hi = std::numeric_limits<float>::quiet_NaN();
      return;
    }
    const size_t k = static_cast<size_t>(qy) * this->B + qx;
    const float v = this->IsHole(values[k]) ? std::numeric_limits<float>::quiet_NaN() : values[k];
    lo = hi = v;
    if (!held.From.empty() && !std::isnan(v) && !std::isnan(held.From[k]))
    {
      lo = std::min(v, held.From[k]);
      hi = std::max(v, held.From[k]);
    }
  }

  /// Level l of a page bilinearly at level-0 point (i, j) (strataHeight's arithmetic), its
  /// texels read by `texel(qx, qy)`.
  template<typename Texel>
  float Bilinear(const PageRef& page, int i, int j, Texel texel) const
  {
    const int l = page.Level;
    const int qx = (i >> l) - page.Base[0], qy = (j >> l) - page.Base[1];
    const int rx = i & ((1 << l) - 1), ry = j & ((1 << l) - 1);
    const float h00 = texel(qx, qy);
    if (rx == 0 && ry == 0)
      return h00;
    const float h10 = rx ? texel(qx + 1, qy) : h00;
    const float h01 = ry ? texel(qx, qy + 1) : h00;
    const float h11 = rx && ry ? texel(qx + 1, qy + 1) : (rx ? h10 : h01);
    const float fx = static_cast<float>(rx) / static_cast<float>(1 << l);
    const float fy = static_cast<float>(ry) / static_cast<float>(1 << l);
    return Mix(Mix(h00, h10, fx), Mix(h01, h11, fx), fy);
  }

  /// The page as shown (stitched, blended) at level-0 point (i, j).
  float PageHeight(const PageRef& page, int i, int j) const
  {
    return this->Bilinear(
      page, i, j, [&](int qx, int qy) { return this->Texel(*page.Page, page.Values, qx, qy); });
  }

  /// The page's level at (i, j) from the heights `values` (B x B) alone, borders unstitched.
  float ArrayHeight(const PageRef& page, const float* values, int i, int j) const
  {
    return this->Bilinear(page,
      i,
      j,
      [&](int qx, int qy)
      {
        const float v = values[static_cast<size_t>(qy) * this->B + qx];
        return this->IsHole(v) ? std::numeric_limits<float>::quiet_NaN() : v;
      });
  }

  float Height(int h, int i, int j) const
  {
    const PageRef page = this->TilePage(
      h, std::min(i / this->S, this->Tiles[0] - 1), std::min(j / this->S, this->Tiles[1] - 1));
    return page.Level < 0 ? Big : this->PageHeight(page, i, j);
  }

  /// The coarsest cut page among the (up to four) tiles whose closed regions hold (i, j).
  PageRef Owner(int h, int i, int j) const
  {
    const int tx = std::min(i / this->S, this->Tiles[0] - 1),
              ty = std::min(j / this->S, this->Tiles[1] - 1);
    PageRef best = this->TilePage(h, tx, ty);
    const bool lx = i > 0 && i % this->S == 0 && i / this->S < this->Tiles[0];
    const bool ly = j > 0 && j % this->S == 0 && j / this->S < this->Tiles[1];
    auto consider = [&](int x, int y)
    {
      const PageRef p = this->TilePage(h, x, y);
      if (p.Effective > best.Effective)
        best = p;
    };
    if (lx)
      consider(tx - 1, ty);
    if (ly)
      consider(tx, ty - 1);
    if (lx && ly)
      consider(tx - 1, ty - 1);
    return best;
  }

  /// The page `held` of node `node` as a lookup (level, first point, shown level).
  PageRef RefOf(int h, int node, const Held& held) const
  {
    const auto& n = this->Pools[this->Horizons[h].PoolIndex]->Tree.GetNode(node);
    PageRef page;
    page.Values = reinterpret_cast<const float*>(held.Data->data()) + held.Offset;
    page.Page = &held;
    page.Node = node;
    page.Level = n.Level;
    page.Base[0] = n.Index[0] * this->S;
    page.Base[1] = n.Index[1] * this->S;
    page.Effective = this->EffectiveLevel(n.Level, held);
    return page;
  }

  /**
   * Blending of refinements (SetMorphFrames): advances the tiles that blend, starts the tiles
   * that entered the cut by a split (from their parent's surface as it was shown last frame, so
   * the first frame looks exactly as before), and adds every blending tile to `uploads`.
   * Returns whether any shown height changed.
   */
  bool MorphEnded = false; ///< a blend ended (or started) in the last Morph(): rebuild the tree
  bool Morph(std::vector<HeightFieldPager::Upload>& uploads)
  {
    bool changed = false;
    this->MorphEnded = false;
    this->Stats.MorphingTiles = 0;
    auto upload = [&](int h, int n)
    {
      const int slot = this->Cut.GetSlot(h, n);
      if (slot < 0)
        return; // in the cut without an atlas slot: not drawn
      for (const auto& u : uploads)
        if (u.Horizon == h && u.Node == n)
          return;
      uploads.push_back({ h, n, slot });
    };
    if (this->MorphFrames <= 0)
    {
      // Off: no cut membership to track per frame; blends under way when it was switched off
      // end now.
      this->WasInCut.clear();
      for (int h = 0; h < static_cast<int>(this->Horizons.size()); ++h)
        for (auto& [n, held] : this->Horizons[h].Pages)
          if (!held.Display.empty())
          {
            held.Display.clear();
            held.From.clear();
            held.LeafMin.clear();
            if (this->Cut.IsInCut(h, n))
              upload(h, n);
            changed = this->MorphEnded = true;
          }
      return changed;
    }
    int morphing = 0;
    const int B = this->B;
    const size_t count = static_cast<size_t>(B) * B;
    this->WasInCut.resize(this->Horizons.size());
    for (int h = 0; h < static_cast<int>(this->Horizons.size()); ++h)
    {
      Horizon& hz = this->Horizons[h];
      const strata::VolumeBrickTree& tree = this->Pools[hz.PoolIndex]->Tree;
      std::vector<char> inCut(tree.GetNumberOfNodes(), 0);
      const std::vector<int> nodes = this->Cut.GetCutNodes(h);
      for (int n : nodes)
        inCut[n] = 1;
      std::vector<char>& was = this->WasInCut[h];
      const bool first = was.size() != inCut.size();
      for (auto& [n, held] : hz.Pages)
        if (!inCut[n] && !held.Display.empty())
        {
          held.Display.clear(); // it left the cut: its children took their start from it
          held.From.clear();
        }
      for (int n : nodes)
      {
        auto it = hz.Pages.find(n);
        if (it == hz.Pages.end())
          continue;
        Held& held = it->second;
        const float* own = reinterpret_cast<const float*>(held.Data->data()) + held.Offset;
        if (held.Display.empty())
        {
          // Entered by a split this frame: start from the parent's surface.
          const int parent = tree.GetParent(n);
          auto p = parent >= 0 ? hz.Pages.find(parent) : hz.Pages.end();
          if (first || was[n] || this->MorphFrames <= 0 || morphing >= MaxMorphingPages ||
              p == hz.Pages.end())
            continue;
          const PageRef from = this->RefOf(h, parent, p->second);
          const auto& node = tree.GetNode(n);
          const int l = node.Level;
          held.From.resize(count);
          for (int qy = 0; qy < B; ++qy)
            for (int qx = 0; qx < B; ++qx)
            {
              const int i = std::min((node.Index[0] * this->S + qx) << l, this->NX - 1);
              const int j = std::min((node.Index[1] * this->S + qy) << l, this->NY - 1);
              held.From[static_cast<size_t>(qy) * B + qx] = this->PageHeight(from, i, j);
            }
          held.MorphStep = 0;
          held.Display = held.From;
          held.LeafMin
            .clear(); // from now on the leaves bound both its parent's and its own heights
          this->MorphEnded = true;
        }
        else if (++held.MorphStep >= this->MorphFrames)
        {
          held.Display.clear(); // done: its own heights from now on
          held.From.clear();
          held.LeafMin.clear();
          upload(h, n);
          changed = true;
          this->MorphEnded = true;
          continue;
        }
        const float t = static_cast<float>(held.MorphStep) / static_cast<float>(this->MorphFrames);
        for (size_t k = 0; k < count; ++k)
        {
          const float a = held.From[k],
                      b = this->IsHole(own[k]) ? std::numeric_limits<float>::quiet_NaN() : own[k];
          held.Display[k] = std::isnan(a) || std::isnan(b) ? b : Mix(a, b, t);
        }
        upload(h, n);
        changed = true;
        ++morphing;
      }
      was.swap(inCut);
    }
    this->Stats.MorphingTiles = morphing;
    return changed;
  }

  /**
   * Stitching: where tiles of different levels meet, the coarser one rules. Each border texel
   * of a cut page whose point a coarser page also holds (up to four tiles share a tile corner)
   * takes that page's value there (its level interpolated along its border), so the finer
   * page's border lies on the coarser one's border line: no crack, no T-junction, whichever
   * lookup a ray uses (a tile's own cells in the layer's search, any point's tile in
   * strataHeight), and one surface, that of the level-0 cells through the point values.
   * Pages are stitched coarsest first, so a border that meets a page which is itself
   * stitched to a coarser one follows that one too: exact for any number of levels. Pages
   * whose borders changed are re-uploaded border only (BorderUploads) and their leaf ranges
   * recomputed.
   */
  std::vector<HeightFieldPager::Upload> BorderUploads;

  void Stitch()
  {
    this->BorderUploads.clear();
    const int B = this->B;
    for (int h = 0; h < static_cast<int>(this->Horizons.size()); ++h)
    {
      Horizon& hz = this->Horizons[h];
      const strata::VolumeBrickTree& tree = this->Pools[hz.PoolIndex]->Tree;
      std::vector<std::pair<float, int>> order; // (shown level, node) of the cut pages held
      for (int n : this->Cut.GetCutNodes(h))
      {
        auto it = !this->Cut.IsEmpty(h, n) ? hz.Pages.find(n) : hz.Pages.end();
        if (it != hz.Pages.end())
          order.emplace_back(this->EffectiveLevel(tree.GetNode(n).Level, it->second), n);
      }
      std::sort(order.rbegin(), order.rend()); // coarsest first
      std::vector<float> border(4 * static_cast<size_t>(B)), borderLo(border.size()),
        borderHi(border.size());
      for (const auto& [e, n] : order)
      {
        Held& held = hz.Pages[n];
        const int l = tree.GetNode(n).Level;
        const auto& node = tree.GetNode(n);
        const float* values = reinterpret_cast<const float*>(held.Data->data()) + held.Offset;
        // Tiles just outside the page's region: a coarser one among them may own its border.
        const int t0[2] = { node.Index[0] << l, node.Index[1] << l };
        const int t1[2] = { std::min((node.Index[0] + 1) << l, this->Tiles[0]),
          std::min((node.Index[1] + 1) << l, this->Tiles[1]) };
        bool coarser = false;
        for (int ty = t0[1] - 1; ty <= t1[1] && !coarser; ++ty)
          for (int tx = t0[0] - 1; tx <= t1[0] && !coarser; ++tx)
          {
            const bool outside = tx < t0[0] || ty < t0[1] || tx >= t1[0] || ty >= t1[1];
            if (outside && tx >= 0 && ty >= 0 && tx < this->Tiles[0] && ty < this->Tiles[1])
              coarser = this->TilePage(h, tx, ty).Effective > e;
          }
        bool any = false;
        if (coarser)
        {
          const int base[2] = { node.Index[0] * this->S, node.Index[1] * this->S };
          for (int side = 0; side < 4; ++side)
            for (int t = 0; t < B; ++t)
            {
              const int qx = side == 0 ? 0 : side == 1 ? B - 1 : t;
              const int qy = side == 2 ? 0 : side == 3 ? B - 1 : t;
              const int i = (base[0] + qx) << l, j = (base[1] + qy) << l;
              float v =
                (held.Display.empty() ? values
                                      : held.Display.data())[static_cast<size_t>(qy) * B + qx];
              float vlo = v, vhi = v;
              if (!held.From.empty()) // its own texel blends: between its parent's and its own
              {
                const float own = values[static_cast<size_t>(qy) * B + qx],
                            from = held.From[static_cast<size_t>(qy) * B + qx];
                vlo = std::min(own, from);
                vhi = std::max(own, from);
              }
              if (i < this->NX && j < this->NY)
              {
                const PageRef owner = this->Owner(h, i, j);
                if (owner.Effective > e)
                {
                  v = this->PageHeight(owner, i, j);
                  vlo = vhi = v;
                  if (!owner.Page->From.empty())
                  {
                    // The owner blends: this texel moves between its parent's and its own there.
                    const float a = this->ArrayHeight(owner, owner.Page->From.data(), i, j);
                    const float b = this->ArrayHeight(owner, owner.Values, i, j);
                    vlo = std::min({ v, a, b });
                    vhi = std::max({ v, a, b });
                  }
                  any = true;
                }
              }
              border[static_cast<size_t>(side) * B + t] = v;
              borderLo[static_cast<size_t>(side) * B + t] = vlo;
              borderHi[static_cast<size_t>(side) * B + t] = vhi;
            }
        }
        if (!any)
        {
          if (!held.Border.empty())
          {
            held.Border.clear();
            held.BorderLo.clear();
            held.BorderHi.clear();
            held.LeafMin.clear();
            this->BorderUploads.push_back({ h, n, this->Cut.GetSlot(h, n) });
          }
          continue;
        }
        if (held.Border != border)
        {
          held.Border = border;
          this->BorderUploads.push_back({ h, n, this->Cut.GetSlot(h, n) });
        }
        if (held.BorderLo != borderLo || held.BorderHi != borderHi)
        {
          held.BorderLo = borderLo;
          held.BorderHi = borderHi;
          held.LeafMin.clear();
        }
      }
    }
  }

  std::vector<float> BuiltMin, BuiltMax; ///< leaf ranges the quadtree was last built from

  /// Rebuilds the quadtree from the leaf ranges; unless `force`, only when some leaf left the
  /// ranges it was built from. Returns whether it rebuilt.
  bool RebuildTree(bool force)
  {
    const int H = static_cast<int>(this->Horizons.size());
    const auto leaves = strata::MinMaxQuadtree::GetLeafCount(this->NX, this->NY, this->Leaf);
    const int R = this->S / this->Leaf;
    std::vector<float> lmin(static_cast<size_t>(leaves[0]) * leaves[1] * H, Inf);
    std::vector<float> lmax(lmin.size(), -Inf);
    for (int h = 0; h < H; ++h)
    {
      Horizon& hz = this->Horizons[h];
      for (int b = 0; b < leaves[1]; ++b)
      {
        for (int a = 0; a < leaves[0]; ++a)
        {
          int level = 0;
          const int node = this->NodeOfTile(
            h, std::min(a / R, this->Tiles[0] - 1), std::min(b / R, this->Tiles[1] - 1), level);
          auto it = node >= 0 ? hz.Pages.find(node) : hz.Pages.end();
          if (it == hz.Pages.end())
            continue; // empty or without a slot: a hole, nothing to bound
          Held& held = it->second;
          if (held.LeafMin.empty())
            this->ComputeLeaves(h, node, held);
          const auto& n = this->Pools[hz.PoolIndex]->Tree.GetNode(node);
          const int la = a - ((n.Index[0] << level) * R);
          const int lb = b - ((n.Index[1] << level) * R);
          const int na =
            std::min(((n.Index[0] + 1) << level) * R, leaves[0]) - ((n.Index[0] << level) * R);
          const size_t k = static_cast<size_t>(lb) * na + la;
          if (k < held.LeafMin.size())
          {
            const size_t out = (static_cast<size_t>(b) * leaves[0] + a) * H + h;
            lmin[out] = held.LeafMin[k];
            lmax[out] = held.LeafMax[k];
          }
        }
      }
    }
    // Only blends moved (no level changed, none started or ended): when every leaf still lies
    // inside the range the tree was built with, the tree still bounds the surface.
    if (!force && lmin.size() == this->BuiltMin.size())
    {
      bool inside = true;
      for (size_t q = 0; q < lmin.size() && inside; ++q)
        inside =
          !(lmin[q] <= lmax[q]) || (lmin[q] >= this->BuiltMin[q] && lmax[q] <= this->BuiltMax[q]);
      if (inside)
        return false;
    }
    this->Tree.BuildFromLeafRanges(this->NX, this->NY, H, this->Leaf, lmin, lmax);
    this->BuiltMin.swap(lmin);
    this->BuiltMax.swap(lmax);
    return true;
  }

  /// Opens tile pool `fileName` as the next pool, checks it against the first one's grid and
  /// builds its quadtree from the page table (nothing read). False with `error` set.
  bool AddPool(const std::string& fileName, std::string& error)
  {
    auto pool = std::make_unique<Pool>();
    pool->Name = fileName;
    pool->File = this->Paging.OpenPool(static_cast<int>(this->Pools.size()), fileName, error);
    if (!pool->File)
    {
      error = "cannot open \"" + fileName + "\": " + error;
      return false;
    }
    const auto& header = pool->File->GetHeader();
    if (header.PoolKind != strata::PagePoolFormat::Kind::TilePool)
    {
      error = "\"" + fileName + "\" is a brick pool, not a tile pool of horizons";
      return false;
    }
    if (this->Pools.empty())
    {
      this->Header = header;
    }
    else if (!this->SameGrid(header))
    {
      error = "\"" + fileName + "\" lies on another grid than \"" + this->Pools[0]->Name +
              "\" (dimensions, page size, spacing, origin or direction differ)";
      return false;
    }
    if (header.Dimensions[0] < 2 || header.Dimensions[1] < 2)
    {
      error = "\"" + fileName + "\" is a line of points; paging needs at least 2 x 2";
      return false;
    }
    if (!strata::PagedPools::BuildTree(*pool->File, pool->Tree))
    {
      error = "\"" + fileName + "\": its tiles do not form the expected quadtree";
      return false;
    }
    this->Pools.push_back(std::move(pool));
    return true;
  }

  /// Whether a pool lies on the first pool's grid (dimensions, page size, geometry).
  bool SameGrid(const strata::PagePoolFile::Header& header) const
  {
    const auto& h0 = this->Header;
    bool same = header.Dimensions[0] == h0.Dimensions[0] &&
                header.Dimensions[1] == h0.Dimensions[1] && header.PageSize == h0.PageSize;
    for (int a = 0; a < 3 && same; ++a)
      same =
        std::abs(header.Spacing[a] - h0.Spacing[a]) <= 1e-9 * std::abs(h0.Spacing[a]) &&
        std::abs(header.Origin[a] - h0.Origin[a]) <= 1e-6 * std::max(1.0, std::abs(h0.Spacing[a]));
    for (int a = 0; a < 9 && same; ++a)
      same = std::abs(header.Direction[a] - h0.Direction[a]) <= 1e-9;
    return same;
  }

  /// The stack's grid, tiles, no-data value, value range and whether it may have holes.
  void SetGeometry()
  {
    this->NX = this->Header.Dimensions[0];
    this->NY = this->Header.Dimensions[1];
    this->B = this->Header.PageSize;
    this->S = this->B - 1;
    const int* tiles = this->Pools[0]->Tree.GetLevelBricks(0);
    this->Tiles[0] = tiles[0];
    this->Tiles[1] = tiles[1];
    this->HasNoData = this->Header.HasNoDataValue;
    this->NoData = this->Header.NoDataValue;
    this->ValueRange[0] = 0.0;
    this->ValueRange[1] = -1.0;
    this->Holes = false;
    for (const auto& pool : this->Pools)
    {
      const auto& header = pool->File->GetHeader();
      if (header.ValueRange[0] <= header.ValueRange[1])
      {
        if (this->ValueRange[0] > this->ValueRange[1])
        {
          this->ValueRange[0] = header.ValueRange[0];
          this->ValueRange[1] = header.ValueRange[1];
        }
        this->ValueRange[0] = std::min(this->ValueRange[0], header.ValueRange[0]);
        this->ValueRange[1] = std::max(this->ValueRange[1], header.ValueRange[1]);
      }
      this->Holes = this->Holes || header.HasNoDataValue ||
                    header.Type == strata::PagePoolFormat::ScalarType::Float32;
      const auto& t = pool->Tree;
      for (int n = 0; n < t.GetNumberOfNodes() && !this->Holes; ++n)
        this->Holes = !(t.GetNode(n).Min <= t.GetNode(n).Max);
    }
  }

  /// Horizon h's quadtree in the cut, under the shared budget: visible where it has data,
  /// split by feedback requests (the pixels that asked below a tile) or, without feedback,
  /// its screen-space error; a tile is available once its page is in RAM.
  void AddToCut(int h)
  {
    const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    const strata::VolumeBrickTree* tree = &this->Pools[this->Horizons[h].PoolIndex]->Tree;
    const int v = this->Cut.AddVolume(tree, identity);
    this->Cut.SetVolumeOpacity(v, [](double lo, double hi) { return lo <= hi ? 1.0 : 0.0; });
    this->Cut.SetVolumePriority(v,
      [this, tree, h](int node, double screenSpaceError)
      {
        if (!this->UseFeedback)
          return screenSpaceError;
        // A tile of the cut splits for the requests alive now; a split one is held by its
        // claim (see Demand).
        const std::vector<double>& demand =
          this->Cut.IsInCut(h, node) ? this->SubtreeRequests[h] : this->Demand[h];
        int children[8];
        const int count = tree->GetChildren(node, children);
        double asked = 0.0;
        for (int c = 0; c < count; ++c)
          asked += demand[children[c]];
        return asked;
      });
    this->Cut.SetVolumeAvailability(v,
      [this, h](int node, double priority)
      {
        Horizon& hz = this->Horizons[h];
        if (hz.Pages.count(node))
          return true;
        const strata::VolumeBrickTree& t = this->Pools[hz.PoolIndex]->Tree;
        const auto& n = t.GetNode(node);
        strata::PageCache::Key key;
        key.Dataset = hz.PoolIndex;
        key.Level = n.Level;
        key.Page = node - t.GetLevelOffset(n.Level);
        strata::PageCache::Page page = this->Paging.Acquire(key, priority);
        if (!page)
          return false;
        Held held;
        held.Data = page;
        held.Offset = static_cast<size_t>(hz.Layer) * this->B * this->B;
        hz.Pages[node] = std::move(held);
        return true;
      });
  }

  /// Horizon h's root tile: the reader's coarsest level when given, else read here once.
  bool HoldRoot(int h, const HeightFieldPager::Source& src, std::string& error)
  {
    Horizon& hz = this->Horizons[h];
    Pool& pool = *this->Pools[hz.PoolIndex];
    const int root = pool.Tree.GetRootId();
    const int rootLevel = pool.Tree.GetNode(root).Level;
    const int* rootDims = pool.Tree.GetLevelDimensions(rootLevel);
    Held held;
    if (src.RootValues && src.RootDims[0] == rootDims[0] && src.RootDims[1] == rootDims[1])
    {
      const int dims[3] = { rootDims[0], rootDims[1], 1 };
      const int page[3] = { this->B, this->B, 1 };
      held.Data = strata::PagedPools::PadRoot(src.RootValues, dims, page);
      held.Offset = 0;
    }
    else
    {
      std::string why;
      held.Data = this->Paging.ReadRoot(hz.PoolIndex, rootLevel, 0, why);
      if (!held.Data)
      {
        error = "cannot read the root tile of \"" + pool.Name + "\": " + why;
        return false;
      }
      held.Offset = static_cast<size_t>(hz.Layer) * this->B * this->B;
    }
    hz.Pages[root] = std::move(held);
    return true;
  }

  void Close()
  {
    this->UseFeedback = false;
    this->Requests.clear();
    this->SubtreeRequests.clear();
    this->Demand.clear();
    this->Paging.Close();
    this->Pools.clear();
    this->Horizons.clear();
    this->OpenedSources.clear();
    this->Cut.RemoveAllVolumes();
    this->Atlas.Clear();
    this->InitializedSlots = -1;
    this->Table.clear();
    this->TilePages.clear();
    this->WasInCut.clear();
    this->BuiltMin.clear();
    this->BuiltMax.clear();
    this->TableLevels.clear();
    this->Open = false;
    this->Stats = HeightFieldPager::Statistics();
  }
};

HeightFieldPager::HeightFieldPager()
  : Internals(new vtkInternals)
{
}

HeightFieldPager::~HeightFieldPager() = default;

bool HeightFieldPager::Open(const std::vector<Source>& sources)
{
  vtkInternals& in = *this->Internals;
  std::vector<std::pair<std::string, int>> wanted;
  for (const auto& s : sources)
    wanted.emplace_back(s.FileName, s.Layer);
  if (in.Open && wanted == in.OpenedSources)
    return true;
  in.Close();
  in.Error.clear();
  auto fail = [&](const std::string& message)
  {
    in.Error = message;
    in.Close();
    return false;
  };
  if (sources.empty())
    return fail("no horizons");
  if (static_cast<int>(sources.size()) > 2047)
    return fail("too many horizons");
  std::map<std::string, int> poolOf;
  std::string error;
  for (size_t h = 0; h < sources.size(); ++h)
  {
    const Source& src = sources[h];
    auto found = poolOf.find(src.FileName);
    if (found == poolOf.end())
    {
      if (!in.AddPool(src.FileName, error))
        return fail(error);
      found = poolOf.emplace(src.FileName, static_cast<int>(in.Pools.size()) - 1).first;
    }
    const int layers = in.Pools[found->second]->File->GetHeader().Dimensions[2];
    if (src.Layer < 0 || src.Layer >= layers)
    {
      std::ostringstream msg;
      msg << "horizon " << h << ": layer " << src.Layer << " out of range [0, " << layers - 1
          << "] of \"" << src.FileName << "\"";
      return fail(msg.str());
    }
    vtkInternals::Horizon hz;
    hz.PoolIndex = found->second;
    hz.Layer = src.Layer;
    in.Horizons.push_back(std::move(hz));
  }
  in.SetGeometry();
  this->SetTileSize(in.TileSize);
  for (size_t h = 0; h < in.Horizons.size(); ++h)
  {
    in.AddToCut(static_cast<int>(h));
    if (!in.HoldRoot(static_cast<int>(h), sources[h], error))
      return fail(error);
  }
  in.OpenedSources = wanted;
  in.Open = true;
  return true;
}

bool HeightFieldPager::IsOpen() const
{
  return this->Internals->Open;
}

const std::string& HeightFieldPager::GetErrorMessage() const
{
  return this->Internals->Error;
}

int HeightFieldPager::GetNX() const
{
  return this->Internals->NX;
}

int HeightFieldPager::GetNY() const
{
  return this->Internals->NY;
}

int HeightFieldPager::GetNumberOfHorizons() const
{
  return static_cast<int>(this->Internals->Horizons.size());
}

int HeightFieldPager::GetPageSize() const
{
  return this->Internals->B;
}

const int* HeightFieldPager::GetTiles() const
{
  return this->Internals->Tiles;
}

void HeightFieldPager::GetSpacing(double spacing[3]) const
{
  std::copy_n(this->Internals->Header.Spacing, 3, spacing);
}

void HeightFieldPager::GetOrigin(double origin[3]) const
{
  std::copy_n(this->Internals->Header.Origin, 3, origin);
}

void HeightFieldPager::GetDirection(double direction[9]) const
{
  std::copy_n(this->Internals->Header.Direction, 9, direction);
}

void HeightFieldPager::GetValueRange(double range[2]) const
{
  range[0] = this->Internals->ValueRange[0];
  range[1] = this->Internals->ValueRange[1];
}

bool HeightFieldPager::MayHaveHoles() const
{
  return this->Internals->Holes;
}

void HeightFieldPager::SetAtlasSlots(int slots)
{
  this->Internals->AtlasSlots = std::max(1, slots);
}

int HeightFieldPager::GetAtlasSlots() const
{
  return this->Internals->AtlasSlots;
}

void HeightFieldPager::InvalidateAtlas()
{
  this->Internals->InitializedSlots = -1;
}

void HeightFieldPager::SetCacheBudgetMiB(double mib)
{
  this->Internals->Paging.SetCacheBudgetMiB(std::max(1.0, mib));
}

void HeightFieldPager::SetPagesPerFrame(int pages)
{
  this->Internals->PagesPerFrame = std::max(1, pages);
  this->Internals->Paging.SetPagesPerFrame(this->Internals->PagesPerFrame);
}

void HeightFieldPager::SetPrefetch(bool prefetch)
{
  this->Internals->Paging.SetPrefetch(prefetch);
}

void HeightFieldPager::SetMorphFrames(int frames)
{
  this->Internals->MorphFrames = std::max(0, frames);
}

void HeightFieldPager::SetTileSize(int tileSize)
{
  vtkInternals& in = *this->Internals;
  in.TileSize = std::max(1, tileSize);
  if (in.S > 0)
  {
    int leaf = std::min(in.TileSize, in.S);
    while (in.S % leaf != 0)
      --leaf;
    if (leaf != in.Leaf)
      in.TableLevels.clear(); // the quadtree must be rebuilt
    in.Leaf = leaf;
    for (auto& hz : in.Horizons)
      for (auto& page : hz.Pages)
        page.second.LeafMin.clear();
  }
}

int HeightFieldPager::GetLeafSize() const
{
  return this->Internals->Leaf;
}

bool HeightFieldPager::Update(const strata::VolumeCut::Camera& camera,
  const double gridToWorld[16],
  std::vector<Upload>& uploads)
{
  vtkInternals& in = *this->Internals;
  uploads.clear();
  if (!in.Open)
    return false;
  if (in.InitializedSlots != in.AtlasSlots)
  {
    in.Atlas.Initialize(1, 1, in.AtlasSlots, in.B);
    in.Cut.SetBudget(in.AtlasSlots);
    in.InitializedSlots = in.AtlasSlots;
    in.TableLevels.clear();
  }
  in.Paging.BeginFrame();
  // The pages the cut holds stay pinned in the cache: leave room there for the loads.
  in.Cut.SetPageBudget(in.Paging.PlanHeldPages(in.AtlasSlots, 4));

  // The tree's index space is (x, y, 0): place it at the middle of the value range, where
  // the screen-space error of a tile is best estimated without its heights.
  const double zMid =
    in.ValueRange[0] <= in.ValueRange[1] ? 0.5 * (in.ValueRange[0] + in.ValueRange[1]) : 0.0;
  double m[16];
  std::copy_n(gridToWorld, 16, m);
  for (int r = 0; r < 4; ++r)
    m[4 * r + 3] += gridToWorld[4 * r + 2] * zMid;
  for (int h = 0; h < static_cast<int>(in.Horizons.size()); ++h)
    in.Cut.SetVolumeMatrix(h, m);
  // The cut sees each tile as a flat rectangle at zMid; its heights span the value range
  // around it. Moving each frustum plane out by the half-span along its normal keeps every
  // tile whose heights can be in view (the Minkowski sum of rectangle and span).
  strata::VolumeCut::Camera cutCamera = camera;
  if (cutCamera.UseFrustum)
  {
    const double half =
      in.ValueRange[0] <= in.ValueRange[1] ? 0.5 * (in.ValueRange[1] - in.ValueRange[0]) : 0.0;
    const double span[3] = { gridToWorld[2] * half, gridToWorld[6] * half, gridToWorld[10] * half };
    for (int q = 0; q < 6; ++q)
    {
      double* pl = cutCamera.FrustumPlanes + 4 * q;
      pl[3] += std::abs(pl[0] * span[0] + pl[1] * span[1] + pl[2] * span[2]);
    }
  }
  in.Cut.SetMaxNewBricksPerUpdate(in.PagesPerFrame);
  const int entered = in.Cut.Update(cutCamera);

  // Keep the pages of the cut and of its ancestors (for collapses), release the rest.
  for (int h = 0; h < static_cast<int>(in.Horizons.size()); ++h)
  {
    vtkInternals::Horizon& hz = in.Horizons[h];
    strata::CutPages::Prune(hz.Pages, in.Cut, h, in.Pools[hz.PoolIndex]->Tree);
  }
  in.Paging.EndFrame();

  in.Atlas.BeginFrame();
  std::vector<strata::VolumeCut::Upload> cutUploads;
  in.Cut.AssignSlots(in.Atlas, cutUploads);
  for (const auto& u : cutUploads)
    uploads.push_back({ u.Volume, u.Node, u.Slot });

  std::vector<uint16_t> table, one;
  for (int h = 0; h < static_cast<int>(in.Horizons.size()); ++h)
  {
    in.Cut.BuildIndexTable(h, in.Atlas, one);
    table.insert(table.end(), one.begin(), one.end());
  }
  const bool tableChanged = table != in.Table;
  in.Table.swap(table);
  std::vector<uint16_t> levels(in.Table.size() / 4);
  for (size_t e = 0; e < levels.size(); ++e)
    levels[e] = in.Table[4 * e + 3];
  const bool treeChanged = levels != in.TableLevels;
  const bool morphed = in.Morph(uploads);
  // The pages behind the tiles change only with the cut's levels; their shown levels with blends.
  if (treeChanged || morphed || in.TilePages.empty())
    in.RefreshTilePages();
  in.BorderUploads.clear();
  bool rebuilt = false;
  if (treeChanged || morphed)
  {
    in.TableLevels.swap(levels);
    in.Stitch();
    rebuilt = in.RebuildTree(treeChanged || in.MorphEnded);
  }

  static_cast<strata::PagedPools::Statistics&>(in.Stats) = in.Paging.GetStatistics();
  in.Stats.Entered = entered;
  in.Stats.CutTiles = in.Cut.GetCost();
  in.Stats.FinestTiles = 0;
  for (int h = 0; h < static_cast<int>(in.Horizons.size()); ++h)
  {
    const strata::VolumeBrickTree& tree = in.Pools[in.Horizons[h].PoolIndex]->Tree;
    for (int n : in.Cut.GetCutNodes(h))
      if (tree.GetNode(n).Level == 0 && !in.Cut.IsEmpty(h, n))
        ++in.Stats.FinestTiles;
  }
  in.Stats.FeedbackPages = static_cast<int>(in.Requests.size());
  // With feedback, settled also means every pixel of the lattice was sampled since the view
  // last changed.
  const bool cycled = !in.UseFeedback || in.FeedbackFrame - in.CycleStart >= in.FeedbackCycle;
  in.Stats.Converged = entered == 0 && in.Stats.MissesThisFrame == 0 &&
                       in.Stats.PendingPages == 0 && cycled && in.Stats.MorphingTiles == 0;
  return tableChanged || treeChanged || rebuilt;
}

void HeightFieldPager::SetFeedback(const std::vector<uint32_t>& pages,
  const std::vector<uint32_t>& coverage,
  int cycleFrames,
  bool viewChanged)
{
  vtkInternals& in = *this->Internals;
  ++in.FeedbackFrame;
  in.FeedbackCycle = std::max(1, cycleFrames);
  if (viewChanged || !in.UseFeedback)
  {
    in.CycleStart = in.FeedbackFrame;
  }
  in.UseFeedback = true;
  for (size_t e = 0; e < pages.size() && e < coverage.size(); ++e)
    in.Requests[pages[e]] = { coverage[e], in.FeedbackFrame };
  // Requests older than a cycle were for pixels that have been sampled again since.
  for (auto it = in.Requests.begin(); it != in.Requests.end();)
    it = in.FeedbackFrame - it->second.second >= in.FeedbackCycle ? in.Requests.erase(it)
                                                                  : std::next(it);
  in.SumRequests();
  in.UpdateDemand(viewChanged);
}

void HeightFieldPager::ClearFeedback()
{
  vtkInternals& in = *this->Internals;
  if (!in.UseFeedback)
    return;
  in.UseFeedback = false;
  in.Requests.clear();
  in.SubtreeRequests.clear();
  in.Demand.clear();
}

const int* HeightFieldPager::GetLevelTiles(int level) const
{
  return this->Internals->Pools[0]->Tree.GetLevelBricks(level);
}

int HeightFieldPager::GetNumberOfLevels() const
{
  return this->Internals->Pools.empty() ? 0 : this->Internals->Pools[0]->Tree.GetNumberOfLevels();
}

void HeightFieldPager::GetUploadValues(const Upload& upload, std::vector<float>& values) const
{
  const vtkInternals& in = *this->Internals;
  const size_t count = static_cast<size_t>(in.B) * in.B;
  values.assign(count, std::numeric_limits<float>::quiet_NaN());
  if (upload.Horizon < 0 || upload.Horizon >= static_cast<int>(in.Horizons.size()))
    return;
  const auto& pages = in.Horizons[upload.Horizon].Pages;
  auto it = pages.find(upload.Node);
  if (it == pages.end())
    return; // cannot happen: the cut holds only tiles whose pages are held
  const float* src = reinterpret_cast<const float*>(it->second.Data->data()) + it->second.Offset;
  for (int qy = 0; qy < in.B; ++qy)
    for (int qx = 0; qx < in.B; ++qx)
      values[static_cast<size_t>(qy) * in.B + qx] = in.Texel(it->second, src, qx, qy);
}

const std::vector<HeightFieldPager::Upload>& HeightFieldPager::GetBorderUploads() const
{
  return this->Internals->BorderUploads;
}

void HeightFieldPager::GetBorderValues(const Upload& upload, std::vector<float>& values) const
{
  const vtkInternals& in = *this->Internals;
  const int B = in.B;
  values.assign(4 * static_cast<size_t>(B), std::numeric_limits<float>::quiet_NaN());
  if (upload.Horizon < 0 || upload.Horizon >= static_cast<int>(in.Horizons.size()))
    return;
  const auto& pages = in.Horizons[upload.Horizon].Pages;
  auto it = pages.find(upload.Node);
  if (it == pages.end())
    return;
  const float* src = reinterpret_cast<const float*>(it->second.Data->data()) + it->second.Offset;
  for (int t = 0; t < B; ++t)
  {
    values[t] = in.Texel(it->second, src, 0, t);
    values[B + t] = in.Texel(it->second, src, B - 1, t);
    values[2 * B + t] = in.Texel(it->second, src, t, 0);
    values[3 * B + t] = in.Texel(it->second, src, t, B - 1);
  }
}

const std::vector<uint16_t>& HeightFieldPager::GetPageTable() const
{
  return this->Internals->Table;
}

const strata::MinMaxQuadtree& HeightFieldPager::GetTree() const
{
  return this->Internals->Tree;
}

std::vector<std::string> HeightFieldPager::TakeNewFailures()
{
  vtkInternals& in = *this->Internals;
  std::vector<std::string> messages;
  for (const auto& f : in.Paging.TakeNewFailures())
  {
    std::ostringstream msg;
    const std::string name =
      f.PageKey.Dataset >= 0 && f.PageKey.Dataset < static_cast<int>(in.Pools.size())
        ? in.Pools[f.PageKey.Dataset]->Name
        : std::string("?");
    msg << "tile " << f.PageKey.Page << " of level " << f.PageKey.Level << " of \"" << name
        << "\": " << f.Error;
    messages.push_back(msg.str());
  }
  in.Stats.Failures = in.Paging.GetStatistics().Failures;
  return messages;
}

void HeightFieldPager::RetryFailedPages()
{
  this->Internals->Paging.RetryFailedPages();
}

std::string HeightFieldPager::TakeBudgetWarning()
{
  return this->Internals->Paging.TakeBudgetWarning();
}

HeightFieldPager::Statistics HeightFieldPager::GetStatistics() const
{
  return this->Internals->Stats;
}

bool HeightFieldPager::WaitForIdle(double seconds)
{
  return this->Internals->Paging.WaitForIdle(seconds);
}

float HeightFieldPager::GetTileHeight(int horizon, int tileX, int tileY, int i, int j) const
{
  const vtkInternals& in = *this->Internals;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  if (!in.Open || horizon < 0 || horizon >= static_cast<int>(in.Horizons.size()) ||
      in.Table.empty() || tileX < 0 || tileY < 0 || tileX >= in.Tiles[0] || tileY >= in.Tiles[1] ||
      i < tileX * in.S || j < tileY * in.S || i > std::min((tileX + 1) * in.S, in.NX - 1) ||
      j > std::min((tileY + 1) * in.S, in.NY - 1))
    return nan;
  const vtkInternals::PageRef page = in.TilePage(horizon, tileX, tileY);
  const float h = page.Level < 0 ? nan : in.PageHeight(page, i, j);
  return std::abs(h) >= 1e30f ? nan : h;
}

float HeightFieldPager::GetHeight(int horizon, int i, int j) const
{
  const vtkInternals& in = *this->Internals;
  if (!in.Open || horizon < 0 || horizon >= static_cast<int>(in.Horizons.size()) ||
      in.Table.empty())
    return std::numeric_limits<float>::quiet_NaN();
  i = std::min(std::max(i, 0), in.NX - 1);
  j = std::min(std::max(j, 0), in.NY - 1);
  const float h = in.Height(horizon, i, j);
  return std::abs(h) >= 1e30f ? std::numeric_limits<float>::quiet_NaN() : h;
}
}
