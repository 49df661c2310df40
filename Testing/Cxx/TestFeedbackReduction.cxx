// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Feedback buffer reduction: page id packing, the CPU reduction against a plain std::map count,
// the OpenCL reduction against the CPU one (identical lists) on random, coherent and
// adversarial buffers, ancestor propagation, and the time of both at 480x270 (a quarter of
// 1920x1080 per axis, the feedback size of the stacked height-field paper).
#include "StrataFeedbackReduction.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "  ok   " : "  FAIL ") << what << "\n";
  failures += ok ? 0 : 1;
}

using Entry = strata::FeedbackReduction::Entry;
using Buffer = std::vector<uint32_t>;

std::vector<Entry> Reference(const Buffer& b)
{
  std::map<uint32_t, uint32_t> m;
  for (uint32_t id : b)
  {
    if (id != strata::FeedbackReduction::NoPage)
    {
      ++m[id];
    }
  }
  std::vector<Entry> list;
  for (const auto& kv : m)
  {
    list.push_back(Entry{ kv.first, kv.second });
  }
  return list;
}

std::string Describe(const std::vector<Entry>& a, const std::vector<Entry>& b)
{
  std::ostringstream os;
  os << a.size() << " vs " << b.size() << " entries";
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
  {
    if (a[i] != b[i])
    {
      os << ", first difference at " << i << ": (" << a[i].Page << "," << a[i].Coverage << ") vs ("
         << b[i].Page << "," << b[i].Coverage << ")";
      break;
    }
  }
  return os.str();
}

// A random valid page id among `distinct` possible ones (drawn from a fixed random table so
// that ids spread over all three fields).
struct IdPool
{
  std::vector<uint32_t> Ids;
  IdPool(size_t distinct, std::mt19937& rng)
  {
    std::uniform_int_distribution<int> ds(0, strata::FeedbackReduction::MaxDataSets - 1);
    std::uniform_int_distribution<int> lv(0, strata::FeedbackReduction::MaxLevels - 1);
    std::uniform_int_distribution<uint32_t> pg(0, strata::FeedbackReduction::MaxPagesPerLevel - 1);
    for (size_t i = 0; i < distinct; ++i)
    {
      this->Ids.push_back(strata::FeedbackReduction::PackPage(ds(rng), lv(rng), pg(rng)));
    }
  }
};

// fill: fraction of texels that hold a page.
Buffer RandomBuffer(size_t texels, size_t distinct, double fill, std::mt19937& rng)
{
  Buffer b(texels, 0);
  if (distinct == 0)
  {
    return b;
  }
  IdPool pool(distinct, rng);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<size_t> pick(0, distinct - 1);
  for (auto& t : b)
  {
    t = u(rng) < fill ? pool.Ids[pick(rng)] : 0;
  }
  return b;
}

// What a renderer writes: screen-space blocks of one page (finer near the bottom, as a
// terrain seen at a grazing angle), some background, two layers.
Buffer CoherentBuffer(int w, int h, int layers)
{
  Buffer b(static_cast<size_t>(w) * h * layers, 0);
  for (int l = 0; l < layers; ++l)
  {
    for (int y = 0; y < h; ++y)
    {
      const int level = std::min(9, 2 + (9 * (h - 1 - y)) / std::max(1, h));
      const int block = std::max(2, 64 >> (9 - level));
      for (int x = 0; x < w; ++x)
      {
        if (y < h / 5 || (l == 1 && x < w / 3))
        {
          continue; // sky / no second layer there
        }
        const uint32_t page = static_cast<uint32_t>((y / block) * 1024 + x / block);
        b[(static_cast<size_t>(l) * h + y) * w + x] =
          strata::FeedbackReduction::PackPage(l, level, page);
      }
    }
  }
  return b;
}

// Ids whose hashes share their low 10 bits: they all want the same slot of the OpenCL local
// table and of any CPU table of up to 1024 slots (long probe chains, local overflow path).
Buffer CollidingBuffer(size_t texels, size_t distinct)
{
  auto hash = [](uint32_t x)
  {
    x ^= x >> 16;
    x *= 0x85ebca6bu;
    x ^= x >> 13;
    x *= 0xc2b2ae35u;
    x ^= x >> 16;
    return x;
  };
  std::vector<uint32_t> ids;
  for (uint32_t page = 0;
       ids.size() < distinct && page < strata::FeedbackReduction::MaxPagesPerLevel;
       ++page)
  {
    const uint32_t id = strata::FeedbackReduction::PackPage(3, 4, page);
    if ((hash(id) & 1023u) == 77u)
    {
      ids.push_back(id);
    }
  }
  Buffer b(texels);
  for (size_t i = 0; i < texels; ++i)
  {
    b[i] = ids[(i * 7919) % ids.size()];
  }
  return b;
}

void CheckPacking()
{
  std::cout << "Page id packing (6 bits data set + 1, 5 bits level, 21 bits page index)\n";
  using R = strata::FeedbackReduction;
  bool roundTrip = true;
  for (int d : { 0, 1, 31, R::MaxDataSets - 1 })
  {
    for (int l : { 0, 7, R::MaxLevels - 1 })
    {
      for (uint32_t p : { 0u, 12345u, R::MaxPagesPerLevel - 1 })
      {
        const uint32_t id = R::PackPage(d, l, p);
        roundTrip = roundTrip && id != R::NoPage && R::GetDataSet(id) == d &&
                    R::GetLevel(id) == l && R::GetPageIndex(id) == p;
      }
    }
  }
  Check(roundTrip, "pack/unpack round trip over the corners of every field, never id 0");
  Check(R::PackPage(0, 0, 0) == (1u << 26), "PackPage(0,0,0) == 1 << 26");
  Check(R::PackPage(R::MaxDataSets - 1, R::MaxLevels - 1, R::MaxPagesPerLevel - 1) == 0xFFFFFFFFu,
    "largest id is 0xFFFFFFFF");
  Check(R::PackPage(-1, 0, 0) == 0 && R::PackPage(R::MaxDataSets, 0, 0) == 0 &&
          R::PackPage(0, R::MaxLevels, 0) == 0 && R::PackPage(0, 0, R::MaxPagesPerLevel) == 0,
    "out-of-range fields give NoPage");
  Check(
    R::PackPage(0, 5, 9) < R::PackPage(0, 6, 0) && R::PackPage(0, 31, 99) < R::PackPage(1, 0, 0),
    "id order is (data set, level, page)");
  const std::string glsl = R::GetGLSLPackFunction();
  Check(glsl.find("uint strataPackPage(uint dataSet, uint level, uint pageIndex)") !=
            std::string::npos &&
          glsl.find("<< 26u") != std::string::npos,
    "GLSL pack function has the same shifts");
}

void RunCase(strata::FeedbackReduction& r, bool haveCL, const std::string& name, const Buffer& b)
{
  std::vector<Entry> cpu, cl;
  const std::vector<Entry> ref = Reference(b);
  const bool cpuOk = r.ReduceCPU(b.data(), b.size(), cpu);
  std::ostringstream what;
  what << name << ": " << b.size() << " texels, " << ref.size() << " pages";
  Check(
    cpuOk && cpu == ref, what.str() + ", CPU == std::map reference (" + Describe(cpu, ref) + ")");
  if (haveCL)
  {
    const bool clOk = r.ReduceOpenCL(b.data(), b.size(), cl);
    Check(clOk && cl == cpu,
      what.str() + ", OpenCL == CPU (" + (clOk ? Describe(cl, cpu) : r.GetOpenCLMessage()) + ")");
  }
}

void CheckPropagation()
{
  std::cout << "Ancestor propagation (quadtree of one data set, level 0 finest)\n";
  using R = strata::FeedbackReduction;
  // Level l has 2^(3-l) x 2^(3-l) pages, x fastest; the parent of (l, i, j) is (l+1, i/2, j/2).
  auto parent = [](uint32_t id) -> uint32_t
  {
    const int l = R::GetLevel(id);
    if (l >= 3)
    {
      return R::NoPage;
    }
    const uint32_t n = 1u << (3 - l), p = R::GetPageIndex(id);
    const uint32_t i = p % n, j = p / n;
    return R::PackPage(R::GetDataSet(id), l + 1, (j / 2) * (n / 2) + i / 2);
  };
  std::vector<Entry> list = {
    { R::PackPage(0, 0, 0), 10 }, { R::PackPage(0, 0, 63), 5 }, { R::PackPage(0, 1, 0), 2 }
  };
  R::PropagateToAncestors(list, parent);
  std::map<uint32_t, uint32_t> m;
  for (const auto& e : list)
  {
    m[e.Page] = e.Coverage;
  }
  const bool sorted = std::is_sorted(
    list.begin(), list.end(), [](const Entry& a, const Entry& b) { return a.Page < b.Page; });
  Check(sorted && list.size() == 7, "sorted, unique: 3 pages + 4 distinct ancestors");
  Check(m[R::PackPage(0, 0, 0)] == 10 && m[R::PackPage(0, 1, 0)] == 12 &&
          m[R::PackPage(0, 2, 0)] == 12 && m[R::PackPage(0, 3, 0)] == 17 &&
          m[R::PackPage(0, 1, 15)] == 5 && m[R::PackPage(0, 2, 3)] == 5,
    "ancestor coverage is the sum over its subtree, root has all 17 texels");
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void Time(strata::FeedbackReduction& r, bool haveCL, const std::string& name, const Buffer& b)
{
  const int runs = 15;
  std::vector<double> cpu, cl;
  std::vector<Entry> list;
  for (int i = 0; i < runs; ++i)
  {
    r.ReduceCPU(b.data(), b.size(), list);
    cpu.push_back(r.GetLastCPUSeconds());
    if (haveCL)
    {
      r.ReduceOpenCL(b.data(), b.size(), list);
      cl.push_back(r.GetLastOpenCLSeconds());
    }
  }
  std::cout << "  time " << std::left << std::setw(34) << name << std::right << std::fixed
            << std::setprecision(3) << " CPU " << std::setw(7) << 1e3 * Median(cpu) << " ms";
  if (haveCL)
  {
    std::cout << "   OpenCL " << std::setw(7) << 1e3 * Median(cl) << " ms";
  }
  std::cout << "   (median of " << runs << ", " << list.size() << " pages)\n";
  std::cout.unsetf(std::ios::floatfield);
}
}

int TestFeedbackReduction(int, char*[])
{
  CheckPacking();
  CheckPropagation();

  strata::FeedbackReduction r;
  const bool haveCL = r.IsOpenCLAvailable();
  if (haveCL)
  {
    std::cout << "OpenCL device: " << r.GetOpenCLDeviceName() << " (set-up "
              << r.GetOpenCLSetupSeconds() << " s, including the program build)\n";
  }
  else
  {
    std::cout << "OpenCL UNAVAILABLE, only the CPU reduction is checked: " << r.GetOpenCLMessage()
              << "\n";
  }

  std::cout << "Reductions\n";
  std::mt19937 rng(20261122);
  RunCase(r, haveCL, "empty (0 texels)", Buffer());
  RunCase(r, haveCL, "1x1 no page", Buffer(1, 0));
  RunCase(r, haveCL, "1x1 one page", Buffer(1, strata::FeedbackReduction::PackPage(2, 3, 4)));
  RunCase(r, haveCL, "64x64 all zero", Buffer(64 * 64, 0));
  const struct
  {
    int W, H;
  } sizes[] = { { 64, 64 }, { 240, 135 }, { 480, 270 } };
  for (const auto& s : sizes)
  {
    const size_t n = static_cast<size_t>(s.W) * s.H;
    const std::string size = std::to_string(s.W) + "x" + std::to_string(s.H);
    RunCase(r, haveCL, size + " sparse few", RandomBuffer(n, 8, 0.05, rng));
    RunCase(r, haveCL, size + " sparse many", RandomBuffer(n, n, 0.05, rng));
    RunCase(r, haveCL, size + " dense few", RandomBuffer(n, 20, 1.0, rng));
    RunCase(r, haveCL, size + " dense many", RandomBuffer(n, n / 2, 0.9, rng));
    RunCase(r, haveCL, size + " coherent 2 layers", CoherentBuffer(s.W, s.H, 2));
  }
  const size_t quarterHD = 480 * 270;
  RunCase(r,
    haveCL,
    "480x270 all texels one id",
    Buffer(quarterHD, strata::FeedbackReduction::PackPage(5, 0, 777)));
  Buffer allDifferent(quarterHD);
  for (size_t i = 0; i < quarterHD; ++i)
  {
    // Descending and spread over every field, the largest id included.
    allDifferent[i] = 0xFFFFFFFFu - static_cast<uint32_t>(i) * 31u;
  }
  RunCase(r, haveCL, "480x270 all texels different ids", allDifferent);
  RunCase(r, haveCL, "480x270 2000 ids with colliding hashes", CollidingBuffer(quarterHD, 2000));
  RunCase(
    r, haveCL, "64x64 after a larger one (buffer reuse)", RandomBuffer(64 * 64, 100, 0.5, rng));

  std::vector<Entry> list(3);
  const Buffer mixed = RandomBuffer(240 * 135, 300, 0.7, rng);
  Check(r.Reduce(mixed.data(), mixed.size(), list) && list == Reference(mixed),
    std::string("Reduce() (") + (haveCL ? "OpenCL" : "CPU fallback") + ") == reference");
  r.SetUseOpenCL(false);
  Check(r.Reduce(mixed.data(), mixed.size(), list) && list == Reference(mixed),
    "Reduce() with UseOpenCL off (CPU) == reference");
  r.SetUseOpenCL(true);
  Check(r.ReduceCPU(nullptr, 0, list) && list.empty(), "null buffer of 0 texels: empty list");
  Check(!r.ReduceCPU(nullptr, 10, list) && list.empty(), "null buffer of 10 texels: refused");

  std::cout << "Timing at 480x270 (1/4 of 1920x1080 per axis)\n";
  Time(r, haveCL, "coherent, 1 layer", CoherentBuffer(480, 270, 1));
  Time(r, haveCL, "random, 1000 ids, 90% filled", RandomBuffer(quarterHD, 1000, 0.9, rng));
  Time(r, haveCL, "all texels different ids", allDifferent);

  std::cout << (failures ? "FAILED: " : "passed, ") << failures << " failure(s)\n";
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
