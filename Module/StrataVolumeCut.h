// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::VolumeCut
 * @brief   Cuts through the brick octrees of all volumes under one shared atlas budget.
 *
 * The working set of Lux and Froehlich (multi-volume multi-resolution ray casting, sections
 * 3.1-3.3, Fig. 2). Each volume's cut is a set of octree nodes that covers its domain exactly
 * once; together the cuts of all volumes must fit the atlas (the budget, in bricks). A greedy
 * split/collapse keeps them there: the split priority of a node is its screen-space error,
 * the size in pixels of one of its voxels seen from the camera (optionally times its highest
 * opacity under the transfer function). Splitting the highest-priority node continues while
 * the budget allows; when a split does not fit, collapsing parents of lower priority pays for
 * it. Because one priority orders the nodes of every volume, a near, large volume takes atlas
 * space from a far, small one, as in the paper's Fig. 2.
 *
 * Bricks that are empty - the highest opacity over the value range of the node and all its
 * descendants is 0 - are neither split nor resident: the cut keeps them as empty nodes that
 * cost no slot, and the ray caster skips them.
 *
 * Update() is incremental (the paper's frame-to-frame refinement): it starts from the last
 * cut and can bound the bricks entering the cut per call (the upload budget), so a moving
 * camera converges over a few frames instead of stalling one.
 *
 * The index table of a volume has one entry per level-0 brick (the finest virtual grid): the
 * atlas slot and level of the cut node covering it. One fetch maps a sample to its brick;
 * MapToAtlas() is the CPU reference of that lookup, for tests and for the shader's author.
 *
 * Plain C++: the mapper feeds it trees, matrices, transfer functions and a camera, and turns
 * the uploads and index tables into textures.
 *
 * @sa strata::VolumeBrickTree strata::BrickAtlasAllocator
 */
#ifndef StrataVolumeCut_h
#define StrataVolumeCut_h

#include "StrataCoreModule.h" // For export macro
#include "StrataRegion.h"     // For strata::Region

#include <cstdint>    // For uint16_t
#include <functional> // For std::function
#include <memory>     // For std::unique_ptr
#include <vector>     // For std::vector

namespace strata
{
class BrickAtlasAllocator;
}
namespace strata
{
class VolumeBrickTree;
}

namespace strata
{
class STRATACORE_EXPORT VolumeCut
{
public:
  /**
   * Highest opacity the transfer function reaches for values in [lo, hi]. It may
   * overestimate (a brick is then kept) but must not underestimate (it would vanish).
   */
  using OpacityRangeFunction = std::function<double(double lo, double hi)>;

  struct Camera
  {
    double Position[3] = { 0.0, 0.0, 0.0 }; ///< eye in world coordinates (perspective)
    /// Perspective scale: viewport height / (2 tan(view angle / 2)), see PixelsPerRadian().
    double PixelsPerRadian = 1000.0;
    /// Parallel projection when > 0: pixels per world unit; Position is then unused.
    double PixelsPerUnit = 0.0;
    /// Nodes wholly outside any plane get priority 0 (never split). Planes as
    /// vtkCamera::GetFrustumPlanes writes them: a x + b y + c z + d >= 0 inside.
    bool UseFrustum = false;
    double FrustumPlanes[24] = {};
    /// A renderer that draws only one box of the scene (sort-last parallel rendering, one box
    /// per process): nodes whose world box misses Region grown by RegionMargin plus one voxel
    /// of the node's level count as empty, so they are neither split, stored nor paged; the
    /// caller's rays never sample there (the margin covers the step past the box's exit face
    /// and gradient taps).
    strata::Region Region;
    double RegionMargin = 0.0;
  };
  /// The perspective scale of a viewport `heightPixels` tall with a vertical view angle.
  static double PixelsPerRadian(int heightPixels, double viewAngleDegrees);

  /// A brick that entered the atlas and must be uploaded: tree node `Node` into slot `Slot`.
  struct Upload
  {
    int Volume;
    int Node;
    int Slot;
  };

  ///@{
  /// Level codes of index-table entries that point at no brick.
  static constexpr uint16_t EmptyLevel = 0xFFFF;   ///< skipped: transparent everywhere
  static constexpr uint16_t MissingLevel = 0xFFFE; ///< in the cut but without a slot
  ///@}

  VolumeCut();
  ~VolumeCut();
  VolumeCut(const VolumeCut&) = delete;
  VolumeCut& operator=(const VolumeCut&) = delete;

  ///@{
  /**
   * Volumes are numbered 0, 1, ... in the order added; the number is also their atlas key.
   * The tree is borrowed. indexToWorld maps level-0 index coordinates to world, a row-major
   * affine 4x4 (vtkImageData's index-to-physical matrix). A new volume's cut is its root.
   */
  int AddVolume(const strata::VolumeBrickTree* tree, const double indexToWorld[16]);
  void SetVolumeMatrix(int volume, const double indexToWorld[16]);
  /// Transfer function of a volume; an empty function makes every brick visible (default).
  void SetVolumeOpacity(int volume, OpacityRangeFunction maxOpacity);
  /**
   * A halo of one brick around the visible ones (default off): a node is then empty only
   * when it and every node of its level that shares a face, an edge or a corner with it are
   * transparent. Pre-integration classifies a segment by the scalars at both its ends, and an
   * empty brick has no data: an end in it reads a stand-in value, and the segment's linear
   * ramp from a visible scalar to that value crosses transfer-function values the data never
   * takes (a mid-range transfer function put the whole visible band between a dense brick's
   * values and a stand-in below them, issue 14). With the halo every brick within one brick of
   * visible data is stored, so a segment shorter than a brick that touches visible data reads
   * true scalars at both ends, and one that touches none has both ends at the same stand-in
   * (transparent). Any level: a node's neighbours contain its children's.
   */
  void SetVolumeHalo(int volume, bool halo);
  /**
   * Whether a node's data can be uploaded now, asked (with the node's priority) for the
   * visible children of a node before it is split; a split waits until all are available. A
   * paging renderer answers from its RAM cache and queues the missing ones at that priority,
   * so the cut refines as pages arrive and never shows a brick it has no data for. Empty
   * function (default): everything is available.
   */
  using AvailabilityFunction = std::function<bool(int node, double priority)>;
  void SetVolumeAvailability(int volume, AvailabilityFunction available);
  /**
   * Replaces the screen-space error as the volume's split priority. A renderer with
   * level-of-detail feedback ranks a node by the pixels whose rays asked for detail below it,
   * so bricks no ray reaches (hidden behind opaque material, outside the view) get priority 0
   * and are never split, while one priority scale still orders the nodes of all volumes for
   * the shared budget. `priority(node, screenSpaceError)` is asked once per node and Update();
   * opacity weighting and the error threshold apply to its result. Empty function (default):
   * the screen-space error.
   */
  using PriorityFunction = std::function<double(int node, double screenSpaceError)>;
  void SetVolumePriority(int volume, PriorityFunction priority);
  void RemoveAllVolumes();
  int GetNumberOfVolumes() const;
  const strata::VolumeBrickTree* GetTree(int volume) const;
  ///@}

  ///@{
  /**
   * Resident bricks allowed over all volumes: the atlas slot count. Default 0; roots are
   * always kept, so a budget below the number of visible roots leaves IsOverBudget() true.
   */
  void SetBudget(int bricks) { this->Budget = bricks; }
  int GetBudget() const { return this->Budget; }
  ///@}

  ///@{
  /**
   * Pages a paging renderer may hold for the cut (default 0: no bound): the resident cut
   * nodes and their ancestors, in the volumes with an availability function. A pager keeps
   * those pages pinned in its RAM cache (strata::CutPages), so they must fit there beside the pages
   * being loaded, or every new load is dropped for want of room and the cut never refines
   * (strata::PagedPools::PlanHeldPages). Splits and collapses keep GetHeldPages() within it as they
   * keep GetCost() within the budget.
   */
  void SetPageBudget(int pages) { this->PageBudget = pages; }
  int GetPageBudget() const { return this->PageBudget; }
  ///@}

  ///@{
  /**
   * Nodes whose priority is at most this many pixels are not split. Default 0: spare atlas
   * space is used for detail, which costs uploads but no ray-casting time; about 1 saves
   * uploads of detail smaller than a pixel.
   */
  void SetErrorThreshold(double pixels) { this->ErrorThreshold = pixels; }
  double GetErrorThreshold() const { return this->ErrorThreshold; }
  ///@}

  ///@{
  /**
   * Multiply the screen-space error by the node's highest opacity, so nearly transparent
   * regions get less detail. Default false: priorities stay in pixels.
   */
  void SetOpacityWeighting(bool on) { this->OpacityWeighting = on; }
  bool GetOpacityWeighting() const { return this->OpacityWeighting; }
  ///@}

  ///@{
  /**
   * Most bricks one Update() may bring into the cut (each split brings its visible
   * children, each collapse the parent), bounding uploads per frame; the first split of an
   * Update is always allowed, so a bound below 8 still refines. Default 0: no bound.
   */
  void SetMaxNewBricksPerUpdate(int bricks) { this->MaxNewBricksPerUpdate = bricks; }
  int GetMaxNewBricksPerUpdate() const { return this->MaxNewBricksPerUpdate; }
  ///@}

  /// Puts every cut back to its root.
  void Reset();

  /**
   * Reclassifies empty nodes, recomputes priorities for `camera` and refines the cuts:
   * collapse while over budget, then split by priority (collapsing lower-priority parents to
   * make room). Returns the number of bricks that entered the cuts; 0 means converged.
   */
  int Update(const Camera& camera);

  ///@{
  /// The cut as of the last Update().
  bool IsInCut(int volume, int node) const;
  /// Classified empty by the last Update() (the node and its subtree are transparent).
  bool IsEmpty(int volume, int node) const;
  /// Node ids of the volume's cut, increasing (so finest level first).
  std::vector<int> GetCutNodes(int volume) const;
  /// Resident (non-empty) cut nodes over all volumes, or of one volume.
  int GetCost() const;
  int GetVolumeCost(int volume) const;
  bool IsOverBudget() const { return this->GetCost() > this->Budget; }
  /// Resident cut nodes and their ancestors in the paged volumes (see SetPageBudget()).
  int GetHeldPages() const;
  /// Priority of a node at the last Update(): error in pixels (times opacity if weighted).
  double GetPriority(int volume, int node) const;
  ///@}

  /// Size in pixels of one voxel of the node, seen from the camera; 0 outside the frustum.
  double ComputeScreenSpaceError(int volume, int node, const Camera& camera) const;

  /**
   * Requests a slot for every resident cut node (call atlas.BeginFrame() first). Bricks
   * already in the atlas are requested first so that no miss evicts one the cut still needs.
   * Fills `uploads` with the misses, which the caller must upload before rendering, and
   * returns the number of nodes that got no slot (0 when the budget fits the atlas).
   */
  int AssignSlots(strata::BrickAtlasAllocator& atlas, std::vector<Upload>& uploads);
  /// Slot of a cut node after AssignSlots(), -1 when none.
  int GetSlot(int volume, int node) const;

  /**
   * The volume's index table: one entry of 4 uint16 per level-0 brick, x fastest, over the
   * tree's GetLevelBricks(0): (slot x, slot y, slot z, level) of the cut node covering it,
   * slot coordinates in atlas slots (texel origin = slot * brick size). Level is
   * EmptyLevel for skipped bricks and MissingLevel for cut nodes without a slot. Returns the
   * number of MissingLevel entries. Upload as an RGBA16UI 3-D texture.
   */
  int BuildIndexTable(int volume,
    const strata::BrickAtlasAllocator& atlas,
    std::vector<uint16_t>& table) const;

  /**
   * CPU reference of the shader lookup. `index` is a position in level-0 index coordinates;
   * table and tableDims are BuildIndexTable's table and the tree's GetLevelBricks(0). On
   * success writes the position in atlas texels (texel t has its centre at t + 0.5, so
   * divide by the atlas texture size for normalised coordinates) and the level, and returns
   * true; returns false for an empty or missing brick. With S = B - 1, per axis:
   *   x = clamp(index, 0, tableDims S)   keeps linear filtering inside the slot
   *   b = min(floor(x / S), tableDims - 1)   the level-0 brick
   *   (slot, l) = table[b]
   *   atlas = slot B + x / 2^l - (b >> l) S + 0.5
   * Exact because brick (l, I) spans level-0 index [I S 2^l, (I+1) S 2^l], so x / 2^l - I S
   * lies in [0, S], inside the brick's B texels.
   */
  static bool MapToAtlas(const uint16_t* table,
    const int tableDims[3],
    int brickSize,
    const double index[3],
    double atlasTexel[3],
    int& level);

  /**
   * Exact highest value over [lo, hi] of a piecewise-linear function given as `count`
   * (x, y) pairs with increasing x, constant beyond its ends (vtkPiecewiseFunction with
   * clamping on): a ready OpacityRangeFunction body.
   */
  static double MaxOfPiecewiseLinear(const double* xy, int count, double lo, double hi);

private:
  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
  int Budget = 0;
  int PageBudget = 0;
  double ErrorThreshold = 0.0;
  bool OpacityWeighting = false;
  int MaxNewBricksPerUpdate = 0;
};
}

#endif
