// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::HeightFieldPager
 * @brief   Pages a stack of horizons from tile pools: cut, RAM cache, atlas slots, leaf ranges.
 *
 * The out-of-core half of the stacked height-field ray caster (Lux and Froehlich, stacked
 * height-field ray casting 3.1-3.3), without any OpenGL: the mapper asks it each frame what to
 * upload and gets back the page table and the min-max quadtree that describe exactly the data
 * on the GPU.
 *
 * - Each horizon is one layer of a tile pool (strata::PagePoolFormat TilePool); all share one grid
 *   (dimensions, page size, geometry). A pool with several layers is read once per page and
 *   shared by its horizons (one cache key per pool page).
 * - Pools, the RAM cache, page requests and roots are strata::PagedPools, as for volumes
 *   (strata::VolumePager).
 * - The cut is a strata::VolumeCut over each horizon's tile quadtree (a brick tree one point
 * thick), all horizons under one atlas budget, refined greedily by screen-space error; a tile
 * enters the cut only once its page is in RAM (strata::PageCache, worker threads), so the render
 * thread never reads a file. Roots are the pages a frame can always show: they come with Open()
 *   (the reader's coarsest level, already read by the pipeline) or are read there once.
 * - The page table has one entry per level-0 tile and horizon: (slot x, slot y, slot z,
 *   level) as strata::VolumeCut::BuildIndexTable writes it. The shader maps level-0 grid point p to
 *   the resident tile of level l covering it and interpolates that level bilinearly at
 *   p / 2^l; the layer's search walks each tile in cells of its own level.
 * - Stitching: where tiles of different levels meet the coarser one rules. A page's border
 *   texels that a coarser page also holds take that page's value there (its level interpolated
 *   along its border; coarsest pages first, so chains of levels follow too), in the atlas and in
 *   GetHeight alike. A finer tile's border then lies on its coarser neighbour's border line, so
 *   any cut is one surface without cracks or T-junctions, whichever way a ray looks it up, and
 *   converged (all level 0) it is the data itself. Borders that change with the cut are
 *   re-uploaded alone (GetBorderUploads).
 * - Blending (SetMorphFrames): a tile that enters by a split shows its parent's surface first and
 *   its own n frames later, so refinements do not pop either; while it blends it counts as a
 *   level between the two for stitching.
 * - The min-max quadtree (strata::MinMaxQuadtree) is rebuilt from leaf ranges whenever the cut
 *   changes: a leaf's range is that of the page points its cells interpolate under the cut,
 *   computed once per resident page from its data. At level 0 that is exactly the in-core
 *   tree's range, so a converged paged rendering equals the in-core one. Leaves never straddle
 *   pages: the leaf size is the largest divisor of the page stride B - 1 not above the
 *   requested tile size.
 *
 * @sa vtkStackedHeightFieldMapper strata::VolumeCut strata::PageCache strata::MinMaxQuadtree
 */
#ifndef StrataHeightFieldPager_h
#define StrataHeightFieldPager_h

#include "StrataCoreModule.h" // For export macro
#include "StrataPagedPools.h" // For strata::PagedPools::Statistics
#include "StrataVolumeCut.h"  // For strata::VolumeCut::Camera

#include <cstdint> // For uint16_t, uint32_t
#include <memory>  // For std::unique_ptr
#include <string>  // For std::string
#include <vector>  // For std::vector

namespace strata
{
class MinMaxQuadtree;
}

namespace strata
{
class STRATACORE_EXPORT HeightFieldPager
{
public:
  /// One horizon: a layer of a tile pool and, optionally, its coarsest level already read.
  struct Source
  {
    std::string FileName;
    int Layer = 0;
    /// Values of the pool's coarsest level (RootDims points, x fastest); null: read it here.
    const float* RootValues = nullptr;
    int RootDims[2] = { 0, 0 };
  };

  /// A page that entered the atlas this frame.
  struct Upload
  {
    int Horizon;
    int Node;
    int Slot;
  };

  /// strata::PagedPools' counts (pending, misses, bytes read and cached, roots read, failures,
  /// since Open()) and the cut's.
  struct Statistics : strata::PagedPools::Statistics
  {
    bool Converged = false; ///< cut settled, nothing missing, pending or blending
    int CutTiles = 0;       ///< resident cut tiles over all horizons
    int FinestTiles = 0;    ///< of which level 0
    int Entered = 0;        ///< tiles that entered the cut this frame
    int FeedbackPages = 0;  ///< distinct tiles the feedback asked for (last cycle)
    int MorphingTiles = 0;  ///< tiles still blending from their parent's surface

    template<typename Visit>
    void ForEachField(Visit&& visit) const
    {
      strata::PagedPools::Statistics::ForEachField(visit);
      visit("Converged", this->Converged);
      visit("CutTiles", this->CutTiles);
      visit("FinestTiles", this->FinestTiles);
      visit("Entered", this->Entered);
      visit("FeedbackPages", this->FeedbackPages);
      visit("MorphingTiles", this->MorphingTiles);
    }
  };

  HeightFieldPager();
  ~HeightFieldPager();
  HeightFieldPager(const HeightFieldPager&) = delete;
  HeightFieldPager& operator=(const HeightFieldPager&) = delete;

  /**
   * Opens the pools of all horizons and checks that they form one stack (tile pools, same
   * grid, page size and geometry, layer in range, at least 2 x 2 points). Returns false with
   * GetErrorMessage() saying why; the pager is then empty. Re-opening the same sources keeps
   * the cache.
   */
  bool Open(const std::vector<Source>& sources);
  bool IsOpen() const;
  const std::string& GetErrorMessage() const;

  ///@{
  /// Geometry of the stack (valid after Open()).
  int GetNX() const;
  int GetNY() const;
  int GetNumberOfHorizons() const;
  int GetPageSize() const;
  /// Level-0 tiles per axis: the page table's size.
  const int* GetTiles() const;
  void GetSpacing(double spacing[3]) const;
  void GetOrigin(double origin[3]) const;
  void GetDirection(double direction[9]) const;
  /// Union of the pools' level-0 value ranges: every level lies inside it.
  void GetValueRange(double range[2]) const;
  /// Whether a sample can be a hole (float pools, no-data values, empty tiles).
  bool MayHaveHoles() const;
  ///@}

  ///@{
  /// Budgets. The atlas is counted in slots of B x B floats; cache in MiB; uploads per frame.
  void SetAtlasSlots(int slots);
  int GetAtlasSlots() const;
  void SetCacheBudgetMiB(double mib);
  void SetPagesPerFrame(int pages);
  /// After a tile loaded on demand, queue its four neighbours and its parent below every demand
  /// request (default off; see vtkStackedHeightFieldMapper::SetPrefetch).
  void SetPrefetch(bool prefetch);
  /**
   * Frames over which a tile that entered the cut by a split blends from its parent's surface
   * (as it was shown) to its own: frame k of n shows parent + (own - parent) k / n, so a
   * refinement never pops (default 0: at once). At most 64 tiles blend at a time (the others
   * appear at once); each is uploaded again every frame it blends. The page table, GetHeight
   * and the quadtree follow the blended heights, and the cut is not converged while any blends.
   */
  void SetMorphFrames(int frames);
  /// Forgets what the atlas holds (its texture was lost): the next Update() uploads all again.
  void InvalidateAtlas();
  /// Requested quadtree leaf size; the effective one divides B - 1 (see GetLeafSize()).
  void SetTileSize(int tileSize);
  int GetLeafSize() const;
  ///@}

  /**
   * One frame: refines the cut for `camera` (gridToWorld[h] maps horizon h's grid space,
   * x and y in points and z the height, to world, row-major), assigns atlas slots and fills
   * `uploads` with the pages the caller must upload before drawing. Returns true when the page
   * table or the quadtree changed (upload them again).
   */
  bool Update(const strata::VolumeCut::Camera& camera,
    const double gridToWorld[16],
    std::vector<Upload>& uploads);

  /**
   * Level-of-detail feedback of the last frame: (page, coverage) entries as
   * strata::FeedbackReduction makes them (data set = horizon, level, tile index in the level),
   * the tile each sampled ray hit at the level its footprint wants. A ray samples one pixel
   * of each cycleFrames-pixel lattice cell per frame, so requests are kept for that many
   * frames. Once feedback arrives the cut splits only tiles with requested tiles below them
   * (priority: the pixels asking), so hidden and out-of-view parts stay coarse; without it
   * the screen-space error of every tile rules. `viewChanged` restarts the cycle.
   */
  void SetFeedback(const std::vector<uint32_t>& pages,
    const std::vector<uint32_t>& coverage,
    int cycleFrames,
    bool viewChanged);
  /// Back to screen-space error priorities (feedback off).
  void ClearFeedback();
  /// Tiles per axis of level l (what the shader needs to number the tiles it asks for).
  const int* GetLevelTiles(int level) const;
  int GetNumberOfLevels() const;

  /// B x B heights of an upload as the atlas holds them (stitched borders), no-data as NaN.
  void GetUploadValues(const Upload& upload, std::vector<float>& values) const;
  /**
   * Pages already in the atlas whose border texels changed in the last Update() (stitching,
   * see the class documentation): upload GetBorderValues of each into its slot's border.
   */
  const std::vector<Upload>& GetBorderUploads() const;
  /// 4 B border heights of a page: the x = 0 column, the x = B - 1 column, the y = 0 row and
  /// the y = B - 1 row, as the atlas holds them, no-data as NaN.
  void GetBorderValues(const Upload& upload, std::vector<float>& values) const;

  /// Page table after Update(): tilesX x tilesY x horizons entries of 4 uint16 (see above).
  const std::vector<uint16_t>& GetPageTable() const;
  /// Quadtree over the current cut after Update().
  const strata::MinMaxQuadtree& GetTree() const;

  /// Load failures since the last call, as messages naming the pool and page.
  std::vector<std::string> TakeNewFailures();
  /// Forgets failed loads so that they are tried again.
  void RetryFailedPages();
  /// Once per change: how inconsistent budgets were clamped (strata::PagedPools::PlanHeldPages).
  std::string TakeBudgetWarning();
  Statistics GetStatistics() const;
  /// Waits (tests, benchmarks) until the cache has no queued or running load.
  bool WaitForIdle(double seconds);

  /**
   * CPU reference of the shader's lookup: the height of horizon h at level-0 point (i, j)
   * under the current cut; NaN for a hole.
   */
  float GetHeight(int horizon, int i, int j) const;
  /**
   * The height that the page covering level-0 tile (tileX, tileY) gives at level-0 point
   * (i, j) of the tile's closed region (its border points included), as the layer's search
   * reads it; NaN for a hole. Where tiles meet both sides must agree: tests check the seams.
   */
  float GetTileHeight(int horizon, int tileX, int tileY, int i, int j) const;

private:
  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};
}

#endif
