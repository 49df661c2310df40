// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Paging makes progress at every pair of budgets (issue: cache livelock). The pagers hold the
// page of every cut node and of every ancestor of one, pinned in the RAM cache; with an atlas
// budget at or above the cache's, those pages fill the cache, every new load is dropped for
// want of room, asked again and read again each frame, and the cut never refines (the soak
// measured 2025 MB read in 2000 frames and no level-0 tile). Here the horizon pager and the
// volume pager run a camera that wants every page at level 0 from one pose and then another,
// under a cache no larger than the atlas, GL-free, waiting for the cache's workers after each
// frame. Asserted:
// - the cut converges at each pose within FrameCap frames and shows level-0 pages;
// - bytes read over both poses stay under ReadBound times the pool's pages: each page is read
//   about once; the bound leaves room for pages evicted after a collapse and read again later
//   (unfixed, the livelock read 112 and 171 times the pools in 2 x FrameCap frames);
// - the inconsistent budgets are reported once, and consistent ones are not (and converge).
#include "StrataHeightFieldPager.h"
#include "StrataPagePoolFile.h"
#include "StrataPagePoolWriter.h"
#include "StrataSubTests.h"
#include "StrataTestPaths.h"
#include "StrataVolumePager.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
const int FrameCap = 300;
const double ReadBound = 2.0;
int Failures = 0;

void Check(bool ok, const std::string& what)
{
  std::printf("  [%s] %s\n", ok ? " ok " : "FAIL", what.c_str());
  if (!ok)
  {
    ++Failures;
  }
}

// A pool of float values v(i, j, k) written by the core's writer: `dims` points, page `b`.
std::string WritePool(const std::string& path,
  strata::PagePoolFormat::Kind kind,
  const int dims[3],
  int b)
{
  strata::PagePoolWriter writer;
  writer.SetFileName(path);
  writer.SetKind(kind);
  writer.SetScalarType(strata::PagePoolFormat::ScalarType::Float32);
  writer.SetDimensions(dims[0], dims[1], dims[2]);
  writer.SetPageSize(b);
  writer.SetSource(
    [dims, kind](int first, int count, void* buffer)
    {
      // Bricks: slices [first, first + count) of rows; tiles: per layer, rows [first, ...).
      const bool tiles = kind == strata::PagePoolFormat::Kind::TilePool;
      const int outer = tiles ? dims[2] : count, rows = tiles ? count : dims[1];
      float* out = static_cast<float*>(buffer);
      for (int s = 0; s < outer; ++s)
        for (int r = 0; r < rows; ++r)
          for (int i = 0; i < dims[0]; ++i)
          {
            const int j = tiles ? first + r : r, k = tiles ? s : first + s;
            *out++ = static_cast<float>(10.0 * std::sin(0.05 * i) * std::cos(0.07 * j) + k);
          }
      return true;
    });
  Check(writer.Write(), "pool " + path + " written " + writer.GetErrorMessage());
  return path;
}

double PoolBytes(const std::string& path)
{
  strata::PagePoolFile pool;
  if (!pool.Open(path))
    return 0.0;
  return static_cast<double>(pool.GetNumberOfPages()) * pool.GetPageValues() * sizeof(float);
}

using Pose = std::array<double, 3>; ///< a camera position, looking at everything

struct Outcome
{
  int Frames = -1; ///< frames the slowest pose took to converge, -2 if one did not
  long long BytesRead = 0;
  int Finest = 0; ///< level-0 pages shown
  int Cut = 0;
  std::vector<std::string> Warnings; ///< TakeBudgetWarning()'s, over all frames
};

void Report(const char* what, const Outcome& o, double poolBytes)
{
  std::printf(
    "%s: converged at each pose by frame %d, %.2f MB read (%.2f x the pool's %.2f MB), cut %d "
    "pages, %d at level 0\n",
    what,
    o.Frames,
    o.BytesRead / 1048576.0,
    o.BytesRead / poolBytes,
    poolBytes / 1048576.0,
    o.Cut,
    o.Finest);
}

void CheckOutcome(const Outcome& o, double poolBytes, bool consistent)
{
  for (const std::string& w : o.Warnings)
    std::printf("  warning: %s\n", w.c_str());
  Check(o.Warnings.size() == (consistent ? 0u : 1u),
    consistent ? "consistent budgets: no warning" : "inconsistent budgets: one warning");
  Check(o.Frames >= 0, "converged at each pose within " + std::to_string(FrameCap) + " frames");
  Check(o.Finest > 0, "level-0 pages shown");
  Check(o.BytesRead <= ReadBound * poolBytes,
    "bytes read within " + std::to_string(ReadBound) + " x the pool's pages");
}

// A 1025^2 horizon in tiles of 33^2 (1024 at level 0, 1365 in all, 4356 bytes each) seen from
// close above its middle, then a corner: every tile wants level 0, those below most.
Outcome RunHorizons(const std::string& pool, int slots, double cacheMiB)
{
  strata::HeightFieldPager pager;
  strata::HeightFieldPager::Source source;
  source.FileName = pool;
  Check(pager.Open({ source }), "horizon pool opened " + pager.GetErrorMessage());
  pager.SetAtlasSlots(slots);
  pager.SetCacheBudgetMiB(cacheMiB);
  pager.SetPagesPerFrame(64);
  const double gridToWorld[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  Outcome o;
  std::vector<strata::HeightFieldPager::Upload> uploads;
  for (const Pose& pose : { Pose{ 512, 512, 100 }, Pose{ 100, 900, 60 } })
  {
    strata::VolumeCut::Camera camera;
    std::copy_n(pose.data(), 3, camera.Position);
    camera.PixelsPerRadian = 1e5;
    int converged = -1;
    for (int f = 0; f < FrameCap && converged < 0; ++f)
    {
      pager.Update(camera, gridToWorld, uploads);
      converged = pager.GetStatistics().Converged ? f : -1;
      const std::string warning = pager.TakeBudgetWarning();
      if (!warning.empty())
        o.Warnings.push_back(warning);
      pager.WaitForIdle(10.0);
    }
    o.Frames = converged < 0 || o.Frames < -1 ? -2 : std::max(o.Frames, converged);
  }
  const strata::HeightFieldPager::Statistics s = pager.GetStatistics();
  o.BytesRead = s.BytesRead;
  o.Finest = s.FinestTiles;
  o.Cut = s.CutTiles;
  return o;
}

// A 64^3 volume in bricks of 8^3 (1000 at level 0, 1161 in all, 2048 bytes each) seen from
// just off a corner, then the opposite one: every brick wants level 0, those near most.
Outcome RunVolumes(const std::string& pool, double atlasMiB, double cacheMiB)
{
  strata::VolumePager pager;
  std::string error;
  Check(pager.OpenPool(0, pool, error) != nullptr, "volume pool opened " + error);
  strata::VolumePager::Volume volume;
  volume.Port = 0;
  bool rebuilt = false;
  Check(pager.SetVolumes({ volume }, 8, atlasMiB, 2048, rebuilt, error), "volumes set " + error);
  strata::VolumePager::Settings settings;
  settings.CacheBudgetMiB = cacheMiB;
  settings.PagesPerFrame = 64;
  Outcome o;
  std::vector<strata::VolumeCut::Upload> uploads;
  for (const Pose& pose : { Pose{ -4, -4, -4 }, Pose{ 68, 68, 68 } })
  {
    strata::VolumeCut::Camera camera;
    std::copy_n(pose.data(), 3, camera.Position);
    camera.PixelsPerRadian = 1e5;
    int converged = -1;
    for (int f = 0; f < FrameCap && converged < 0; ++f)
    {
      if (pager.Update(camera, settings, true, uploads, error) < 0)
        Check(false, "frame " + std::to_string(f) + ": " + error);
      converged = pager.GetStatistics().Converged ? f : -1;
      const std::string warning = pager.TakeBudgetWarning();
      if (!warning.empty())
        o.Warnings.push_back(warning);
      pager.WaitForIdle(10.0);
    }
    o.Frames = converged < 0 || o.Frames < -1 ? -2 : std::max(o.Frames, converged);
  }
  o.BytesRead = pager.GetStatistics().BytesRead;
  const std::vector<int> levels = pager.GetResidentBricksPerLevel(0);
  o.Finest = levels.empty() ? 0 : levels[0];
  o.Cut = pager.GetCut().GetCost();
  return o;
}
}

// ClosePool forgets a paged port (its pool and tree: an in-core volume may take the port), and
// the port opens again as new.
void ClosePool(const std::string& pool)
{
  strata::VolumePager pager;
  std::string error;
  Check(pager.OpenPool(0, pool, error) != nullptr && pager.GetPoolTree(0) != nullptr,
    "the pool opens " + error);
  pager.ClosePool(0);
  pager.ClosePool(5); // never opened: nothing to do
  Check(pager.GetPool(0) == nullptr && pager.GetPoolTree(0) == nullptr,
    "ClosePool forgets the port's pool and tree");
  Check(pager.OpenPool(0, pool, error) != nullptr && pager.GetPoolTree(0) != nullptr,
    "the port opens again " + error);
}

int TestPagingBudgets(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string stem = paths.Output + "/TestPagingBudgets-" + std::to_string(::getpid());
  const int tileDims[3] = { 1025, 1025, 1 };
  const std::string tiles =
    WritePool(stem + "-h.spp", strata::PagePoolFormat::Kind::TilePool, tileDims, 33);
  const int brickDims[3] = { 64, 64, 64 };
  const std::string bricks =
    WritePool(stem + "-v.spp", strata::PagePoolFormat::Kind::BrickPool, brickDims, 8);
  const double tileBytes = PoolBytes(tiles), brickBytes = PoolBytes(bricks);

  const int result = strata_test::RunSubTests(
    {
      { "ClosePool", [&] { ClosePool(bricks); } },
      { "HorizonsAtlasAtCache",
        [&]
        {
          // 240 slots of 4356 bytes: the atlas is as large as the 1 MB cache.
          const Outcome o = RunHorizons(tiles, 240, 1.0);
          Report("horizons, 1 MB atlas, 1 MB cache", o, tileBytes);
          CheckOutcome(o, tileBytes, false);
        } },
      { "HorizonsConsistent",
        [&]
        {
          const Outcome o = RunHorizons(tiles, 240, 8.0);
          Report("horizons, 1 MB atlas, 8 MB cache", o, tileBytes);
          CheckOutcome(o, tileBytes, true);
        } },
      { "VolumesAtlasAtCache",
        [&]
        {
          // 128 slots of 2048 bytes, as large as the cache.
          const Outcome o = RunVolumes(bricks, 0.25, 0.25);
          Report("volumes, 0.25 MB atlas, 0.25 MB cache", o, brickBytes);
          CheckOutcome(o, brickBytes, false);
        } },
      { "VolumesConsistent",
        [&]
        {
          const Outcome o = RunVolumes(bricks, 0.25, 4.0);
          Report("volumes, 0.25 MB atlas, 4 MB cache", o, brickBytes);
          CheckOutcome(o, brickBytes, true);
        } },
    },
    [] { return Failures; });
  std::remove(tiles.c_str());
  std::remove(bricks.c_str());
  std::printf("%s: %d failure(s)\n", Failures ? "FAILED" : "PASSED", Failures);
  return result;
}
