// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataVolumePager.h"

#include "StrataBrickAtlasAllocator.h"
#include "StrataBrickAtlasFormat.h"
#include "StrataCutPages.h"
#include "StrataPagePoolFile.h"
#include "StrataVolumeBrickTree.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>

namespace strata
{

class VolumePager::vtkInternals
{
public:
  /// A paged port: its pool's tree, and the pages held for the cut and its ancestors (held
  /// pages are never evicted, so a collapse always finds its parent), by node id.
  struct Paged
  {
    std::unique_ptr<strata::VolumeBrickTree> Tree;
    std::map<int, strata::PageCache::Page> Held;
    int Step = 0;        ///< the time step shown
    int PoolId = 0;      ///< its pool (GetPoolId)
    int NextPoolId = -1; ///< the step prefetched (SetNextStep), -1 none
    std::unique_ptr<strata::VolumeBrickTree> NextTree; ///< its structure and ranges
    bool Switched = false; ///< the step changed since the last Update: swap the held pages
    int PlayedStep = -1;   ///< the step FollowPlayback saw last
    int Direction = 1;     ///< of playback: the sign of the last step change
  };
  strata::PagedPools Pools;
  std::map<int, Paged> Ports;
  strata::VolumeCut Cut;
  strata::BrickAtlasAllocator Atlas;
  std::vector<Volume> Volumes; ///< of the frame, trees resolved
  int BrickSize = 0;
  double Budget = 0.0;
  strata::VolumeBrickTree::ScalarType AtlasType = strata::VolumeBrickTree::ScalarType::Float32;
  Statistics Stats;
  /// Per volume and node: the pixels that asked for detail below the node (split priority).
  std::vector<std::vector<double>> Demand;
  std::map<int, std::vector<std::array<int, 2>>> FixedCuts;
  bool FixedCutsChanged = false;

  const Paged* PagedPort(int port) const
  {
    auto it = this->Ports.find(port);
    return it == this->Ports.end() ? nullptr : &it->second;
  }
  Paged* PagedPort(int port)
  {
    auto it = this->Ports.find(port);
    return it == this->Ports.end() ? nullptr : &it->second;
  }

  /// Node of the frame's volume that a packed page id names, -1 if none.
  int NodeOf(uint32_t page, int& volume) const
  {
    volume = strata::FeedbackReduction::GetDataSet(page);
    if (volume < 0 || volume >= static_cast<int>(this->Volumes.size()))
      return -1;
    const strata::VolumeBrickTree* tree = this->Volumes[volume].Tree;
    const int level = strata::FeedbackReduction::GetLevel(page);
    if (level >= tree->GetNumberOfLevels())
      return -1;
    const int* b = tree->GetLevelBricks(level);
    const uint32_t index = strata::FeedbackReduction::GetPageIndex(page);
    if (index >= static_cast<uint32_t>(b[0]) * b[1] * b[2])
      return -1;
    return tree->GetLevelOffset(level) + static_cast<int>(index);
  }

  /// Split exactly the strict ancestors of a fixed cut's bricks, before anything else.
  strata::VolumeCut::PriorityFunction FixedPriority(const strata::VolumeBrickTree* tree,
    const std::vector<std::array<int, 2>>& bricks) const
  {
    auto split = std::make_shared<std::vector<char>>(tree->GetNumberOfNodes(), 0);
    for (const auto& b : bricks)
    {
      if (b[0] < 0 || b[0] >= tree->GetNumberOfLevels() || b[1] < 0)
        continue;
      const int* n = tree->GetLevelBricks(b[0]);
      if (b[1] >= n[0] * n[1] * n[2])
        continue;
      for (int a = tree->GetParent(tree->GetLevelOffset(b[0]) + b[1]); a >= 0 && !(*split)[a];
           a = tree->GetParent(a))
        (*split)[a] = 1;
    }
    return [split](int node, double) { return (*split)[node] ? 1e30 : 0.0; };
  }

  /// A paged brick may enter the cut only with its page in RAM: found now (and held), or
  /// requested at the node's priority for a later frame.
  strata::VolumeCut::AvailabilityFunction Availability(int port, Paged* paged)
  {
    return [this, paged](int node, double priority)
    {
      if (paged->Held.count(node))
        return true;
      const strata::PageCache::Key key = this->KeyOf(*paged, paged->PoolId, node);
      if (strata::PageCache::Page page = this->Pools.Acquire(key, priority))
      {
        paged->Held[node] = page;
        return true;
      }
      return false;
    };
  }

  static strata::PageCache::Key KeyOf(const Paged& paged, int poolId, int node)
  {
    const int level = paged.Tree->GetNode(node).Level;
    strata::PageCache::Key key;
    key.Dataset = poolId;
    key.Level = level;
    key.Page = node - paged.Tree->GetLevelOffset(level);
    return key;
  }

  /// Whether `node` of `tree` may be visible under `volume`'s transfer function: a cut leaf
  /// that was empty (and had no page) may show data in another step. With a halo a
  /// neighbour's range decides too: then every node may.
  static bool MayShow(const Volume& volume, const strata::VolumeBrickTree& tree, int node)
  {
    const auto& n = tree.GetNode(node);
    return volume.Halo || !volume.Opacity ||
           (n.SubtreeMin <= n.SubtreeMax && volume.Opacity(n.SubtreeMin, n.SubtreeMax) > 0.0);
  }

  /// The pages a step of `paged` needs for the last cut of volume `v`: the held ones, and the
  /// cut's leaves without a page that the step's `tree` may show.
  std::vector<int> StepNodes(int v, const Paged& paged, const strata::VolumeBrickTree& tree) const
  {
    std::vector<int> nodes;
    for (const auto& held : paged.Held)
      nodes.push_back(held.first);
    for (int n : this->Cut.GetCutNodes(v))
      if (!paged.Held.count(n) && MayShow(this->Volumes[v], tree, n))
        nodes.push_back(n);
    return nodes;
  }

  /// After a step switch: every page of the last cut becomes the new step's page of the same
  /// brick, from the cache (prefetched) or read here; the atlas is written again. Returns the
  /// pages read, -1 with `error` set when one cannot be.
  int SwitchSteps(std::string& error)
  {
    int read = 0;
    for (size_t v = 0; v < this->Volumes.size(); ++v)
    {
      Paged* paged = this->PagedPort(this->Volumes[v].Port);
      if (!paged || !paged->Switched || static_cast<int>(v) >= this->Cut.GetNumberOfVolumes())
        continue;
      paged->Switched = false;
      for (int node : this->StepNodes(static_cast<int>(v), *paged, *paged->Tree))
      {
        const strata::PageCache::Key key = KeyOf(*paged, paged->PoolId, node);
        strata::PageCache::Page page = this->Pools.Find(key);
        if (!page)
        {
          std::string why;
          page = this->Pools.ReadPage(key.Dataset, key.Level, static_cast<uint64_t>(key.Page), why);
          if (!page)
          {
            error = "Cannot read page " + std::to_string(key.Level) + "/" +
                    std::to_string(key.Page) + " of \"" + this->Pools.GetPoolName(key.Dataset) +
                    "\": " + why;
            return -1;
          }
          ++read;
        }
        paged->Held[node] = page;
      }
      this->Atlas.Clear(); // every resident brick holds the old step
      ++this->Stats.StepSwitches;
    }
    return read;
  }

  /// The next step's pages of the cut (StepNodes under the next step's ranges), below the
  /// demand requests: coarse levels first, so an interrupted prefetch still helps.
  void PrefetchNextSteps()
  {
    this->Stats.NextStepPagesResident = this->Stats.NextStepPagesWanted = 0;
    for (size_t v = 0; v < this->Volumes.size(); ++v)
    {
      const Paged* paged = this->PagedPort(this->Volumes[v].Port);
      if (!paged || paged->NextPoolId < 0 || !paged->NextTree)
        continue;
      for (int node : this->StepNodes(static_cast<int>(v), *paged, *paged->NextTree))
      {
        const strata::PageCache::Key key = KeyOf(*paged, paged->NextPoolId, node);
        ++this->Stats.NextStepPagesWanted;
        if (this->Pools.IsResident(key))
          ++this->Stats.NextStepPagesResident;
        else
          this->Pools.Prefetch(key, key.Level);
      }
    }
  }

  /// The cut's priority, opacity and availability of every volume for this frame.
  void Configure(const Settings& settings)
  {
    this->Cut.SetErrorThreshold(settings.Feedback ? 0.0 : settings.ErrorThreshold);
    for (size_t v = 0; v < this->Volumes.size(); ++v)
    {
      const Volume& volume = this->Volumes[v];
      const int vi = static_cast<int>(v);
      this->Cut.SetVolumeMatrix(vi, volume.IndexToWorld);
      this->Cut.SetVolumeOpacity(vi, volume.Opacity);
      this->Cut.SetVolumeHalo(vi, volume.Halo);
      if (settings.Feedback)
      {
        const std::vector<double>* demand = &this->Demand[v];
        this->Cut.SetVolumePriority(vi, [demand](int node, double) { return (*demand)[node]; });
      }
      else
      {
        this->Cut.SetVolumePriority(vi, nullptr);
      }
      const auto fixed = this->FixedCuts.find(volume.Port);
      if (fixed != this->FixedCuts.end())
      {
        this->Cut.SetVolumePriority(vi, this->FixedPriority(volume.Tree, fixed->second));
      }
      Paged* paged = this->PagedPort(volume.Port);
      this->Cut.SetVolumeAvailability(vi, paged ? this->Availability(volume.Port, paged) : nullptr);
    }
    this->Cut.SetMaxNewBricksPerUpdate(this->AnyPaged() ? settings.PagesPerFrame : 0);
  }

  bool AnyPaged() const
  {
    for (const auto& v : this->Volumes)
      if (this->Ports.count(v.Port))
        return true;
    return false;
  }

  /// Roots first, so that a volume is never a hole: the reader's coarsest level when it
  /// matches the root, else read here once.
  bool HoldRoots(std::string& error)
  {
    for (const Volume& volume : this->Volumes)
    {
      Paged* paged = this->PagedPort(volume.Port);
      const int root = paged ? paged->Tree->GetRootId() : -1;
      if (root < 0 || paged->Held.count(root))
        continue;
      const int level = paged->Tree->GetNode(root).Level;
      const int* dims = paged->Tree->GetLevelDimensions(level);
      const int B = this->BrickSize;
      int rootDims[3] = { 0, 0, 0 };
      const std::vector<float> values =
        volume.RootValues ? volume.RootValues(rootDims) : std::vector<float>();
      bool fits = !values.empty();
      for (int a = 0; a < 3; ++a)
        fits = fits && rootDims[a] == dims[a] && dims[a] <= B;
      if (fits)
      {
        const int page[3] = { B, B, B };
        paged->Held[root] = strata::PagedPools::PadRoot(values.data(), dims, page);
        ++this->Stats.RootPagesFromPipeline;
        continue;
      }
      std::string why;
      paged->Held[root] = this->Pools.ReadRoot(paged->PoolId, level, 0, why);
      if (!paged->Held[root])
      {
        paged->Held.erase(root);
        error =
          "Cannot read the root page of \"" + this->Pools.GetPoolName(paged->PoolId) + "\": " + why;
        return false;
      }
    }
    return true;
  }
};

VolumePager::VolumePager()
  : Internals(new vtkInternals)
{
}

VolumePager::~VolumePager() = default;

namespace
{
/// Two trees of the same levels, level dimensions and brick size: one cut fits both.
bool SameStructure(const strata::VolumeBrickTree& a, const strata::VolumeBrickTree& b)
{
  bool same = a.GetNumberOfNodes() == b.GetNumberOfNodes() &&
              a.GetNumberOfLevels() == b.GetNumberOfLevels() &&
              a.GetBrickSize() == b.GetBrickSize();
  for (int l = 0; same && l < a.GetNumberOfLevels(); ++l)
    same =
      std::equal(a.GetLevelDimensions(l), a.GetLevelDimensions(l) + 3, b.GetLevelDimensions(l));
  return same;
}
}

const strata::PagePoolFile* VolumePager::OpenPool(int port,
  const std::string& fileName,
  std::string& error,
  int step)
{
  vtkInternals& in = *this->Internals;
  if (port < 0 || port >= MaxChannels || step < 0 || step >= MaxSteps)
  {
    error = "port " + std::to_string(port) + " or time step " + std::to_string(step) +
            " out of range (at most " + std::to_string(MaxPorts) + " ports of " +
            std::to_string(MaxComponents) + " components and " + std::to_string(MaxSteps) +
            " steps)";
    return nullptr;
  }
  const int id = GetPoolId(port, step);
  vtkInternals::Paged* paged = in.PagedPort(port);
  const bool same = paged && paged->PoolId == id && in.Pools.GetPoolName(id) == fileName;
  std::shared_ptr<strata::PagePoolFile> file = in.Pools.OpenPool(id, fileName, error);
  if (!file)
  {
    return nullptr;
  }
  if (same)
  {
    return file.get();
  }
  if (file->GetKind() != strata::PagePoolFormat::Kind::BrickPool)
  {
    error = "not a brick pool";
    return nullptr;
  }
  auto tree = std::make_unique<strata::VolumeBrickTree>();
  if (!strata::PagedPools::BuildTree(*file, *tree))
  {
    error = "the pool \"" + fileName + "\" does not match its brick tree";
    return nullptr;
  }
  if (paged && paged->Step != step && SameStructure(*paged->Tree, *tree))
  {
    // Another step of the series: the same cut, the new ranges in the same tree (the cut
    // keeps its pointer), the held pages swapped at the next Update.
    strata::PagedPools::BuildTree(*file, *paged->Tree);
    paged->Step = step;
    paged->PoolId = id;
    paged->Switched = true;
    return file.get();
  }
  vtkInternals::Paged& p = in.Ports[port];
  p.Tree = std::move(tree);
  p.Held.clear();
  p.Step = step;
  p.PoolId = id;
  p.NextPoolId = -1;
  p.Switched = false;
  this->CutValid = false;
  return file.get();
}

bool VolumePager::SetNextStep(int port, int step, const std::string& fileName, std::string& error)
{
  vtkInternals& in = *this->Internals;
  vtkInternals::Paged* paged = in.PagedPort(port);
  if (!paged)
    return step < 0;
  const int id = step >= 0 && step < MaxSteps ? GetPoolId(port, step) : -1;
  if (id >= 0 && id == paged->NextPoolId && in.Pools.GetPoolName(id) == fileName)
    return true; // checked before
  paged->NextPoolId = -1;
  if (step < 0 || step == paged->Step)
    return true;
  if (id < 0)
  {
    error = "time step " + std::to_string(step) + " out of range";
    return false;
  }
  std::shared_ptr<strata::PagePoolFile> file = in.Pools.OpenPool(id, fileName, error);
  if (!file)
    return false;
  auto tree = std::make_unique<strata::VolumeBrickTree>();
  if (file->GetKind() != strata::PagePoolFormat::Kind::BrickPool ||
      !strata::PagedPools::BuildTree(*file, *tree) || !SameStructure(*tree, *paged->Tree))
  {
    error = "the pool \"" + fileName + "\" of step " + std::to_string(step) +
            " does not have the structure of the step shown";
    return false;
  }
  paged->NextPoolId = id;
  paged->NextTree = std::move(tree);
  return true;
}

int VolumePager::FollowPlayback(int port, int step, int steps)
{
  vtkInternals::Paged* paged = this->Internals->PagedPort(port);
  if (!paged || steps < 2)
    return -1;
  if (paged->PlayedStep >= 0 && step != paged->PlayedStep)
  {
    int change = step - paged->PlayedStep;
    if (2 * std::abs(change) > steps)
      change += change > 0 ? -steps : steps;
    paged->Direction = change > 0 ? 1 : -1;
  }
  paged->PlayedStep = step;
  return ((step + paged->Direction) % steps + steps) % steps;
}

void VolumePager::ClosePool(int port)
{
  vtkInternals& in = *this->Internals;
  if (port < 0 || port >= MaxChannels)
    return;
  for (int step = 0; step < MaxSteps; ++step)
    in.Pools.ClosePool(GetPoolId(port, step));
  if (in.Ports.erase(port) > 0)
    this->CutValid = false;
}

const strata::PagePoolFile* VolumePager::GetPool(int port) const
{
  auto it = this->Internals->Ports.find(port);
  return it == this->Internals->Ports.end() ? nullptr
                                            : this->Internals->Pools.GetPool(it->second.PoolId);
}

const strata::VolumeBrickTree* VolumePager::GetPoolTree(int port) const
{
  auto it = this->Internals->Ports.find(port);
  return it == this->Internals->Ports.end() ? nullptr : it->second.Tree.get();
}

bool VolumePager::SetVolumes(const std::vector<Volume>& volumes,
  int brickSize,
  double budgetMiB,
  int maxTextureSize,
  bool& rebuilt,
  std::string& error)
{
  vtkInternals& in = *this->Internals;
  std::vector<Volume> resolved = volumes;
  std::vector<strata::VolumeBrickTree::ScalarType> types;
  for (Volume& v : resolved)
  {
    if (const strata::VolumeBrickTree* tree = this->GetPoolTree(v.Port))
      v.Tree = tree;
    types.push_back(v.Tree->GetScalarType());
  }
  const auto atlasType = strata::BrickAtlasFormat::Choose(types, this->AtlasStorage);
  bool same = this->CutValid && resolved.size() == in.Volumes.size() && brickSize == in.BrickSize &&
              budgetMiB == in.Budget && atlasType == in.AtlasType;
  for (size_t v = 0; same && v < resolved.size(); ++v)
    same = resolved[v].Port == in.Volumes[v].Port && resolved[v].Tree == in.Volumes[v].Tree;
  in.Volumes = std::move(resolved);
  rebuilt = !same;
  if (same)
  {
    return true;
  }
  // No larger than every brick of every level: small scenes do not pay for the whole budget.
  double allBricks = 0.0;
  for (const Volume& v : in.Volumes)
    allBricks += v.Tree->GetNumberOfNodes();
  const int texel = strata::BrickAtlasFormat::GetTexelSize(atlasType);
  const double brickMiB = std::pow(double(brickSize), 3) * texel / (1024.0 * 1024.0);
  const double budget = std::min(budgetMiB, (allBricks + 0.5) * brickMiB);
  if (!in.Atlas.InitializeFromBudget(budget, brickSize, texel, std::min(maxTextureSize, 2048)))
  {
    std::ostringstream msg;
    msg << "An atlas budget of " << budgetMiB << " MB holds no brick of " << brickSize << "^3 "
        << strata::BrickAtlasFormat::GetName(atlasType) << " voxels.";
    error = msg.str();
    this->CutValid = false;
    return false;
  }
  in.AtlasType = atlasType;
  in.Cut.RemoveAllVolumes();
  for (const Volume& v : in.Volumes)
    in.Cut.AddVolume(v.Tree, v.IndexToWorld);
  in.Cut.SetBudget(in.Atlas.GetNumberOfSlots());
  in.BrickSize = brickSize;
  in.Budget = budgetMiB;
  for (auto& p : in.Ports)
    p.second.Held.clear(); // a new cut starts from the roots
  in.Demand.clear();
  this->CutValid = true;
  return true;
}

int VolumePager::GetNumberOfVolumes() const
{
  return static_cast<int>(this->Internals->Volumes.size());
}

int VolumePager::GetVolumeOf(int port) const
{
  const vtkInternals& in = *this->Internals;
  for (size_t v = 0; v < in.Volumes.size(); ++v)
    if (in.Volumes[v].Port == port && static_cast<int>(v) < in.Cut.GetNumberOfVolumes())
      return static_cast<int>(v);
  return -1;
}

bool VolumePager::PrepareDemand(bool feedback, bool moved)
{
  vtkInternals& in = *this->Internals;
  if (!feedback)
  {
    in.Demand.clear();
    return true;
  }
  bool fresh = false;
  if (in.Demand.size() != in.Volumes.size())
  {
    in.Demand.resize(in.Volumes.size());
    for (size_t v = 0; v < in.Volumes.size(); ++v)
      in.Demand[v].assign(in.Volumes[v].Tree->GetNumberOfNodes(), 0.0);
    fresh = true; // feedback written for another cut
  }
  if (moved)
  {
    for (auto& d : in.Demand)
      for (double& x : d)
        x *= 0.5;
  }
  return fresh;
}

void VolumePager::AddFeedback(const std::vector<strata::FeedbackReduction::Entry>& asked)
{
  vtkInternals& in = *this->Internals;
  std::vector<strata::FeedbackReduction::Entry> below = asked;
  strata::FeedbackReduction::PropagateToAncestors(below,
    [&in](uint32_t page)
    {
      int v = -1;
      const int node = in.NodeOf(page, v);
      const strata::VolumeBrickTree* tree = node < 0 ? nullptr : in.Volumes[v].Tree;
      const int parent = tree ? tree->GetParent(node) : -1;
      if (parent < 0)
        return strata::FeedbackReduction::NoPage;
      const int level = tree->GetNode(parent).Level;
      return strata::FeedbackReduction::PackPage(
        v, level, static_cast<uint32_t>(parent - tree->GetLevelOffset(level)));
    });
  // A node's demand: the pixels that asked for a page strictly below it. Both lists are
  // sorted by page id: one merge subtracts the node's own requests.
  auto own = asked.begin();
  for (const auto& e : below)
  {
    while (own != asked.end() && own->Page < e.Page)
      ++own;
    const uint32_t self = own != asked.end() && own->Page == e.Page ? own->Coverage : 0;
    int v = -1;
    const int node = in.NodeOf(e.Page, v);
    if (node >= 0 && v < static_cast<int>(in.Demand.size()))
    {
      double& d = in.Demand[v][node];
      d = std::max(d, static_cast<double>(e.Coverage - self));
    }
  }
  long long pixels = 0;
  for (const auto& e : asked)
    pixels += e.Coverage;
  in.Stats.FeedbackPages = static_cast<int>(asked.size());
  in.Stats.FeedbackPixels = static_cast<int>(pixels);
}

int VolumePager::Update(const strata::VolumeCut::Camera& camera,
  const Settings& settings,
  bool feedbackCurrent,
  std::vector<strata::VolumeCut::Upload>& uploads,
  std::string& error)
{
  vtkInternals& in = *this->Internals;
  uploads.clear();
  if (settings.Feedback && in.Demand.size() != in.Volumes.size())
  {
    this->PrepareDemand(true, false);
  }
  in.Configure(settings);
  const bool paged = in.AnyPaged();
  int switched = 0;
  bool waited = false;
  if (paged)
  {
    in.Pools.SetCacheBudgetMiB(settings.CacheBudgetMiB);
    in.Pools.SetPagesPerFrame(settings.PagesPerFrame);
    in.Pools.SetPrefetch(settings.Prefetch);
    in.Pools.BeginFrame();
    // The pages the cut holds stay pinned in the cache: leave room there for the loads.
    in.Cut.SetPageBudget(in.Pools.PlanHeldPages(in.Atlas.GetNumberOfSlots(), 8));
    const int readBefore = in.Pools.GetStatistics().RootPagesRead;
    switched = in.SwitchSteps(error);
    if (switched < 0 || !in.HoldRoots(error))
      return -1;
    waited = switched > 0 || in.Pools.GetStatistics().RootPagesRead > readBefore;
  }
  else
  {
    in.Cut.SetPageBudget(0);
  }
  if (in.FixedCutsChanged)
  {
    in.Cut.Reset(); // a fixed cut may be coarser than the cut: start from the roots
    in.FixedCutsChanged = false;
  }
  const int entered = in.Cut.Update(camera);
  if (paged)
  {
    // Keep the pages of the cut and of its ancestors (for collapses), release the rest.
    for (size_t v = 0; v < in.Volumes.size(); ++v)
      if (vtkInternals::Paged* p = in.PagedPort(in.Volumes[v].Port))
        strata::CutPages::Prune(p->Held, in.Cut, static_cast<int>(v), *p->Tree);
    in.PrefetchNextSteps();
    in.Pools.EndFrame();
    static_cast<strata::PagedPools::Statistics&>(in.Stats) = in.Pools.GetStatistics();
    // The cache's reads plus the root pages, read here or by the readers, a page of floats each.
    in.Stats.BytesRead +=
      (in.Stats.RootPagesRead + in.Stats.StepPagesRead + in.Stats.RootPagesFromPipeline) *
      static_cast<long long>(std::pow(in.BrickSize, 3) * sizeof(float));
    in.Stats.IoWaitFrames += waited ? 1 : 0;
    in.Stats.Converged = entered == 0 && in.Stats.MissesThisFrame == 0 &&
                         in.Stats.PendingPages == 0 && (!settings.Feedback || feedbackCurrent);
  }
  in.Atlas.BeginFrame();
  return in.Cut.AssignSlots(in.Atlas, uploads);
}

const float* VolumePager::GetBrick(const strata::VolumeCut::Upload& upload,
  std::vector<float>& scratch) const
{
  const vtkInternals& in = *this->Internals;
  const Volume& volume = in.Volumes[upload.Volume];
  if (volume.Tree->HasData())
  {
    scratch.resize(static_cast<size_t>(in.BrickSize) * in.BrickSize * in.BrickSize);
    volume.Tree->ExtractBrick(upload.Node, scratch.data());
    return scratch.data();
  }
  auto paged = in.Ports.find(volume.Port);
  if (paged == in.Ports.end())
    return nullptr;
  auto it = paged->second.Held.find(upload.Node);
  return it == paged->second.Held.end() ? nullptr
                                        : reinterpret_cast<const float*>(it->second->data());
}

void VolumePager::BuildIndexTable(int volume, std::vector<uint16_t>& table) const
{
  this->Internals->Cut.BuildIndexTable(volume, this->Internals->Atlas, table);
}

const strata::VolumeBrickTree* VolumePager::GetTree(int volume) const
{
  return this->Internals->Volumes[volume].Tree;
}

strata::VolumeBrickTree::ScalarType VolumePager::GetAtlasType() const
{
  return this->Internals->AtlasType;
}

strata::VolumeBrickTree::ScalarType VolumePager::GetVolumeType(int volume) const
{
  return this->Internals->Volumes[volume].Tree->GetScalarType();
}

const strata::BrickAtlasAllocator& VolumePager::GetAtlas() const
{
  return this->Internals->Atlas;
}

const strata::VolumeCut& VolumePager::GetCut() const
{
  return this->Internals->Cut;
}

void VolumePager::SetFixedCut(int port, const std::vector<std::array<int, 2>>& bricks)
{
  this->Internals->FixedCuts[port] = bricks;
  this->Internals->FixedCutsChanged = true;
}

void VolumePager::RemoveAllFixedCuts()
{
  if (this->Internals->FixedCuts.empty())
    return;
  this->Internals->FixedCuts.clear();
  this->Internals->FixedCutsChanged = true;
}

bool VolumePager::HasFixedCuts() const
{
  return !this->Internals->FixedCuts.empty();
}

std::vector<std::array<int, 2>> VolumePager::GetCutBricks(int port) const
{
  const vtkInternals& in = *this->Internals;
  std::vector<std::array<int, 2>> bricks;
  const int v = this->GetVolumeOf(port);
  if (v < 0)
    return bricks;
  const strata::VolumeBrickTree* tree = in.Volumes[v].Tree;
  for (int n : in.Cut.GetCutNodes(v))
  {
    const int level = tree->GetNode(n).Level;
    bricks.push_back({ level, n - tree->GetLevelOffset(level) });
  }
  return bricks;
}

std::vector<int> VolumePager::GetResidentBricksPerLevel(int port) const
{
  const vtkInternals& in = *this->Internals;
  std::vector<int> counts;
  const int v = this->GetVolumeOf(port);
  if (v < 0)
    return counts;
  const strata::VolumeBrickTree* tree = in.Volumes[v].Tree;
  counts.assign(tree->GetNumberOfLevels(), 0);
  for (int n : in.Cut.GetCutNodes(v))
    counts[tree->GetNode(n).Level] += in.Cut.IsEmpty(v, n) ? 0 : 1;
  return counts;
}

std::vector<std::string> VolumePager::TakeNewFailures()
{
  std::vector<std::string> messages;
  for (const auto& f : this->Internals->Pools.TakeNewFailures())
  {
    const int channel = f.PageKey.Dataset % MaxChannels, step = f.PageKey.Dataset / MaxChannels;
    const int port = channel % MaxPorts, component = channel / MaxPorts;
    messages.push_back("Page " + std::to_string(f.PageKey.Level) + "/" +
                       std::to_string(f.PageKey.Page) + " of the volume on port " +
                       std::to_string(port) +
                       (component ? " (component " + std::to_string(component) + ")" : "") +
                       (step ? " (time step " + std::to_string(step) + ")" : std::string()) +
                       " failed to load (" + f.Error + ")");
  }
  this->Internals->Stats.Failures = this->Internals->Pools.GetStatistics().Failures;
  return messages;
}

VolumePager::Statistics VolumePager::GetStatistics() const
{
  return this->Internals->Stats;
}

void VolumePager::RetryFailedPages()
{
  this->Internals->Pools.RetryFailedPages();
}

std::string VolumePager::TakeBudgetWarning()
{
  return this->Internals->Pools.TakeBudgetWarning();
}

bool VolumePager::WaitForIdle(double seconds)
{
  return this->Internals->Pools.WaitForIdle(seconds);
}
}
