// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::VolumePager
 * @brief   The cut, atlas slots and paging of every volume of a multi-volume scene, without
 *          OpenGL: what vtkMultiVolumeRayCastMapper uploads each frame and why.
 *
 * The working set of Lux and Froehlich (multi-volume multi-resolution ray casting, 3.1-3.3)
 * for in-core and paged volumes alike, beside strata::HeightFieldPager and on the same shared piece
 * (strata::PagedPools: pools, RAM cache, requests, roots, failures):
 * - One strata::VolumeCut through the brick trees of all volumes under one atlas budget
 *   (strata::BrickAtlasAllocator slots of B^3 texels of the atlas's type, strata::BrickAtlasFormat,
 * never more than all bricks of all levels). An in-core volume brings its own tree (with data); a
 * paged one (OpenPool) is a brick pool whose tree structure comes from the page table, nothing
 * read.
 * - A paged brick may enter the cut only with its page in RAM: found (and held, with its
 *   ancestors, until the cut no longer needs it; strata::CutPages) or requested at its priority
 *   for a later frame, at most PagesPerFrame new bricks a frame. Roots are always there: the
 *   reader's coarsest level, or read here once.
 * - Level-of-detail feedback: the pages the rays asked for (strata::FeedbackReduction entries,
 *   volume = the volume's number in the frame) raise the split priority of every ancestor to
 *   the pixels that asked below it; the priority is kept while the view is still and halves
 *   for each frame it moves (PrepareDemand).
 * - Fixed cuts (SetFixedCut) split exactly the ancestors of given bricks, so the in-core
 *   rendering of any paged frame's cut can be drawn.
 * - Time series: each step of a paged port is its own pool (cache data set
 *   GetPoolId(port, step)). OpenPool with another step of the same structure (level
 *   dimensions and page size) keeps the cut: the next Update swaps every held page for the
 *   new step's page of the same brick, found in the cache or, when it did not arrive, read on
 *   the render thread (StepPagesRead; that frame counts in IoWaitFrames), and uploads every
 *   brick again. SetNextStep names the step playback goes to next: each Update then
 *   prefetches that step's pages of the bricks it holds (the cut and its ancestors), below
 *   every demand request, so that the switch finds them in RAM. The cache must hold two cuts
 *   for that (the held one and the prefetched one). A port keeps the pools of the steps it
 *   visited open (one file each) until the cut is rebuilt for another structure.
 *
 * The caller (the mapper) turns the uploads into atlas texture writes (GetBrick) and the index
 * tables (BuildIndexTable) into index textures; the shader lookup is the atlas's.
 *
 * @sa strata::VolumeCut strata::PagedPools strata::HeightFieldPager vtkMultiVolumeRayCastMapper
 */
#ifndef StrataVolumePager_h
#define StrataVolumePager_h

#include "StrataBrickAtlasFormat.h"  // For strata::BrickAtlasFormat::Storage
#include "StrataCoreModule.h"        // For export macro
#include "StrataFeedbackReduction.h" // For strata::FeedbackReduction::Entry
#include "StrataPagedPools.h"        // For strata::PagedPools::Statistics
#include "StrataVolumeBrickTree.h"   // For strata::VolumeBrickTree::ScalarType
#include "StrataVolumeCut.h"         // For strata::VolumeCut::Camera, Upload

#include <array>      // For std::array
#include <functional> // For std::function
#include <memory>     // For std::unique_ptr
#include <string>     // For std::string
#include <vector>     // For std::vector

namespace strata
{
class BrickAtlasAllocator;
}
namespace strata
{
class PagePoolFile;
}

namespace strata
{
class STRATACORE_EXPORT VolumePager
{
public:
  /// One volume of a frame; its place in the list is its number in the cut, atlas and ids.
  struct Volume
  {
    /// The caller's id (its input port, or a component's channel, GetChannel); a paged
    /// volume's pool is kept by it.
    int Port = 0;
    /// In core: the caller's tree, with data. Paged (an open pool on Port): null.
    const strata::VolumeBrickTree* Tree = nullptr;
    double IndexToWorld[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    strata::VolumeCut::OpacityRangeFunction Opacity; ///< highest opacity over a value range
    /// Store the bricks next to visible ones too (pre-integration,
    /// strata::VolumeCut::SetVolumeHalo).
    bool Halo = false;
    /**
     * Paged: the reader's coarsest level as floats (x fastest) and its dimensions, asked for
     * only while the root page is not held; empty (or no function): read the root here.
     */
    std::function<std::vector<float>(int dims[3])> RootValues;
  };

  struct Statistics : strata::PagedPools::Statistics
  {
    /// The last cut did not change, nothing is pending, and (with feedback) the feedback it
    /// used was rendered from the same view and cut.
    bool Converged = false;
    int RootPagesFromPipeline = 0; ///< roots taken from the readers' coarsest levels
    int FeedbackPages = 0;         ///< distinct pages in the last feedback reduced
    int FeedbackPixels = 0;        ///< its pixels that asked for a page
    int StepSwitches = 0;          ///< time-step switches kept the cut, in all
    /**
     * Frames the render thread waited on the disk, in all: it read a page itself (a root, or a
     * new step's page of a brick the last step's cut held that was not prefetched in time). A
     * switch never draws such a brick coarser instead: it waits, and counts here. Bricks the
     * new step's cut adds arrive like any refinement (MissesThisFrame).
     */
    int IoWaitFrames = 0;
    /// Of the pages the last frame held, how many of the next step's are in RAM now.
    int NextStepPagesResident = 0;
    int NextStepPagesWanted = 0; ///< and how many it held (0 without SetNextStep)

    template<typename Visit>
    void ForEachField(Visit&& visit) const
    {
      strata::PagedPools::Statistics::ForEachField(visit);
      visit("Converged", this->Converged);
      visit("RootPagesFromPipeline", this->RootPagesFromPipeline);
      visit("FeedbackPages", this->FeedbackPages);
      visit("FeedbackPixels", this->FeedbackPixels);
      visit("StepSwitches", this->StepSwitches);
      visit("IoWaitFrames", this->IoWaitFrames);
      visit("NextStepPagesResident", this->NextStepPagesResident);
      visit("NextStepPagesWanted", this->NextStepPagesWanted);
    }
  };

  /// Per-frame settings of the cut and the paging.
  struct Settings
  {
    double CacheBudgetMiB = 512.0;
    int PagesPerFrame = 64;
    bool Prefetch = false;
    bool Feedback = false;       ///< demand from feedback ranks the nodes
    double ErrorThreshold = 0.0; ///< pixels per voxel below which the cut does not split
  };

  VolumePager();
  ~VolumePager();
  VolumePager(const VolumePager&) = delete;
  VolumePager& operator=(const VolumePager&) = delete;

  /// Ports, components and time steps a pool id (a cache data set, 24 bits) can name.
  static constexpr int MaxPorts = 64;
  static constexpr int MaxComponents = 4;
  static constexpr int MaxChannels = MaxPorts * MaxComponents;
  static constexpr int MaxSteps = 1024;
  /**
   * The channel of component `component` of the volume on `port`: port + MaxPorts component.
   * Every method below that takes a port takes a channel: a volume of several components is
   * paged as one single-scalar volume per component (strata::PagePoolFormat, Components), the
   * component c > 0 under its channel (component 0's channel is the port).
   */
  static int GetChannel(int port, int component) { return port + MaxPorts * component; }
  /// The pool id of step `step` of `channel`: channel + MaxChannels step.
  static int GetPoolId(int channel, int step) { return channel + MaxChannels * step; }

  /**
   * Pages the volume of `port` from the brick pool `fileName`, time step `step` of its series
   * (kept while the name and step stay); null with `error` set when it cannot be opened, is
   * not a brick pool, its pages do not form its tree, or port or step is out of range. Another
   * step of the same structure keeps the cut (see the class documentation).
   */
  const strata::PagePoolFile* OpenPool(int port,
    const std::string& fileName,
    std::string& error,
    int step = 0);
  /**
   * The step `step` (pool `fileName`) that playback on `port` shows next, whose pages each
   * Update prefetches; `step` < 0: none. False, with `error` set, when the pool cannot be
   * opened or its structure differs from the port's (then nothing is prefetched).
   */
  bool SetNextStep(int port, int step, const std::string& fileName, std::string& error);
  /**
   * The step playback on paged `port` goes to after showing `step` of a series of `steps`
   * (call once a frame): the next one in the direction of the last step change (forward at
   * first), wrapping around at the ends, as a looping animation does; a change of more than
   * half the series is taken as such a wrap (7 -> 0 of 8 steps goes forward). -1 for a series
   * of fewer than two steps or a port that is not paged.
   */
  int FollowPlayback(int port, int step, int steps);
  /**
   * Stops paging `port`: its pools (every step opened) and their pages are forgotten, and the
   * next SetVolumes starts a new cut. A port that goes on in core, or with fewer components,
   * must be closed so: SetVolumes takes a paged port's tree over the one it is given.
   */
  void ClosePool(int port);
  /// The pool of a paged port and its tree (structure only); null when `port` is not paged.
  const strata::PagePoolFile* GetPool(int port) const;
  const strata::VolumeBrickTree* GetPoolTree(int port) const;

  /**
   * The frame's volumes and atlas. The cut starts again from the roots when the volumes, their
   * trees or types, the brick size, the budget (MiB of bricks in the atlas's type) or the
   * atlas's type changed, or after InvalidateCut(); `rebuilt` then says that the atlas was
   * re-laid (GetAtlas(), GetAtlasType()). False, with `error` set, when the budget holds no
   * brick.
   */
  bool SetVolumes(const std::vector<Volume>& volumes,
    int brickSize,
    double budgetMiB,
    int maxTextureSize,
    bool& rebuilt,
    std::string& error);
  ///@{
  /**
   * How the atlas stores 8- and 16-bit volumes (strata::BrickAtlasFormat::Choose; default
   * Float32). Takes effect at the next SetVolumes (which then rebuilds).
   */
  void SetAtlasStorage(strata::BrickAtlasFormat::Storage storage) { this->AtlasStorage = storage; }
  strata::BrickAtlasFormat::Storage GetAtlasStorage() const { return this->AtlasStorage; }
  ///@}
  /// The atlas's texel type, and the values' type of the frame's volume `volume` (its tree's:
  /// the in-core tree's, or the pool's for a paged one).
  strata::VolumeBrickTree::ScalarType GetAtlasType() const;
  strata::VolumeBrickTree::ScalarType GetVolumeType(int volume) const;
  /// Forces the next SetVolumes to rebuild (a caller's tree was rebuilt, or its atlas lost).
  void InvalidateCut() { this->CutValid = false; }
  int GetNumberOfVolumes() const;
  /// The frame's number of the volume on `port`, -1 if none.
  int GetVolumeOf(int port) const;

  /**
   * Feedback bookkeeping before a frame's cut: with `feedback` on, the demand of every node
   * (allocated for the current trees if needed) halves when `moved`; off, it is dropped.
   * Returns true when earlier feedback no longer applies (demand new or dropped): the caller
   * discards a feedback buffer it has not read.
   */
  bool PrepareDemand(bool feedback, bool moved);
  /// The pages a frame's rays asked for (sorted by id): raises the demand of their ancestors.
  void AddFeedback(const std::vector<strata::FeedbackReduction::Entry>& asked);

  /**
   * One frame's cut for `camera`: priorities (feedback demand or screen-space error, fixed
   * cuts first), availability of paged bricks, roots, the update, held pages, atlas slots.
   * `feedbackCurrent`: the feedback used was rendered from this view and cut. Fills `uploads`
   * (bricks that entered the atlas) and returns the bricks that found no slot; -1, with
   * `error` set, when a root cannot be read.
   */
  int Update(const strata::VolumeCut::Camera& camera,
    const Settings& settings,
    bool feedbackCurrent,
    std::vector<strata::VolumeCut::Upload>& uploads,
    std::string& error);

  /**
   * The B^3 values of an upload: the in-core tree's brick (extracted into `scratch`) or the
   * held page of a paged one; null if a paged brick has no page (cannot happen: the cut holds
   * only bricks whose pages are held).
   */
  const float* GetBrick(const strata::VolumeCut::Upload& upload, std::vector<float>& scratch) const;
  /// Volume `volume`'s index table (strata::VolumeCut::BuildIndexTable) after Update().
  void BuildIndexTable(int volume, std::vector<uint16_t>& table) const;
  /// The tree the cut uses for volume `volume`.
  const strata::VolumeBrickTree* GetTree(int volume) const;

  const strata::BrickAtlasAllocator& GetAtlas() const;
  const strata::VolumeCut& GetCut() const;

  ///@{
  /// Fixed cuts by port: (level, brick index within the level) per brick (see the class doc).
  void SetFixedCut(int port, const std::vector<std::array<int, 2>>& bricks);
  void RemoveAllFixedCuts();
  bool HasFixedCuts() const;
  ///@}
  /// The cut of the volume on `port` as the last Update left it (transparent bricks included).
  std::vector<std::array<int, 2>> GetCutBricks(int port) const;
  /// Resident (non-empty) cut bricks of the volume on `port`, counted by level.
  std::vector<int> GetResidentBricksPerLevel(int port) const;

  /// Load failures not reported before, as messages naming the page and port.
  std::vector<std::string> TakeNewFailures();
  Statistics GetStatistics() const;
  void RetryFailedPages();
  /// Once per change: how inconsistent budgets were clamped (strata::PagedPools::PlanHeldPages).
  std::string TakeBudgetWarning();
  bool WaitForIdle(double seconds);

private:
  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
  bool CutValid = false;
  strata::BrickAtlasFormat::Storage AtlasStorage = strata::BrickAtlasFormat::Storage::Float32;
};
}

#endif
