// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataPageCache.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <list>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace strata
{

namespace
{
// Pages within a level are below 2^31 (pool page ids are 32-bit); data sets are pools of
// (component) channels times time steps (strata::VolumePager::GetPoolId).
constexpr int DatasetBits = 24;
constexpr int LevelBits = 8;
constexpr int PageBits = 32;

std::string Describe(const PageCache::Key& k)
{
  std::ostringstream s;
  s << "page (data set " << k.Dataset << ", level " << k.Level << ", index " << k.Page << ")";
  return s.str();
}
}

bool PageCache::Key::IsValid() const
{
  return this->Dataset >= 0 && this->Dataset < (1 << DatasetBits) && this->Level >= 0 &&
         this->Level < (1 << LevelBits) && this->Page >= 0 && this->Page < (int64_t(1) << PageBits);
}

uint64_t PageCache::Key::Pack() const
{
  return (static_cast<uint64_t>(this->Dataset) << (LevelBits + PageBits)) |
         (static_cast<uint64_t>(this->Level) << PageBits) | static_cast<uint64_t>(this->Page);
}

PageCache::Key PageCache::Key::Unpack(uint64_t packed)
{
  Key k;
  k.Dataset = static_cast<int>(packed >> (LevelBits + PageBits));
  k.Level = static_cast<int>((packed >> PageBits) & ((1u << LevelBits) - 1));
  k.Page = static_cast<int64_t>(packed & ((uint64_t(1) << PageBits) - 1));
  return k;
}

class PageCache::vtkInternals
{
public:
  struct Resident
  {
    uint64_t Key;
    Page Data;
    int64_t LastUsed; ///< frame of the last Find (or demand load); pinned when == Frame
  };
  enum Tier
  {
    Demand = 0,
    Prefetch = 1
  };
  struct Queued
  {
    int Tier;
    double Priority;
    uint64_t Sequence; ///< first come first served among equal priorities
    uint64_t Key;
  };
  struct QueueOrder
  {
    bool operator()(const Queued& a, const Queued& b) const
    {
      if (a.Tier != b.Tier)
      {
        return a.Tier < b.Tier;
      }
      if (a.Priority != b.Priority)
      {
        return a.Priority > b.Priority;
      }
      return a.Sequence < b.Sequence;
    }
  };
  using QueueSet = std::set<Queued, QueueOrder>;
  struct QueueEntry
  {
    QueueSet::iterator It;
    int64_t Renewed; ///< frame of the last Request/Prefetch
  };
  struct FailureState
  {
    std::string Error;
    int64_t Frame = 0;
    int64_t RetryAt = 0; ///< first frame a Request may try again (RetryFrames > 0)
  };
  struct Loading
  {
    bool Demand; ///< pin on arrival: a Request asked for it (a Prefetch alone does not pin)
  };

  // Everything below is guarded by Mutex, except Workers (touched only by Start/Stop).
  mutable std::mutex Mutex;
  std::condition_variable WorkCv; ///< queue not empty, or stopping
  std::condition_variable IdleCv; ///< queue empty and nothing in flight
  std::vector<std::thread> Workers;
  bool Running = false;
  bool Stopping = false;

  LoadFunction Loader;
  NeighbourFunction Neighbours;
  int NumberOfThreads = 2;
  size_t Budget = size_t(1024) << 20;
  int RetryFrames = 0;

  int64_t Frame = 0;
  uint64_t Sequence = 0;
  std::list<Resident> Lru; ///< front: least recently used
  std::unordered_map<uint64_t, std::list<Resident>::iterator> ResidentMap;
  size_t CurrentBytes = 0;
  QueueSet Queue;
  std::unordered_map<uint64_t, QueueEntry> QueueMap;
  std::unordered_map<uint64_t, Loading> InFlight;
  std::unordered_set<uint64_t> DeferredKeys; ///< cleared by BeginFrame()
  std::unordered_set<uint64_t> Discard;      ///< in flight when their data set was forgotten
  std::unordered_map<uint64_t, FailureState> Failed;
  std::unordered_map<uint64_t, int> Attempts; ///< failed loads since the last success/Retry
  std::vector<uint64_t> NewFailures;
  Statistics Stats;

  bool IsIdle() const { return this->Queue.empty() && this->InFlight.empty(); }

  bool IsEvictable(const Resident& r) const
  {
    // use_count() is exact here: copies leave the cache only through Find(), under the lock,
    // so a count of 1 cannot grow behind our back.
    return r.LastUsed != this->Frame && r.Data.use_count() == 1;
  }

  void Evict(std::list<Resident>::iterator it)
  {
    this->CurrentBytes -= it->Data->size();
    this->ResidentMap.erase(it->Key);
    this->Lru.erase(it);
    ++this->Stats.Evictions;
  }

  /// Evicts least recently used evictable pages until `bytes` more fit; nothing if they cannot.
  bool MakeRoom(size_t bytes)
  {
    if (this->CurrentBytes + bytes <= this->Budget)
    {
      return true;
    }
    if (bytes > this->Budget)
    {
      return false;
    }
    const size_t need = this->CurrentBytes + bytes - this->Budget;
    size_t found = 0;
    auto last = this->Lru.begin();
    for (; last != this->Lru.end() && found < need; ++last)
    {
      found += this->IsEvictable(*last) ? last->Data->size() : 0;
    }
    if (found < need)
    {
      return false; // all pinned or referenced: keep the cache as it is
    }
    for (auto it = this->Lru.begin(); it != last;)
    {
      auto next = std::next(it);
      if (this->IsEvictable(*it))
      {
        this->Evict(it);
      }
      it = next;
    }
    return true;
  }

  void Trim()
  {
    for (auto it = this->Lru.begin(); it != this->Lru.end() && this->CurrentBytes > this->Budget;)
    {
      auto next = std::next(it);
      if (this->IsEvictable(*it))
      {
        this->Evict(it);
      }
      it = next;
    }
  }

  void Enqueue(uint64_t key, int tier, double priority)
  {
    auto it = this->Queue.insert(Queued{ tier, priority, this->Sequence++, key }).first;
    this->QueueMap[key] = QueueEntry{ it, this->Frame };
  }

  /// Neither resident, queued, loading, failed nor deferred.
  bool IsAbsent(uint64_t key) const
  {
    return !this->ResidentMap.count(key) && !this->QueueMap.count(key) &&
           !this->InFlight.count(key) && !this->Failed.count(key) && !this->DeferredKeys.count(key);
  }

  void RecordFailure(uint64_t key, const std::string& error)
  {
    ++this->Stats.Failures;
    const int attempts = ++this->Attempts[key];
    FailureState& f = this->Failed[key];
    f.Error = error;
    f.Frame = this->Frame;
    const int64_t backoff = int64_t(this->RetryFrames)
                            << std::min(attempts - 1, 10); // n, 2n, ..., 1024n
    f.RetryAt = this->Frame + backoff;
    if (attempts == 1)
    {
      this->NewFailures.push_back(key); // a key failing again after a back-off is not news
    }
  }

  void Finish(uint64_t key, bool ok, std::vector<uint8_t>&& data, const std::string& error)
  {
    const Loading loading = this->InFlight[key];
    this->InFlight.erase(key);
    if (this->Stopping || this->Discard.erase(key) > 0)
    {
      return;
    }
    if (!ok)
    {
      this->RecordFailure(key, error);
      return;
    }
    ++this->Stats.Loads;
    this->Stats.BytesRead += static_cast<int64_t>(data.size());
    const size_t bytes = data.size();
    if (bytes > this->Budget)
    {
      std::ostringstream s;
      s << Describe(Key::Unpack(key)) << ": " << bytes << " bytes exceed the cache budget of "
        << this->Budget << " bytes";
      this->RecordFailure(key, s.str());
      return;
    }
    if (!this->MakeRoom(bytes))
    {
      ++this->Stats.Deferred;
      this->DeferredKeys.insert(key);
      return;
    }
    this->Attempts.erase(key);
    auto page = std::make_shared<const std::vector<uint8_t>>(std::move(data));
    this->Lru.push_back(Resident{ key, std::move(page), loading.Demand ? this->Frame : -1 });
    this->ResidentMap[key] = std::prev(this->Lru.end());
    this->CurrentBytes += bytes;
  }

  void Work()
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    while (true)
    {
      this->WorkCv.wait(lock, [this] { return this->Stopping || !this->Queue.empty(); });
      if (this->Stopping)
      {
        return;
      }
      const Queued next = *this->Queue.begin();
      this->Queue.erase(this->Queue.begin());
      this->QueueMap.erase(next.Key);
      this->InFlight[next.Key] = Loading{ next.Tier == Demand };
      const LoadFunction& loader = this->Loader;        // set only while stopped
      const NeighbourFunction& more = this->Neighbours; // idem
      lock.unlock();

      // The slow part, without the lock: the render thread never waits for it.
      const Key key = Key::Unpack(next.Key);
      std::vector<uint8_t> data;
      std::string error;
      bool ok = false;
      try
      {
        ok = loader(key, data, error);
      }
      catch (const std::exception& e)
      {
        error = std::string("the loader threw: ") + e.what();
      }
      catch (...)
      {
        error = "the loader threw an unknown exception";
      }
      if (!ok)
      {
        error = Describe(key) + ": " + (error.empty() ? "load failed without a message" : error);
        data.clear();
      }
      std::vector<Key> prefetch;
      if (ok && more && next.Tier == Demand)
      {
        try
        {
          more(key, prefetch);
        }
        catch (...)
        {
          prefetch.clear(); // a prefetch hint is not worth a failure
        }
      }

      lock.lock();
      this->Finish(next.Key, ok, std::move(data), error);
      if (!this->Stopping)
      {
        for (const Key& p : prefetch)
        {
          if (p.IsValid() && this->IsAbsent(p.Pack()))
          {
            this->Enqueue(p.Pack(), Prefetch, next.Priority);
            this->WorkCv.notify_one();
            ++this->Stats.Prefetches;
          }
        }
      }
      if (this->IsIdle())
      {
        this->IdleCv.notify_all();
      }
    }
  }
};

PageCache::PageCache()
  : Internals(new vtkInternals)
{
}

PageCache::~PageCache()
{
  this->Stop();
}

bool PageCache::SetLoadFunction(LoadFunction loader)
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  if (this->Internals->Running)
  {
    return false;
  }
  this->Internals->Loader = std::move(loader);
  return true;
}

void PageCache::AddGridNeighbours(const Key& key,
  const int pages[3],
  const int* parentPages,
  std::vector<Key>& prefetch)
{
  const int64_t nx = pages[0], ny = pages[1], nz = pages[2];
  if (key.Page < 0 || key.Page >= nx * ny * nz)
    return;
  const int64_t x = key.Page % nx, y = (key.Page / nx) % ny, z = key.Page / (nx * ny);
  auto add = [&](int level, int64_t i, int64_t j, int64_t k, int64_t mx, int64_t my, int64_t mz)
  {
    if (i < 0 || j < 0 || k < 0 || i >= mx || j >= my || k >= mz)
      return;
    Key n = key;
    n.Level = level;
    n.Page = i + mx * (j + my * k);
    prefetch.push_back(n);
  };
  for (int d = -1; d <= 1; d += 2)
  {
    add(key.Level, x + d, y, z, nx, ny, nz);
    add(key.Level, x, y + d, z, nx, ny, nz);
    add(key.Level, x, y, z + d, nx, ny, nz);
  }
  if (parentPages)
    add(key.Level + 1, x / 2, y / 2, z / 2, parentPages[0], parentPages[1], parentPages[2]);
}

bool PageCache::SetNeighbourFunction(NeighbourFunction neighbours)
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  if (this->Internals->Running)
  {
    return false;
  }
  this->Internals->Neighbours = std::move(neighbours);
  return true;
}

void PageCache::SetNumberOfThreads(int n)
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  this->Internals->NumberOfThreads = std::max(1, n);
}

int PageCache::GetNumberOfThreads() const
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  return this->Internals->NumberOfThreads;
}

void PageCache::SetBudgetMiB(double mib)
{
  this->SetBudgetBytes(mib > 0 ? static_cast<size_t>(mib * 1048576.0) : 0);
}

void PageCache::SetBudgetBytes(size_t bytes)
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  this->Internals->Budget = bytes;
  this->Internals->Trim();
}

size_t PageCache::GetBudgetBytes() const
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  return this->Internals->Budget;
}

void PageCache::SetRetryFrames(int frames)
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  this->Internals->RetryFrames = std::max(0, frames);
}

int PageCache::GetRetryFrames() const
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  return this->Internals->RetryFrames;
}

bool PageCache::Start()
{
  vtkInternals& in = *this->Internals;
  std::lock_guard<std::mutex> lock(in.Mutex);
  if (in.Running)
  {
    return true;
  }
  if (!in.Loader)
  {
    return false;
  }
  in.Running = true;
  in.Stopping = false;
  for (int i = 0; i < in.NumberOfThreads; ++i)
  {
    in.Workers.emplace_back([&in] { in.Work(); });
  }
  return true;
}

void PageCache::Stop()
{
  vtkInternals& in = *this->Internals;
  {
    std::lock_guard<std::mutex> lock(in.Mutex);
    if (!in.Running)
    {
      return;
    }
    in.Stopping = true;
    in.Stats.Cancelled += static_cast<int64_t>(in.Queue.size());
    in.Queue.clear();
    in.QueueMap.clear();
  }
  in.WorkCv.notify_all();
  for (std::thread& t : in.Workers)
  {
    t.join(); // a load in flight returns first; its result is discarded
  }
  std::lock_guard<std::mutex> lock(in.Mutex);
  in.Workers.clear();
  in.InFlight.clear();
  in.Discard.clear();
  in.Running = false;
  in.Stopping = false;
  in.IdleCv.notify_all();
}

bool PageCache::IsRunning() const
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  return this->Internals->Running;
}

void PageCache::BeginFrame()
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  ++this->Internals->Frame;
  this->Internals->DeferredKeys.clear();
}

int64_t PageCache::GetFrame() const
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  return this->Internals->Frame;
}

PageCache::State PageCache::Request(const Key& key, double priority)
{
  if (!key.IsValid())
  {
    return State::Invalid;
  }
  priority = priority == priority ? priority : 0.0; // a NaN would break the queue's order
  const uint64_t k = key.Pack();
  vtkInternals& in = *this->Internals;
  std::unique_lock<std::mutex> lock(in.Mutex);
  if (in.ResidentMap.count(k))
  {
    return State::Resident;
  }
  auto q = in.QueueMap.find(k);
  if (q != in.QueueMap.end())
  {
    q->second.Renewed = in.Frame;
    const vtkInternals::Queued old = *q->second.It;
    if (old.Tier != vtkInternals::Demand || old.Priority != priority)
    {
      in.Queue.erase(q->second.It);
      q->second.It = in.Queue.insert({ vtkInternals::Demand, priority, old.Sequence, k }).first;
    }
    return State::Queued;
  }
  auto l = in.InFlight.find(k);
  if (l != in.InFlight.end())
  {
    l->second.Demand = true;
    return State::Loading;
  }
  auto f = in.Failed.find(k);
  if (f != in.Failed.end())
  {
    if (in.RetryFrames <= 0 || in.Frame < f->second.RetryAt)
    {
      return State::Failed;
    }
    in.Failed.erase(f); // back-off over: try again (Attempts remembers the count)
  }
  if (in.DeferredKeys.count(k))
  {
    return State::Deferred;
  }
  in.Enqueue(k, vtkInternals::Demand, priority);
  lock.unlock(); // a woken worker must not find the lock taken, nor preempt us holding it
  in.WorkCv.notify_one();
  return State::Queued;
}

PageCache::State PageCache::Prefetch(const Key& key, double priority)
{
  if (!key.IsValid())
  {
    return State::Invalid;
  }
  priority = priority == priority ? priority : 0.0;
  const uint64_t k = key.Pack();
  vtkInternals& in = *this->Internals;
  std::unique_lock<std::mutex> lock(in.Mutex);
  if (in.ResidentMap.count(k))
  {
    return State::Resident;
  }
  auto q = in.QueueMap.find(k);
  if (q != in.QueueMap.end())
  {
    q->second.Renewed = in.Frame;
    return State::Queued;
  }
  if (in.InFlight.count(k))
  {
    return State::Loading;
  }
  if (in.Failed.count(k))
  {
    return State::Failed;
  }
  if (in.DeferredKeys.count(k))
  {
    return State::Deferred;
  }
  in.Enqueue(k, vtkInternals::Prefetch, priority);
  ++in.Stats.Prefetches;
  lock.unlock(); // a woken worker must not find the lock taken, nor preempt us holding it
  in.WorkCv.notify_one();
  return State::Queued;
}

PageCache::Page PageCache::Find(const Key& key)
{
  if (!key.IsValid())
  {
    return nullptr;
  }
  vtkInternals& in = *this->Internals;
  std::lock_guard<std::mutex> lock(in.Mutex);
  auto r = in.ResidentMap.find(key.Pack());
  if (r == in.ResidentMap.end())
  {
    ++in.Stats.Misses;
    return nullptr;
  }
  ++in.Stats.Hits;
  r->second->LastUsed = in.Frame;
  in.Lru.splice(in.Lru.end(), in.Lru, r->second);
  return r->second->Data;
}

bool PageCache::IsResident(const Key& key) const
{
  if (!key.IsValid())
  {
    return false;
  }
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  return this->Internals->ResidentMap.count(key.Pack()) > 0;
}

int PageCache::CancelStale(int64_t frame)
{
  vtkInternals& in = *this->Internals;
  std::lock_guard<std::mutex> lock(in.Mutex);
  int dropped = 0;
  for (auto q = in.QueueMap.begin(); q != in.QueueMap.end();)
  {
    if (q->second.Renewed < frame)
    {
      in.Queue.erase(q->second.It);
      q = in.QueueMap.erase(q);
      ++dropped;
    }
    else
    {
      ++q;
    }
  }
  in.Stats.Cancelled += dropped;
  if (dropped && in.IsIdle())
  {
    in.IdleCv.notify_all();
  }
  return dropped;
}

std::vector<PageCache::Failure> PageCache::GetFailedPages() const
{
  vtkInternals& in = *this->Internals;
  std::lock_guard<std::mutex> lock(in.Mutex);
  std::vector<Failure> out;
  for (const auto& f : in.Failed)
  {
    auto a = in.Attempts.find(f.first);
    out.push_back(Failure{ Key::Unpack(f.first),
      f.second.Error,
      f.second.Frame,
      a == in.Attempts.end() ? 0 : a->second });
  }
  std::sort(out.begin(),
    out.end(),
    [](const Failure& a, const Failure& b) { return a.PageKey.Pack() < b.PageKey.Pack(); });
  return out;
}

bool PageCache::GetError(const Key& key, std::string& error) const
{
  if (!key.IsValid())
  {
    return false;
  }
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  auto f = this->Internals->Failed.find(key.Pack());
  if (f == this->Internals->Failed.end())
  {
    return false;
  }
  error = f->second.Error;
  return true;
}

std::vector<PageCache::Failure> PageCache::TakeNewFailures()
{
  vtkInternals& in = *this->Internals;
  std::lock_guard<std::mutex> lock(in.Mutex);
  std::vector<Failure> out;
  for (uint64_t k : in.NewFailures)
  {
    auto f = in.Failed.find(k);
    if (f != in.Failed.end()) // not retried since
    {
      out.push_back(Failure{ Key::Unpack(k), f->second.Error, f->second.Frame, in.Attempts[k] });
    }
  }
  in.NewFailures.clear();
  return out;
}

void PageCache::Retry(const Key& key)
{
  if (!key.IsValid())
  {
    return;
  }
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  this->Internals->Failed.erase(key.Pack());
  this->Internals->Attempts.erase(key.Pack());
}

void PageCache::RetryAll()
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  this->Internals->Failed.clear();
  this->Internals->Attempts.clear();
}

bool PageCache::WaitForIdle(double seconds)
{
  vtkInternals& in = *this->Internals;
  std::unique_lock<std::mutex> lock(in.Mutex);
  return in.IdleCv.wait_for(
    lock, std::chrono::duration<double>(std::max(0.0, seconds)), [&in] { return in.IsIdle(); });
}

size_t PageCache::EvictAll()
{
  vtkInternals& in = *this->Internals;
  std::lock_guard<std::mutex> lock(in.Mutex);
  size_t n = 0;
  for (auto it = in.Lru.begin(); it != in.Lru.end();)
  {
    auto next = std::next(it);
    if (in.IsEvictable(*it))
    {
      in.Evict(it);
      ++n;
    }
    it = next;
  }
  return n;
}

size_t PageCache::Forget(int dataset)
{
  vtkInternals& in = *this->Internals;
  std::lock_guard<std::mutex> lock(in.Mutex);
  auto of = [dataset](uint64_t key) { return Key::Unpack(key).Dataset == dataset; };
  size_t n = 0;
  for (auto it = in.Lru.begin(); it != in.Lru.end();)
  {
    if (!of(it->Key))
    {
      ++it;
      continue;
    }
    in.CurrentBytes -= it->Data->size(); // not an eviction: holders keep their copies
    in.ResidentMap.erase(it->Key);
    it = in.Lru.erase(it);
    ++n;
  }
  for (auto it = in.Queue.begin(); it != in.Queue.end();)
  {
    if (!of(it->Key))
    {
      ++it;
      continue;
    }
    in.QueueMap.erase(it->Key);
    it = in.Queue.erase(it);
  }
  for (const auto& loading : in.InFlight)
    if (of(loading.first))
      in.Discard.insert(loading.first);
  for (auto it = in.Failed.begin(); it != in.Failed.end();)
    it = of(it->first) ? in.Failed.erase(it) : std::next(it);
  for (auto it = in.Attempts.begin(); it != in.Attempts.end();)
    it = of(it->first) ? in.Attempts.erase(it) : std::next(it);
  for (auto it = in.DeferredKeys.begin(); it != in.DeferredKeys.end();)
    it = of(*it) ? in.DeferredKeys.erase(it) : std::next(it);
  return n;
}

PageCache::Statistics PageCache::GetStatistics() const
{
  const vtkInternals& in = *this->Internals;
  std::lock_guard<std::mutex> lock(in.Mutex);
  Statistics s = in.Stats;
  s.QueueLength = in.Queue.size();
  s.InFlight = in.InFlight.size();
  s.Pages = in.ResidentMap.size();
  s.CurrentBytes = in.CurrentBytes;
  s.BudgetBytes = in.Budget;
  return s;
}

void PageCache::ResetStatistics()
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  this->Internals->Stats = Statistics();
}
}
