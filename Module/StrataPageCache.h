// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::PageCache
 * @brief   RAM page cache (LRU, byte budget) filled asynchronously by worker threads.
 *
 * The brick data cache of Lux and Froehlich (multi-volume multi-resolution ray casting,
 * section 3.1, Fig. 1) and the tile cache of stacked height-field ray casting: the second-level
 * cache in system memory between the page pool on disk and the GPU atlas (the first level,
 * strata::BrickAtlasAllocator). One cache serves every data set, so one budget balances them all.
 *
 * Why asynchronous: the renderer must never stall on the disk. The cut update asks the cache
 * for what it would like (Request, with a priority such as screen coverage) and uses only what
 * is resident now (Find); worker threads read and decode the wanted pages in priority order,
 * and the cut picks them up in a later frame. Until then the renderer keeps drawing the coarser
 * level it already has.
 *
 * Threads. Request, Prefetch, Find, IsResident, BeginFrame, CancelStale and the queries are
 * meant for one render thread (they are thread safe, but frame semantics assume one caller).
 * None of them waits for a load: the internal lock is never held across the loader, and the
 * work done under it is a hash look-up, an ordered-set update or an LRU splice (eviction scans
 * the LRU list, a few microseconds per thousand pages). The loader runs only on worker threads.
 * Start(), Stop() and destruction belong to the owning thread and must not be called from the
 * loader or the neighbour function.
 *
 * Pages are immutable, reference-counted byte buffers: the renderer may keep one it is still
 * uploading while the cache moves on. A page referenced outside the cache is never evicted, and
 * neither is a page pinned by this frame (found with Find, or loaded by a demand Request, since
 * the last BeginFrame()). Among the others the least recently used goes first.
 *
 * Budget. The bytes of resident pages never exceed the budget. When a loaded page does not fit
 * and the evictable pages cannot make room (everything pinned or referenced), the page is
 * dropped, counted in Statistics::Deferred, and its key is not queued again before the next
 * BeginFrame(); the renderer's next request loads it once a frame has unpinned room. A page
 * larger than the whole budget fails with an error. Transient excess: lowering the budget
 * evicts what it can at once, and pinned or referenced pages leave when they become evictable;
 * pages being loaded (at most one per worker) are not yet counted.
 *
 * Faults. A load that fails (the loader returns false or throws) records an error naming the
 * page; the key is not loaded again until Retry() or, with SetRetryFrames(n > 0), after an
 * exponential back-off of n, 2n, 4n, ... frames. TakeNewFailures() reports each failure once,
 * so the renderer can print one clear message and go on with coarser data.
 *
 * Shutdown. Stop() (and the destructor) drops the queued work, lets loads in flight return,
 * discards their results and joins the workers. The loader must stay callable until then.
 *
 * @sa strata::BrickAtlasAllocator strata::VolumeCut
 */
#ifndef StrataPageCache_h
#define StrataPageCache_h

#include "StrataCoreModule.h" // For export macro

#include <cstddef>    // For size_t
#include <cstdint>    // For int64_t, uint8_t, uint64_t
#include <functional> // For std::function
#include <memory>     // For std::unique_ptr, std::shared_ptr
#include <string>     // For std::string
#include <vector>     // For std::vector

namespace strata
{
class STRATACORE_EXPORT PageCache
{
public:
  /**
   * Page address: data set, level of detail (0 finest) and page index within the level.
   * Packs into 64 bits: 16 bits of data set, 8 of level, 40 of page index.
   */
  struct Key
  {
    int Dataset = 0;  ///< [0, 2^24)
    int Level = 0;    ///< [0, 255]
    int64_t Page = 0; ///< [0, 2^32)
    bool operator==(const Key& o) const
    {
      return this->Dataset == o.Dataset && this->Level == o.Level && this->Page == o.Page;
    }
    bool operator!=(const Key& o) const { return !(*this == o); }
    bool IsValid() const;
    /// Meaningful for valid keys only (see IsValid()).
    uint64_t Pack() const;
    static Key Unpack(uint64_t packed);
  };

  /// An immutable page; whoever holds one keeps it alive and resident.
  using Page = std::shared_ptr<const std::vector<uint8_t>>;

  /**
   * Reads and decodes one page into `out`. Returns false and sets `error` on failure; an
   * exception counts as a failure too. Called only on worker threads, possibly concurrently
   * for different keys, never twice at once for the same key.
   */
  using LoadFunction =
    std::function<bool(const Key&, std::vector<uint8_t>& out, std::string& error)>;

  /**
   * Keys worth prefetching after `key` was loaded on demand (its parent, its neighbours).
   * Called on the worker thread after the load; the keys are queued at prefetch priority.
   */
  using NeighbourFunction = std::function<void(const Key&, std::vector<Key>& prefetch)>;

  /**
   * The usual prefetch set of a page of a level cut into a grid of `pages` (x fastest, page
   * index x + nx (y + ny z)): its face neighbours in that level and, when `parentPages` is
   * given (the next coarser level's grid), its parent (index / 2 per axis). A moving camera
   * asks for the neighbours of what it sees next, and a collapse for the parent.
   */
  static void AddGridNeighbours(const Key& key,
    const int pages[3],
    const int* parentPages,
    std::vector<Key>& prefetch);

  /// What Request() found or did.
  enum class State
  {
    Resident, ///< in the cache; Find() returns it
    Queued,   ///< waiting for a worker (queued now or before; priority updated)
    Loading,  ///< a worker is loading it
    Failed,   ///< its last load failed; not retried yet (see GetError(), Retry())
    Deferred, ///< loaded but did not fit (all pinned or referenced); asked again next frame
    Invalid   ///< the key does not pack (see Key)
  };

  struct Failure
  {
    Key PageKey;
    std::string Error; ///< names the page and says what went wrong
    int64_t Frame = 0; ///< frame of the failure
    int Attempts = 0;  ///< failed loads of this key since the last Retry()
  };

  struct Statistics
  {
    int64_t Hits = 0;      ///< Find() calls that returned a page
    int64_t Misses = 0;    ///< Find() calls that returned null
    int64_t Loads = 0;     ///< successful loads
    int64_t BytesRead = 0; ///< bytes of successful loads
    int64_t Evictions = 0;
    int64_t Failures = 0;   ///< failed loads
    int64_t Deferred = 0;   ///< loads dropped because nothing evictable made room
    int64_t Cancelled = 0;  ///< queued requests dropped by CancelStale() or Stop()
    int64_t Prefetches = 0; ///< keys queued by Prefetch() or the neighbour function
    size_t QueueLength = 0; ///< now
    size_t InFlight = 0;    ///< loads running now
    size_t Pages = 0;       ///< resident pages now
    size_t CurrentBytes = 0;
    size_t BudgetBytes = 0;
  };

  PageCache();
  /// Stop()s: drops queued work, waits for loads in flight, discards them.
  ~PageCache();
  PageCache(const PageCache&) = delete;
  PageCache& operator=(const PageCache&) = delete;

  ///@{
  /// The loader; may only change while stopped (returns false otherwise). Default: none.
  bool SetLoadFunction(LoadFunction loader);
  bool SetNeighbourFunction(NeighbourFunction neighbours);
  ///@}

  ///@{
  /// Worker threads started by Start(); default 2, at least 1. Takes effect at the next Start().
  void SetNumberOfThreads(int n);
  int GetNumberOfThreads() const;
  ///@}

  ///@{
  /**
   * Budget of resident page bytes; default 1024 MiB (2^20 bytes). Lowering it evicts at once
   * what may be evicted.
   */
  void SetBudgetMiB(double mib);
  void SetBudgetBytes(size_t bytes);
  size_t GetBudgetBytes() const;
  ///@}

  ///@{
  /**
   * Back-off of failed keys, in frames: 0 (default) retries only on Retry(); n > 0 allows a
   * new attempt n frames after the first failure, 2n after the second, ... (capped at 1024 n).
   */
  void SetRetryFrames(int frames);
  int GetRetryFrames() const;
  ///@}

  /**
   * Starts the workers; returns false without a loader. Requests made before are served
   * then. Starting a running cache does nothing.
   */
  bool Start();
  /// Drops queued requests, waits for loads in flight (their results are discarded), joins.
  void Stop();
  bool IsRunning() const;

  /// New frame: pages pinned so far become evictable; deferred keys may be requested again.
  void BeginFrame();
  int64_t GetFrame() const;

  /**
   * Asks for a page, priority higher first (e.g. its screen coverage in pixels). Queues it if
   * absent, raises a prefetch to a demand request, and sets the priority of a queued request;
   * either way marks the request as renewed this frame (see CancelStale()). Never waits.
   */
  State Request(const Key& key, double priority);
  /// Queues a page below every demand request (priority among prefetches); never re-prioritises.
  State Prefetch(const Key& key, double priority = 0.0);
  /// The page if resident (a hit: pins it for this frame, most recently used), else null.
  Page Find(const Key& key);
  /// Residency without pinning, LRU update or statistics (for the cut's planning).
  bool IsResident(const Key& key) const;
  /// Drops queued requests (and prefetches) last renewed before `frame`; returns how many.
  int CancelStale(int64_t frame);

  ///@{
  /// Failed pages and their errors. GetError() returns false for a key that has not failed.
  std::vector<Failure> GetFailedPages() const;
  bool GetError(const Key& key, std::string& error) const;
  /// Failures not returned by an earlier call, oldest first: report each once.
  std::vector<Failure> TakeNewFailures();
  /// Forgets the failure of one key (or all), so the next Request() loads it again.
  void Retry(const Key& key);
  void RetryAll();
  ///@}

  /**
   * Blocks until no request is queued or loading, at most `seconds`; true when idle. For tests
   * and offline rendering that needs complete data - never in an interactive render loop.
   */
  bool WaitForIdle(double seconds);

  /// Drops every evictable page (pinned and referenced pages stay); returns how many.
  size_t EvictAll();
  /**
   * Forgets data set `dataset` (its file was replaced under the same keys): its pages leave the
   * cache pinned or not (whoever holds one keeps it alive, but no Find returns it again), its
   * queued requests and failures are dropped, and its loads in flight are discarded when they
   * finish. Returns the pages dropped.
   */
  size_t Forget(int dataset);

  Statistics GetStatistics() const;
  void ResetStatistics();

private:
  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};
}

#endif
