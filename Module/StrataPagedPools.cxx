// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataPagedPools.h"

#include "StrataPagePoolFile.h"
#include "StrataVolumeBrickTree.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>

namespace strata
{

class PagedPools::vtkInternals
{
public:
  struct Pool
  {
    std::shared_ptr<strata::PagePoolFile> File;
    std::string Name;
  };
  strata::PageCache Cache;
  mutable std::mutex Mutex; ///< guards Pools against the cache's workers
  std::map<int, Pool> Pools;
  std::atomic<bool> Prefetch{ false };

  std::shared_ptr<strata::PagePoolFile> Find(int id) const
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    auto it = this->Pools.find(id);
    return it == this->Pools.end() ? nullptr : it->second.File;
  }

  vtkInternals()
  {
    this->Cache.SetLoadFunction(
      [this](const strata::PageCache::Key& key, std::vector<uint8_t>& out, std::string& error)
      {
        const std::shared_ptr<strata::PagePoolFile> pool = this->Find(key.Dataset);
        if (!pool)
        {
          error = "no page pool " + std::to_string(key.Dataset);
          return false;
        }
        out.resize(pool->GetPageValues() * sizeof(float));
        return pool->ReadPage(
          key.Level, static_cast<uint64_t>(key.Page), reinterpret_cast<float*>(out.data()), &error);
      });
    // After a page loaded on demand: its face neighbours and its parent, ahead of the camera.
    this->Cache.SetNeighbourFunction(
      [this](const strata::PageCache::Key& key, std::vector<strata::PageCache::Key>& more)
      {
        if (!this->Prefetch)
          return;
        const std::shared_ptr<strata::PagePoolFile> pool = this->Find(key.Dataset);
        if (!pool || key.Level < 0 || key.Level >= pool->GetNumberOfLevels())
          return;
        const bool parent = key.Level + 1 < pool->GetNumberOfLevels();
        strata::PageCache::AddGridNeighbours(key,
          pool->GetLevel(key.Level).Pages,
          parent ? pool->GetLevel(key.Level + 1).Pages : nullptr,
          more);
      });
  }
};

PagedPools::PagedPools()
  : Internals(new vtkInternals)
{
}

PagedPools::~PagedPools()
{
  this->Internals->Cache.Stop();
}

std::shared_ptr<strata::PagePoolFile> PagedPools::OpenPool(int id,
  const std::string& fileName,
  std::string& error)
{
  vtkInternals& in = *this->Internals;
  {
    std::lock_guard<std::mutex> lock(in.Mutex);
    auto it = in.Pools.find(id);
    if (it != in.Pools.end() && it->second.Name == fileName)
      return it->second.File;
  }
  // Shared with the reader that shows the pool (and any other pager of it): one descriptor.
  std::shared_ptr<strata::PagePoolFile> file = strata::PagePoolFile::OpenShared(fileName, error);
  if (!file)
    return nullptr;
  bool replaced = false;
  {
    std::lock_guard<std::mutex> lock(in.Mutex);
    replaced = in.Pools.count(id) > 0;
    in.Pools[id] = { file, fileName };
  }
  if (replaced)
  {
    in.Cache.Forget(id); // pages of the old file under the same keys, pinned ones too
  }
  return file;
}

strata::PagePoolFile* PagedPools::GetPool(int id) const
{
  return this->Internals->Find(id).get();
}

std::string PagedPools::GetPoolName(int id) const
{
  std::lock_guard<std::mutex> lock(this->Internals->Mutex);
  auto it = this->Internals->Pools.find(id);
  return it == this->Internals->Pools.end() ? std::string() : it->second.Name;
}

bool PagedPools::ClosePool(int id)
{
  vtkInternals& in = *this->Internals;
  {
    std::lock_guard<std::mutex> lock(in.Mutex);
    if (in.Pools.erase(id) == 0)
      return false;
  }
  in.Cache.Forget(id);
  return true;
}

void PagedPools::Close()
{
  vtkInternals& in = *this->Internals;
  in.Cache.Stop();
  std::vector<int> ids;
  {
    std::lock_guard<std::mutex> lock(in.Mutex);
    for (const auto& pool : in.Pools)
      ids.push_back(pool.first);
    in.Pools.clear();
  }
  // Pinned and held pages too: a pool opened later under one of these ids is another file.
  for (int id : ids)
    in.Cache.Forget(id);
  in.Cache.EvictAll();
  this->Stats = Statistics();
  this->Warning.clear();
  this->LastWarning.clear();
}

namespace
{
// The brick tree's name for a pool's scalar type.
strata::VolumeBrickTree::ScalarType TreeType(const strata::PagePoolFile& pool)
{
  switch (pool.GetScalarType())
  {
    case strata::PagePoolFormat::ScalarType::UInt8:
      return strata::VolumeBrickTree::ScalarType::UInt8;
    case strata::PagePoolFormat::ScalarType::UInt16:
      return strata::VolumeBrickTree::ScalarType::UInt16;
    case strata::PagePoolFormat::ScalarType::Int16:
      return strata::VolumeBrickTree::ScalarType::Int16;
    default:
      return strata::VolumeBrickTree::ScalarType::Float32;
  }
}
}

bool PagedPools::BuildTree(const strata::PagePoolFile& pool, strata::VolumeBrickTree& tree)
{
  const uint64_t pages = pool.GetNumberOfPages();
  std::vector<float> lo(pages), hi(pages);
  for (uint64_t id = 0; id < pages; ++id)
  {
    lo[id] = pool.GetPageEntry(id).Min;
    hi[id] = pool.GetPageEntry(id).Max;
  }
  const int* d = pool.GetDimensions();
  // A tile pool's layers live inside its pages: its hierarchy is a quadtree over x and y.
  const int dims[3] = {
    d[0], d[1], pool.GetKind() == strata::PagePoolFormat::Kind::TilePool ? 1 : d[2]
  };
  return tree.BuildStructure(dims, pool.GetPageSize(), lo.data(), hi.data(), TreeType(pool)) &&
         static_cast<uint64_t>(tree.GetNumberOfNodes()) == pages;
}

void PagedPools::SetPrefetch(bool prefetch)
{
  this->Internals->Prefetch = prefetch;
}

void PagedPools::BeginFrame()
{
  strata::PageCache& cache = this->Internals->Cache;
  cache.SetBudgetMiB(this->CacheMiB);
  cache.Start();
  cache.BeginFrame();
  this->Stats.MissesThisFrame = 0;
}

strata::PageCache::Page PagedPools::Acquire(const strata::PageCache::Key& key, double priority)
{
  strata::PageCache& cache = this->Internals->Cache;
  if (strata::PageCache::Page page = cache.Find(key))
  {
    return page;
  }
  if (this->Stats.MissesThisFrame < this->FrameRequests)
  {
    cache.Request(key, priority);
  }
  ++this->Stats.MissesThisFrame;
  return nullptr;
}

bool PagedPools::IsResident(const strata::PageCache::Key& key) const
{
  return this->Internals->Cache.IsResident(key);
}

strata::PageCache::Page PagedPools::Find(const strata::PageCache::Key& key)
{
  return this->Internals->Cache.Find(key);
}

void PagedPools::Prefetch(const strata::PageCache::Key& key, double priority)
{
  this->Internals->Cache.Prefetch(key, priority);
}

int PagedPools::PlanHeldPages(int slots, int children)
{
  vtkInternals& in = *this->Internals;
  size_t pageBytes = 0;
  {
    std::lock_guard<std::mutex> lock(in.Mutex);
    for (const auto& p : in.Pools)
      pageBytes = std::max<size_t>(pageBytes, p.second.File->GetPageValues() * sizeof(float));
  }
  this->FrameRequests = this->RequestLimit;
  if (pageBytes == 0)
    return 0;
  const long long capacity = static_cast<long long>(in.Cache.GetBudgetBytes() / pageBytes);
  const long long full = slots + (slots - 1 + children - 2) / std::max(1, children - 1);
  if (capacity >= full + this->RequestLimit)
    return static_cast<int>(capacity - this->RequestLimit);
  const long long least =
    std::min<long long>(this->RequestLimit, std::max<long long>(2 * children, capacity / 4));
  // Room for two frames of loads: this frame's and the last one's that the cut has not taken
  // yet (a split waits for all its children), so that no load evicts another before its use.
  const long long room = std::max(least, std::min<long long>(this->RequestLimit, capacity - full));
  this->FrameRequests = static_cast<int>(std::max<long long>(1, room / 2));
  const int held = static_cast<int>(std::max<long long>(1, capacity - room));
  std::ostringstream msg;
  msg << "The page cache (" << in.Cache.GetBudgetBytes() / 1048576.0 << " MB, " << capacity
      << " pages of " << pageBytes << " bytes) cannot hold a cut filling the atlas (" << slots
      << " pages and up to " << full - slots << " ancestors, all kept in RAM) beside "
      << this->RequestLimit << " loads a frame: the cut is limited to " << held
      << " pages held and " << this->FrameRequests
      << " loads a frame. Raise PageCacheBudget to at least "
      << std::ceil((full + this->RequestLimit) * static_cast<double>(pageBytes) / 1048576.0)
      << " MB or lower AtlasBudget.";
  if (msg.str() != this->LastWarning)
    this->Warning = this->LastWarning = msg.str();
  return held;
}

std::string PagedPools::TakeBudgetWarning()
{
  std::string warning;
  warning.swap(this->Warning);
  return warning;
}

void PagedPools::EndFrame()
{
  // Requests this frame's cut did not renew are for views gone by.
  strata::PageCache& cache = this->Internals->Cache;
  cache.CancelStale(cache.GetFrame());
}

PagedPools::Statistics PagedPools::GetStatistics() const
{
  Statistics stats = this->Stats;
  const strata::PageCache::Statistics s = this->Internals->Cache.GetStatistics();
  stats.PendingPages = static_cast<int>(s.QueueLength + s.InFlight);
  stats.BytesRead = s.BytesRead;
  stats.CacheBytes = static_cast<long long>(s.CurrentBytes);
  return stats;
}

std::vector<strata::PageCache::Failure> PagedPools::TakeNewFailures()
{
  std::vector<strata::PageCache::Failure> failures = this->Internals->Cache.TakeNewFailures();
  this->Stats.Failures += static_cast<int>(failures.size());
  return failures;
}

strata::PageCache::Page PagedPools::PadRoot(const float* values,
  const int dims[3],
  const int pageDims[3])
{
  const size_t count = static_cast<size_t>(pageDims[0]) * pageDims[1] * pageDims[2];
  auto page = std::make_shared<std::vector<uint8_t>>(count * sizeof(float));
  float* out = reinterpret_cast<float*>(page->data());
  for (int k = 0; k < pageDims[2]; ++k)
    for (int j = 0; j < pageDims[1]; ++j)
      for (int i = 0; i < pageDims[0]; ++i)
      {
        const size_t at =
          (static_cast<size_t>(std::min(k, dims[2] - 1)) * dims[1] + std::min(j, dims[1] - 1)) *
            dims[0] +
          std::min(i, dims[0] - 1);
        out[(static_cast<size_t>(k) * pageDims[1] + j) * pageDims[0] + i] = values[at];
      }
  return page;
}

strata::PageCache::Page PagedPools::ReadNow(int id, int level, uint64_t index, std::string& error)
{
  const std::shared_ptr<strata::PagePoolFile> pool = this->Internals->Find(id);
  if (!pool)
  {
    error = "no page pool " + std::to_string(id);
    return nullptr;
  }
  auto page = std::make_shared<std::vector<uint8_t>>(pool->GetPageValues() * sizeof(float));
  if (!pool->ReadPage(level, index, reinterpret_cast<float*>(page->data()), &error))
  {
    return nullptr;
  }
  return page;
}

strata::PageCache::Page PagedPools::ReadRoot(int id, int level, uint64_t index, std::string& error)
{
  strata::PageCache::Page page = this->ReadNow(id, level, index, error);
  this->Stats.RootPagesRead += page ? 1 : 0;
  return page;
}

strata::PageCache::Page PagedPools::ReadPage(int id, int level, uint64_t index, std::string& error)
{
  strata::PageCache::Page page = this->ReadNow(id, level, index, error);
  this->Stats.StepPagesRead += page ? 1 : 0;
  return page;
}

void PagedPools::RetryFailedPages()
{
  this->Internals->Cache.RetryAll();
}

bool PagedPools::WaitForIdle(double seconds)
{
  return this->Internals->Cache.WaitForIdle(seconds);
}
}
