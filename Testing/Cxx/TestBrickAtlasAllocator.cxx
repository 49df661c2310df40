// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Atlas slot layouts from budgets, LRU order, pinning of the current frame's bricks, and a
// long random run against a plain reference LRU (no slot handed out twice, exact counts).
#include "StrataBrickAtlasAllocator.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <list>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "  ok   " : "  FAIL ") << what << "\n";
  failures += ok ? 0 : 1;
}

using Key = strata::BrickAtlasAllocator::Key;
Key K(int volume, int level, int64_t brick)
{
  Key k;
  k.Volume = volume;
  k.Level = level;
  k.Brick = brick;
  return k;
}

std::string Num(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

void CheckLayout(double mib, int B, int bpv, int maxTex, int x, int y, int z, const char* why)
{
  const auto l = strata::BrickAtlasAllocator::ComputeLayout(mib, B, bpv, maxTex);
  Check(l[0] == x && l[1] == y && l[2] == z,
    Num(mib) + " MiB, B=" + std::to_string(B) + ", " + std::to_string(bpv) +
      " B/voxel, max texture " + std::to_string(maxTex) + " -> " + std::to_string(l[0]) + "x" +
      std::to_string(l[1]) + "x" + std::to_string(l[2]) + " slots (" + why + ")");
}
}

int TestBrickAtlasAllocator(int, char*[])
{
  std::cout << "Layouts (slots = floor(budget / brick bytes), each axis <= max texture / B)\n";
  CheckLayout(512, 64, 1, 2048, 16, 16, 8, "the paper's 512 MiB of 64^3 8-bit bricks: 2048");
  CheckLayout(64, 32, 2, 2048, 16, 8, 8, "1024 slots, the most cubic of the exact factorings");
  CheckLayout(100, 64, 4, 2048, 5, 5, 4, "1 MiB bricks: 100");
  CheckLayout(1, 32, 4, 2048, 2, 2, 2, "128 KiB bricks: 8");
  CheckLayout(7 * 4096 / 1048576.0, 16, 1, 2048, 7, 1, 1, "7 is prime: one row");
  CheckLayout(13 * 4096 / 1048576.0, 16, 1, 64, 3, 2, 2, "13 wanted, 4 per axis: 12 fit");
  CheckLayout(1e6, 64, 4, 2048, 32, 32, 32, "capped by the texture size");
  CheckLayout(0.1, 64, 1, 2048, 0, 0, 0, "less than one brick");

  strata::BrickAtlasAllocator atlas;
  Check(!atlas.InitializeFromBudget(0.1, 64, 1) && atlas.GetNumberOfSlots() == 0,
    "a budget below one brick gives no atlas");
  Check(atlas.InitializeFromBudget(1, 32, 4) && atlas.GetNumberOfSlots() == 8 &&
          atlas.GetTextureSize()[0] == 64 && atlas.GetSlotPosition(5)[0] == 1 &&
          atlas.GetSlotPosition(5)[1] == 0 && atlas.GetSlotPosition(5)[2] == 1,
    "8 slots, texture 64^3, slot 5 at (1,0,1)");

  std::cout << "LRU order and pinning (4 slots)\n";
  atlas.Initialize(2, 2, 1, 8);
  atlas.BeginFrame(); // frame 1: A B C D fill the free slots in order
  bool fill = true;
  for (int b = 0; b < 4; ++b)
  {
    const auto r = atlas.Request(K(0, 0, b));
    fill = fill && r.Slot == b && !r.Hit && !r.Evicted;
  }
  Check(fill && atlas.GetNumberOfPinnedSlots() == 4, "four misses take the free slots 0..3");
  const auto full = atlas.Request(K(0, 0, 9));
  Check(full.Slot == -1 && atlas.Find(K(0, 0, 9)) == -1,
    "a fifth brick in the same frame gets no slot: all four are pinned");
  atlas.BeginFrame(); // frame 2: C and A used again
  const auto c = atlas.Request(K(0, 0, 2));
  const auto a = atlas.Request(K(0, 0, 0));
  const auto again = atlas.Request(K(0, 0, 0));
  Check(c.Hit && c.Slot == 2 && a.Hit && a.Slot == 0 && again.Hit &&
          atlas.GetNumberOfPinnedSlots() == 2 && atlas.IsPinned(0) && !atlas.IsPinned(1),
    "hits keep their slots; a second request of a pinned brick pins nothing new");
  atlas.BeginFrame(); // frame 3: new bricks evict B, D (frame 1), then C, A (frame 2)
  std::vector<int64_t> evictedOrder;
  std::vector<int> slotOrder;
  for (int b = 10; b < 14; ++b)
  {
    const auto r = atlas.Request(K(1, 2, b));
    evictedOrder.push_back(r.Evicted ? r.EvictedKey.Brick : -1);
    slotOrder.push_back(r.Slot);
  }
  Check(evictedOrder == std::vector<int64_t>({ 1, 3, 2, 0 }) &&
          slotOrder == std::vector<int>({ 1, 3, 2, 0 }),
    "evictions in LRU order: B, D (last used frame 1), then C, A (frame 2)");
  const auto none = atlas.Request(K(1, 2, 99));
  Check(none.Slot == -1 && atlas.Find(K(1, 2, 10)) == 1 && atlas.Find(K(0, 0, 0)) == -1,
    "bricks requested this frame are never evicted");
  const auto& st = atlas.GetStatistics();
  Check(st.Hits == 3 && st.Misses == 10 && st.Evictions == 4 && st.Failures == 2,
    "statistics: 3 hits, 10 misses, 4 evictions, 2 failures");

  atlas.BeginFrame();
  atlas.Release(K(1, 2, 12));
  const auto reuse = atlas.Request(K(2, 0, 0));
  Check(reuse.Slot == 2 && !reuse.Evicted, "a released slot is reused before any eviction");
  atlas.ReleaseVolume(1);
  Check(atlas.GetNumberOfUsedSlots() == 1 && atlas.Find(K(1, 2, 10)) == -1,
    "releasing a volume frees all its slots");
  strata::BrickAtlasAllocator::Key held;
  Check(atlas.GetSlotKey(2, held) && held == K(2, 0, 0) && !atlas.GetSlotKey(1, held),
    "slot keys: slot 2 holds (2,0,0), slot 1 is free");

  std::cout << "Random run against a reference LRU (64 slots, 300 keys, 400 frames)\n";
  atlas.Initialize(4, 4, 4, 16);
  std::list<Key> reference; // most recently used at the back
  std::map<std::tuple<int, int, int64_t>, int> residentSlot;
  auto tup = [](const Key& k) { return std::make_tuple(k.Volume, k.Level, k.Brick); };
  std::mt19937 rng(7);
  int64_t hits = 0, misses = 0, evictions = 0;
  bool unique = true, pinnedKept = true, neverFailed = true, sameAsReference = true;
  for (int frame = 0; frame < 400; ++frame)
  {
    atlas.BeginFrame();
    // A working set that drifts, as a moving camera's cut does, at most 64 distinct keys.
    std::set<std::tuple<int, int, int64_t>> thisFrame;
    const int n = 20 + static_cast<int>(rng() % 45);
    const int center = (frame * 3) % 300;
    for (int q = 0; q < n; ++q)
    {
      const int id = (center + static_cast<int>(rng() % 80)) % 300;
      const Key key = K(id % 3, id % 5, id);
      if (thisFrame.size() == 64 && !thisFrame.count(tup(key)))
        continue;
      thisFrame.insert(tup(key));
      const auto r = atlas.Request(key);
      neverFailed = neverFailed && r.Slot >= 0;
      // Reference LRU.
      auto it = std::find(reference.begin(), reference.end(), key);
      const bool refHit = it != reference.end();
      if (refHit)
        reference.erase(it);
      else if (reference.size() == 64)
      {
        sameAsReference = sameAsReference && r.Evicted && r.EvictedKey == reference.front();
        reference.pop_front();
        ++evictions;
      }
      reference.push_back(key);
      hits += refHit;
      misses += !refHit;
      sameAsReference = sameAsReference && r.Hit == refHit;
      if (r.Evicted)
      {
        pinnedKept = pinnedKept && !thisFrame.count(tup(r.EvictedKey));
        residentSlot.erase(tup(r.EvictedKey));
      }
      if (r.Slot >= 0)
      {
        if (!r.Hit)
        {
          for (const auto& e : residentSlot)
            unique = unique && e.second != r.Slot;
        }
        residentSlot[tup(key)] = r.Slot;
      }
    }
    for (const auto& e : residentSlot)
    {
      strata::BrickAtlasAllocator::Key k;
      unique =
        unique && atlas.GetSlotKey(e.second, k) && tup(k) == e.first && atlas.Find(k) == e.second;
    }
  }
  const auto& rs = atlas.GetStatistics();
  Check(unique, "no slot handed out twice: every resident key has its own slot, both ways");
  Check(pinnedKept, "no eviction ever hit a brick requested in the same frame");
  Check(neverFailed, "<= 64 distinct bricks per frame always get a slot");
  Check(sameAsReference && rs.Hits == hits && rs.Misses == misses && rs.Evictions == evictions,
    "hits/misses/evictions equal a reference LRU: " + std::to_string(rs.Hits) + "/" +
      std::to_string(rs.Misses) + "/" + std::to_string(rs.Evictions));

  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
