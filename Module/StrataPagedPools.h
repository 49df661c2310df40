// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::PagedPools
 * @brief   What both pagers share: the open page pools, the RAM page cache and its loaders,
 *          pages asked for under a request limit, roots, failures and the statistics of it.
 *
 * strata::VolumePager (bricks) and strata::HeightFieldPager (tiles) differ in their cuts, page
 * tables and feedback; everything between a pool on disk and a page in RAM is this one piece:
 * - Pools are kept by id, the cache key's data set (strata::VolumePager::GetPoolId of a volume's
 *   port, component and time step, or the horizon stack's pool index); an id opened again for
 *   another file forgets the old file's pages (strata::PageCache::Forget). The cache's workers
 *   read them (strata::PagePoolFile::ReadPage, as floats) and, with prefetch on, queue a loaded
 *   page's face neighbours and parent (strata::PageCache::AddGridNeighbours on the pool's level
 *   grids); the map of pools is guarded for them.
 * - Acquire() is the cut's availability answer: the page if it is in RAM, else a request at
 *   the node's priority. Requests per frame are capped at four frames' worth of uploads
 *   (4 x PagesPerFrame): a longer queue would load pages the cache evicts again before the cut
 *   could use them. Misses are counted either way.
 * - Roots, the pages every frame can always show, are never waited for: PadRoot() makes one
 *   from the coarsest level a reader already produced, ReadRoot() reads it on the calling
 *   thread once when there is none.
 * - BeginFrame() and EndFrame() bracket a cut update: the budget and workers are set, and at
 *   the end requests the frame did not renew (views gone by) are dropped.
 *
 * Thread contract: everything but the loaders runs on the render thread; the loaders only read
 * the pool map under its lock. Destruction stops the workers first.
 *
 * @sa strata::PageCache strata::PagePoolFile strata::VolumePager strata::HeightFieldPager
 * strata::CutPages
 */
#ifndef StrataPagedPools_h
#define StrataPagedPools_h

#include "StrataCoreModule.h" // For export macro
#include "StrataPageCache.h"  // For strata::PageCache::Key, Page, Failure

#include <memory> // For std::unique_ptr, std::shared_ptr
#include <string> // For std::string
#include <vector> // For std::vector

namespace strata
{
class PagePoolFile;
}
namespace strata
{
class VolumeBrickTree;
}

namespace strata
{
class STRATACORE_EXPORT PagedPools
{
public:
  struct Statistics
  {
    int PendingPages = 0;     ///< queued or loading after the last frame
    int MissesThisFrame = 0;  ///< pages the last frame's cut wanted and had no page for
    long long BytesRead = 0;  ///< by the cache's workers, in all
    long long CacheBytes = 0; ///< resident in the page cache now
    int RootPagesRead = 0;    ///< roots the render thread read itself (ReadRoot)
    int StepPagesRead = 0;    ///< pages of a new time step the render thread read itself (ReadPage)
    int Failures = 0;         ///< pages whose load failed, in all (TakeNewFailures)

    /// Calls `visit(name, value)` for each field, in declaration order (wrappable forms, logs).
    template<typename Visit>
    void ForEachField(Visit&& visit) const
    {
      visit("PendingPages", this->PendingPages);
      visit("MissesThisFrame", this->MissesThisFrame);
      visit("BytesRead", this->BytesRead);
      visit("CacheBytes", this->CacheBytes);
      visit("RootPagesRead", this->RootPagesRead);
      visit("StepPagesRead", this->StepPagesRead);
      visit("Failures", this->Failures);
    }
  };

  PagedPools();
  ~PagedPools();
  PagedPools(const PagedPools&) = delete;
  PagedPools& operator=(const PagedPools&) = delete;

  /**
   * Opens `fileName` as pool `id`, or keeps the pool already open under that id and name.
   * Returns null with `error` set when the file cannot be opened.
   */
  std::shared_ptr<strata::PagePoolFile> OpenPool(int id,
    const std::string& fileName,
    std::string& error);
  /// The pool of `id`, null if none.
  strata::PagePoolFile* GetPool(int id) const;
  /// The file name pool `id` was opened from (empty if none).
  std::string GetPoolName(int id) const;
  /// Forgets pool `id` and its pages (pinned ones too; holders keep their copies). False if no
  /// pool was open under `id`.
  bool ClosePool(int id);
  /// Stops the workers, drops every page and forgets every pool and statistic.
  void Close();

  /**
   * The structure of a pool's page hierarchy: node i is page i, its range the page's min and
   * max (the page table's, so nothing is read). False when the pages do not form the tree its
   * dimensions imply.
   */
  static bool BuildTree(const strata::PagePoolFile& pool, strata::VolumeBrickTree& tree);

  ///@{
  /// Budgets: RAM cache in MiB, pages uploaded per frame (requests: 4x), prefetch.
  void SetCacheBudgetMiB(double mib) { this->CacheMiB = mib; }
  void SetPagesPerFrame(int pages) { this->RequestLimit = this->FrameRequests = 4 * pages; }
  void SetPrefetch(bool prefetch);
  ///@}

  /**
   * How many pages the cut may hold pinned in the cache (strata::VolumeCut::SetPageBudget), for an
   * atlas of `slots` pages in trees of `children` children per node. The cache must hold the
   * pages of the cut and of their ancestors (strata::CutPages) and, beside them, the pages being
   * loaded; else every load is dropped for want of room, asked again and read again each frame
   * while the cut never refines. A cut filling the atlas holds about
   *   slots + (slots - 1) / (children - 1)
   * pages (its ancestors in a full tree). When the cache holds that and a frame's requests
   * (4 x PagesPerFrame), nothing changes: the bound is the cache's pages less the requests.
   * Otherwise the budgets are inconsistent and both are clamped: the room for loads to what the
   * cache can hold beside that cut (but at least a quarter of the cache and two splits'
   * children, so loads progress), the held pages to the rest, and the requests per frame to
   * half the room (this frame's loads beside the last one's that the cut has not taken yet, so
   * that no load evicts another before its use); TakeBudgetWarning() then says so.
   * Call after BeginFrame() (the budget it applies) with the pools open.
   */
  int PlanHeldPages(int slots, int children);
  /// The message of the last PlanHeldPages() that clamped, once per change of the budgets;
  /// empty otherwise. The mappers print it as a warning.
  std::string TakeBudgetWarning();

  /// Before a cut update: applies the budget, starts the workers, counts misses from 0.
  void BeginFrame();
  /**
   * Page `key` if it is in RAM (pinned for this frame); otherwise null, counted as a miss,
   * and requested at `priority` while the frame's requests are under the limit.
   */
  strata::PageCache::Page Acquire(const strata::PageCache::Key& key, double priority);
  /// Whether page `key` is in RAM now (no pin, no statistics).
  bool IsResident(const strata::PageCache::Key& key) const;
  /// Page `key` if it is in RAM (pinned for this frame), else null; requests nothing.
  strata::PageCache::Page Find(const strata::PageCache::Key& key);
  /**
   * Queues page `key` below every demand request, at `priority` among prefetches (the next
   * time step of a series); renews it while it waits. Never waits.
   */
  void Prefetch(const strata::PageCache::Key& key, double priority);
  /// After the cut update: drops the requests it did not renew.
  void EndFrame();
  /// Load failures not reported before, oldest first (each counts in Failures).
  std::vector<strata::PageCache::Failure> TakeNewFailures();

  /**
   * A root page from the coarsest level a reader produced: `values` of dims[0] x dims[1] x
   * dims[2] points, x fastest, padded to `pageDims` by repeating the level's last point (as
   * the pool writer pads).
   */
  static strata::PageCache::Page PadRoot(const float* values,
    const int dims[3],
    const int pageDims[3]);
  /// Page `index` of `level` of pool `id` read on the calling thread (the root when no reader
  /// produced it); null with `error` set on failure. Counts in RootPagesRead.
  strata::PageCache::Page ReadRoot(int id, int level, uint64_t index, std::string& error);
  /// The same read for a page that had to be there and is not (a time step's page that was not
  /// prefetched in time): the render thread waits for it. Counts in StepPagesRead.
  strata::PageCache::Page ReadPage(int id, int level, uint64_t index, std::string& error);

  /// The counts so far, the cache's (pending, bytes read and resident) as of now.
  Statistics GetStatistics() const;
  /// Loads failed pages again (after a transient error).
  void RetryFailedPages();
  /// Waits (tests, benchmarks) until no load is queued or running.
  bool WaitForIdle(double seconds);

private:
  strata::PageCache::Page ReadNow(int id, int level, uint64_t index, std::string& error);

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
  double CacheMiB = 512.0;
  int RequestLimit = 256;  ///< 4 x PagesPerFrame
  int FrameRequests = 256; ///< RequestLimit as PlanHeldPages() clamped it
  std::string Warning;     ///< not taken yet
  std::string LastWarning; ///< the last one made, so that each is made once
  Statistics Stats;
};
}

#endif
