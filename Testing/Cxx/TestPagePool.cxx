// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// Page pools on disk: every page written by strata::PagePoolWriter and read back by
// strata::PagePoolFile must equal, bit for bit, strata::VolumeBrickTree::ExtractBrick of the same
// node (volumes) or a direct 2-D evaluation of the same filter (tile pools); per-page min/max and
// value ranges must match; compression and the memory limit must not change what is read (the limit
// must not even change the bytes of the file); and every fault must give a clear error.
#include "StrataSubTests.h"
#include "StrataTestPaths.h"

#include "StrataPagePoolFile.h"
#include "StrataPagePoolFormat.h"
#include "StrataPagePoolWriter.h"
#include "StrataVolumeBrickTree.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

namespace
{
using Format = strata::PagePoolFormat;
int Failures = 0;

void Check(bool ok, const std::string& what)
{
  std::printf("  [%s] %s\n", ok ? " ok " : "FAIL", what.c_str());
  if (!ok)
  {
    ++Failures;
  }
}

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

std::string TestDirectory(const std::string& output)
{
  std::string dir = output + "/TestPagePool-" + std::to_string(static_cast<long>(::getpid()));
  ::mkdir(dir.c_str(), 0755);
  return dir;
}

std::vector<unsigned char> ReadBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>(
    (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void WriteBytes(const std::string& path, const std::vector<unsigned char>& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(
    reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

bool Exists(const std::string& path)
{
  struct stat info;
  return ::stat(path.c_str(), &info) == 0;
}

int CountTempFiles(const std::string& dir)
{
  int count = 0;
  if (DIR* d = ::opendir(dir.c_str()))
  {
    while (dirent* e = ::readdir(d))
    {
      count += Contains(e->d_name, ".tmp-") ? 1 : 0;
    }
    ::closedir(d);
  }
  return count;
}

strata::VolumeBrickTree::ScalarType TreeType(Format::ScalarType t)
{
  switch (t)
  {
    case Format::ScalarType::UInt8:
      return strata::VolumeBrickTree::ScalarType::UInt8;
    case Format::ScalarType::UInt16:
      return strata::VolumeBrickTree::ScalarType::UInt16;
    case Format::ScalarType::Int16:
      return strata::VolumeBrickTree::ScalarType::Int16;
    default:
      return strata::VolumeBrickTree::ScalarType::Float32;
  }
}

template<typename T>
Format::ScalarType TypeOf()
{
  if (std::is_same<T, uint8_t>::value)
  {
    return Format::ScalarType::UInt8;
  }
  if (std::is_same<T, uint16_t>::value)
  {
    return Format::ScalarType::UInt16;
  }
  if (std::is_same<T, int16_t>::value)
  {
    return Format::ScalarType::Int16;
  }
  return Format::ScalarType::Float32;
}

// Smooth structure plus hashed noise spanning the type's range, so rounding, clamping and
// compression are all exercised; float gets negative values and a few NaN.
template<typename T>
std::vector<T> MakeData(const int dims[3], unsigned seed)
{
  std::vector<T> data(static_cast<size_t>(dims[0]) * dims[1] * dims[2]);
  size_t q = 0;
  for (int z = 0; z < dims[2]; ++z)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x, ++q)
      {
        unsigned h = (static_cast<unsigned>(q) + seed) * 2654435761u;
        h ^= h >> 15;
        const double smooth = std::sin(0.11 * x) * std::cos(0.07 * y) + 0.02 * z;
        const double noise = (h % 1000) / 1000.0;
        if (std::is_same<T, float>::value)
        {
          data[q] = static_cast<T>(h % 997 == 0 ? std::nan("") : 300.0 * smooth + 7.3 * noise);
        }
        else
        {
          const double lo = static_cast<double>(std::numeric_limits<T>::lowest());
          const double hi = static_cast<double>(std::numeric_limits<T>::max());
          const double t = std::clamp(0.5 + 0.35 * smooth + 0.1 * noise, 0.0, 1.0);
          data[q] = static_cast<T>(std::floor(lo + t * (hi - lo)));
        }
      }
    }
  }
  return data;
}

struct WriteOptions
{
  Format::Kind PoolKind = Format::Kind::BrickPool;
  int PageSize = 8;
  bool Compress = false;
  double LimitMB = 512;
  int FailAtSlab = -1; // the source reports an error when asked for this slab
};

// Writes `data` (x fastest, then y, then z or layer) through the streaming interface.
template<typename T>
bool WritePool(const std::vector<T>& data,
  const int dims[3],
  const std::string& path,
  const WriteOptions& opt,
  strata::PagePoolWriter& writer,
  std::vector<double>* progress = nullptr)
{
  writer.SetFileName(path);
  writer.SetKind(opt.PoolKind);
  writer.SetScalarType(TypeOf<T>());
  writer.SetDimensions(dims[0], dims[1], dims[2]);
  writer.SetSpacing(0.5, 0.75, 2.0);
  writer.SetOrigin(1000.0, -20.0, 3.5);
  writer.SetPageSize(opt.PageSize);
  writer.SetCompression(opt.Compress);
  writer.SetMemoryLimit(opt.LimitMB);
  const bool tiles = opt.PoolKind == Format::Kind::TilePool;
  writer.SetSource(
    [&, tiles](int first, int count, void* buffer)
    {
      if (opt.FailAtSlab >= first && opt.FailAtSlab < first + count)
      {
        return false;
      }
      T* out = static_cast<T*>(buffer);
      if (!tiles)
      {
        const size_t slice = static_cast<size_t>(dims[0]) * dims[1];
        std::copy_n(data.data() + first * slice, count * slice, out);
        return true;
      }
      for (int layer = 0; layer < dims[2]; ++layer) // block: x, row, layer
      {
        for (int r = 0; r < count; ++r)
        {
          std::copy_n(data.data() + (static_cast<size_t>(layer) * dims[1] + first + r) * dims[0],
            dims[0],
            out);
          out += dims[0];
        }
      }
      return true;
    });
  if (progress)
  {
    writer.SetProgressCallback([progress](double f) { progress->push_back(f); });
  }
  return writer.Write();
}

bool SameFloat(float a, float b)
{
  return a == b || (std::isnan(a) && std::isnan(b));
}

// Writes a brick pool and compares every page, both read paths and the ranges with the tree.
template<typename T>
void CheckVolume(const std::string& dir, const char* name, const int dims[3], int B, bool compress)
{
  std::printf("brick pool %s %d x %d x %d, B = %d, %s:\n",
    name,
    dims[0],
    dims[1],
    dims[2],
    B,
    compress ? "zstd" : "raw");
  const std::vector<T> data = MakeData<T>(dims, 17u * dims[0] + B);
  strata::VolumeBrickTree tree;
  tree.Build(data.data(), TreeType(TypeOf<T>()), dims, B);
  const std::string path = dir + "/" + name + (compress ? "-z" : "") + ".spp";
  strata::PagePoolWriter writer;
  WriteOptions opt;
  opt.PageSize = B;
  opt.Compress = compress;
  std::vector<double> progress;
  const bool written = WritePool(data, dims, path, opt, writer, &progress);
  Check(written, "written " + (written ? "" : writer.GetErrorMessage()));
  const auto& s = writer.GetStatistics();
  std::printf(
    "        %llu pages, raw %llu bytes, stored %llu bytes (%llu compressed), file %llu\n",
    static_cast<unsigned long long>(s.NumberOfPages),
    static_cast<unsigned long long>(s.RawBytes),
    static_cast<unsigned long long>(s.StoredBytes),
    static_cast<unsigned long long>(s.CompressedPages),
    static_cast<unsigned long long>(s.FileSize));
  Check(
    !progress.empty() && progress.back() == 1.0 && std::is_sorted(progress.begin(), progress.end()),
    "progress is non-decreasing and ends at 1");
  strata::PagePoolFile file;
  if (!file.Open(path))
  {
    Check(false, "open: " + file.GetErrorMessage());
    return;
  }
  Check(file.GetNumberOfLevels() == tree.GetNumberOfLevels() &&
          file.GetNumberOfPages() == static_cast<uint64_t>(tree.GetNumberOfNodes()),
    "levels (" + std::to_string(file.GetNumberOfLevels()) + ") and pages (" +
      std::to_string(file.GetNumberOfPages()) + ") as strata::VolumeBrickTree");
  const size_t values = static_cast<size_t>(B) * B * B;
  std::vector<T> expectNative(values), gotNative(values);
  std::vector<float> expectFloat(values), gotFloat(values);
  bool pagesEqual = true, rangesEqual = true;
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (int id = 0; id < tree.GetNumberOfNodes(); ++id)
  {
    const strata::VolumeBrickTree::Node& node = tree.GetNode(id);
    const uint64_t index = static_cast<uint64_t>(id - tree.GetLevelOffset(node.Level));
    tree.ExtractBrickNative(id, expectNative.data());
    tree.ExtractBrick(id, expectFloat.data());
    std::string error;
    if (!file.ReadPageNative(node.Level, index, gotNative.data(), &error) ||
        !file.ReadPage(node.Level, index, gotFloat.data(), &error) ||
        std::memcmp(expectNative.data(), gotNative.data(), values * sizeof(T)) != 0 ||
        std::memcmp(expectFloat.data(), gotFloat.data(), values * sizeof(float)) != 0)
    {
      if (pagesEqual)
      {
        std::printf("        first differing page: node %d %s\n", id, error.c_str());
      }
      pagesEqual = false;
    }
    rangesEqual = rangesEqual && SameFloat(file.GetPageMin(node.Level, index), node.Min) &&
                  SameFloat(file.GetPageMax(node.Level, index), node.Max);
    if (node.Level == 0)
    {
      lo = std::min(lo, node.Min);
      hi = std::max(hi, node.Max);
    }
  }
  Check(pagesEqual, "every page (native and float) equals ExtractBrick bit for bit");
  Check(rangesEqual, "every page min/max equals the tree node's");
  const Format::Header& h = file.GetHeader();
  Check(h.ValueRange[0] == lo && h.ValueRange[1] == hi && h.Spacing[1] == 0.75 &&
          h.Origin[0] == 1000.0 && h.PageSize == B,
    "header value range [" + std::to_string(h.ValueRange[0]) + ", " +
      std::to_string(h.ValueRange[1]) + "] and geometry");
}

// Reference tile pool: each layer down-sampled in x and y by [1 2 1]/4 exactly as documented.
template<typename T>
void CheckTiles(const std::string& dir, int nx, int ny, int layers, int B)
{
  std::printf("tile pool %d x %d x %d layers, B = %d, float with holes:\n", nx, ny, layers, B);
  const int dims[3] = { nx, ny, layers };
  std::vector<T> data = MakeData<T>(dims, 5u);
  const std::string path = dir + "/tiles.spp";
  strata::PagePoolWriter writer;
  WriteOptions opt;
  opt.PoolKind = Format::Kind::TilePool;
  opt.PageSize = B;
  opt.Compress = true;
  const bool written = WritePool(data, dims, path, opt, writer);
  Check(written, "written " + (written ? "" : writer.GetErrorMessage()));
  strata::PagePoolFile file;
  if (!file.Open(path))
  {
    Check(false, "open: " + file.GetErrorMessage());
    return;
  }
  const int S = B - 1;
  std::vector<T> level = data;
  int n[2] = { nx, ny };
  bool equal = true, ranges = true;
  int l = 0;
  auto tap = [](int v, int d, int m) { return std::clamp(2 * v + d, 0, m - 1); };
  for (;; ++l)
  {
    const int tx = n[0] <= 1 ? 1 : (n[0] - 1 + S - 1) / S;
    const int ty = n[1] <= 1 ? 1 : (n[1] - 1 + S - 1) / S;
    if (l >= file.GetNumberOfLevels() || file.GetLevel(l).Pages[0] != tx ||
        file.GetLevel(l).Pages[1] != ty)
    {
      equal = false;
      break;
    }
    std::vector<T> expect(static_cast<size_t>(B) * B * layers), got(expect.size());
    for (int j = 0; j < ty; ++j)
    {
      for (int i = 0; i < tx; ++i)
      {
        float mn = std::numeric_limits<float>::infinity(), mx = -mn;
        for (int layer = 0; layer < layers; ++layer)
        {
          for (int b = 0; b < B; ++b)
          {
            for (int a = 0; a < B; ++a)
            {
              const int x = std::min(i * S + a, n[0] - 1);
              const int y = std::min(j * S + b, n[1] - 1);
              const T v = level[(static_cast<size_t>(layer) * n[1] + y) * n[0] + x];
              expect[(static_cast<size_t>(layer) * B + b) * B + a] = v;
              if (!std::isnan(static_cast<float>(v)))
              {
                mn = std::min(mn, static_cast<float>(v));
                mx = std::max(mx, static_cast<float>(v));
              }
            }
          }
        }
        const uint64_t index = static_cast<uint64_t>(j) * tx + i;
        equal = equal && file.ReadPageNative(l, index, got.data()) &&
                std::memcmp(expect.data(), got.data(), got.size() * sizeof(T)) == 0;
        ranges = ranges && SameFloat(file.GetPageMin(l, index), mn) &&
                 SameFloat(file.GetPageMax(l, index), mx);
      }
    }
    if (tx * ty == 1)
    {
      break;
    }
    const int c[2] = { n[0] > 1 ? n[0] / 2 + 1 : 1, n[1] > 1 ? n[1] / 2 + 1 : 1 };
    std::vector<T> coarse(static_cast<size_t>(c[0]) * c[1] * layers);
    for (int layer = 0; layer < layers; ++layer)
    {
      for (int cy = 0; cy < c[1]; ++cy)
      {
        // The weighted mean of the 3 x 3 taps that hold data (NaN takes no part), NaN where
        // none does.
        std::vector<double> acc(c[0], 0.0), weight(c[0], 0.0);
        for (int dy = -1; dy <= 1; ++dy)
        {
          const T* row =
            level.data() + (static_cast<size_t>(layer) * n[1] + tap(cy, dy, n[1])) * n[0];
          for (int cx = 0; cx < c[0]; ++cx)
          {
            for (int dx = -1; dx <= 1; ++dx)
            {
              const double v = static_cast<double>(row[tap(cx, dx, n[0])]);
              const double w = (dy == 0 ? 2.0 : 1.0) * (dx == 0 ? 2.0 : 1.0);
              if (!std::isnan(v))
              {
                acc[cx] += w * v;
                weight[cx] += w;
              }
            }
          }
        }
        for (int cx = 0; cx < c[0]; ++cx)
        {
          coarse[(static_cast<size_t>(layer) * c[1] + cy) * c[0] + cx] =
            weight[cx] > 0.0 ? static_cast<T>(acc[cx] / weight[cx])
                             : std::numeric_limits<T>::quiet_NaN();
        }
      }
    }
    level.swap(coarse);
    n[0] = c[0];
    n[1] = c[1];
  }
  Check(equal && l + 1 == file.GetNumberOfLevels(),
    "all " + std::to_string(file.GetNumberOfLevels()) +
      " levels of tiles equal the 2-D reference bit for bit");
  Check(ranges, "every tile min/max (NaN excluded) as expected");
  strata::PagePoolWriter bounded;
  opt.LimitMB = 0.05;
  const bool rewritten = WritePool(data, dims, dir + "/tiles-bounded.spp", opt, bounded);
  Check(rewritten && bounded.GetStatistics().SourceCalls > 1 &&
          ReadBytes(path) == ReadBytes(dir + "/tiles-bounded.spp"),
    "0.05 MB limit (" + std::to_string(bounded.GetStatistics().SourceCalls) +
      " source calls) writes the same bytes " + bounded.GetErrorMessage());
}

// Rewrites a pool's header through `edit` (recomputing the header CRC unless told not to).
template<typename F>
std::string OpenEdited(const std::string& good, const std::string& bad, F edit, bool recrc = true)
{
  std::vector<unsigned char> bytes = ReadBytes(good);
  if (recrc)
  {
    Format::Header h;
    Format::DecodeHeader(bytes.data(), h);
    edit(h, bytes);
    Format::EncodeHeader(h, bytes.data());
  }
  else
  {
    Format::Header h;
    edit(h, bytes);
  }
  WriteBytes(bad, bytes);
  strata::PagePoolFile file;
  return file.Open(bad) ? std::string("(opened!)") : file.GetErrorMessage();
}
}

namespace
{
/// Every scalar type through the writer and back, then a tile pool.
void VolumesAndTiles(const std::string& dir)
{
  // Dimensions with a 1 in some axis and not multiples of the stride.
  const int d1[3] = { 37, 1, 29 };
  CheckVolume<uint8_t>(dir, "u8", d1, 8, false);
  const int d2[3] = { 45, 33, 20 };
  CheckVolume<uint16_t>(dir, "u16", d2, 16, false);
  CheckVolume<uint16_t>(dir, "u16", d2, 16, true);
  const int d3[3] = { 1, 23, 17 };
  CheckVolume<int16_t>(dir, "i16", d3, 8, false);
  const int d4[3] = { 50, 41, 36 };
  CheckVolume<float>(dir, "f32", d4, 8, false);
  CheckVolume<float>(dir, "f32", d4, 8, true);
  const int d5[3] = { 1, 1, 1 };
  CheckVolume<uint8_t>(dir, "single", d5, 8, false);
  CheckTiles<float>(dir, 70, 45, 3, 16);
}

void MemoryLimit(const std::string& dir)
{
  std::printf("memory limit:\n");
  const int dims[3] = { 160, 128, 256 };
  const std::vector<uint16_t> data = MakeData<uint16_t>(dims, 99u);
  WriteOptions opt;
  opt.PageSize = 16;
  strata::PagePoolWriter free, bounded, tooSmall;
  const bool a = WritePool(data, dims, dir + "/free.spp", opt, free);
  opt.LimitMB = 1.5;
  const bool b = WritePool(data, dims, dir + "/bounded.spp", opt, bounded);
  const double volumeMB = data.size() * 2.0 / 1048576.0;
  std::printf("        volume %.2f MB; unlimited: %d slabs/call, %llu calls, ~%.2f MB; "
              "limit 1.5 MB: %d slabs/call, %llu calls, ~%.2f MB\n",
    volumeMB,
    free.GetStatistics().SlabsPerCall,
    static_cast<unsigned long long>(free.GetStatistics().SourceCalls),
    free.GetStatistics().EstimatedPeakBytes / 1048576.0,
    bounded.GetStatistics().SlabsPerCall,
    static_cast<unsigned long long>(bounded.GetStatistics().SourceCalls),
    bounded.GetStatistics().EstimatedPeakBytes / 1048576.0);
  Check(a && b, "both written " + free.GetErrorMessage() + bounded.GetErrorMessage());
  const auto& bs = bounded.GetStatistics();
  const uint64_t slab = static_cast<uint64_t>(dims[0]) * dims[1] * 2;
  std::printf("        limited run: measured peak of slice windows %.2f MB + block %.2f MB\n",
    bs.MeasuredPeakSlabBytes / 1048576.0,
    bs.SlabsPerCall * slab / 1048576.0);
  Check(bs.SourceCalls > 1 && bs.EstimatedPeakBytes <= 1.5 * 1048576.0 &&
          bs.MeasuredPeakSlabBytes + bs.SlabsPerCall * slab <= bs.EstimatedPeakBytes,
    "the limited run read in several blocks; measured buffers within the 1.5 MB budget");
  const auto fa = ReadBytes(dir + "/free.spp");
  Check(!fa.empty() && fa == ReadBytes(dir + "/bounded.spp"),
    "files are identical byte for byte (" + std::to_string(fa.size()) + " bytes)");
  opt.LimitMB = 0.1;
  const bool c = WritePool(data, dims, dir + "/small.spp", opt, tooSmall);
  Check(!c && Contains(tooSmall.GetErrorMessage(), "memory limit") && !Exists(dir + "/small.spp"),
    "a limit below the minimum is refused: " + tooSmall.GetErrorMessage());
}

/// Reads free.spp (MemoryLimit's) from several threads at once.
void ConcurrentReads(const std::string& dir)
{
  // Several threads reading all pages at once get the same bytes as one thread.
  strata::PagePoolFile file;
  const bool opened = file.Open(dir + "/free.spp");
  std::vector<std::vector<uint16_t>> serial(file.GetNumberOfPages());
  for (int l = 0; opened && l < file.GetNumberOfLevels(); ++l)
  {
    const auto& L = file.GetLevel(l);
    for (uint64_t i = 0; i < static_cast<uint64_t>(L.Pages[0]) * L.Pages[1] * L.Pages[2]; ++i)
    {
      serial[L.FirstPage + i].resize(file.GetPageValues());
      file.ReadPageNative(l, i, serial[L.FirstPage + i].data());
    }
  }
  std::atomic<int> mismatches{ 0 };
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
  {
    threads.emplace_back(
      [&, t]()
      {
        std::vector<uint16_t> page(file.GetPageValues());
        for (int pass = 0; pass < 2; ++pass)
        {
          for (int l = file.GetNumberOfLevels() - 1; l >= 0; --l)
          {
            const auto& L = file.GetLevel(l);
            const uint64_t count = static_cast<uint64_t>(L.Pages[0]) * L.Pages[1] * L.Pages[2];
            for (uint64_t k = 0; k < count; ++k)
            {
              const uint64_t i = (k * 7 + t) % count;
              if (!file.ReadPageNative(l, i, page.data()) || page != serial[L.FirstPage + i])
              {
                ++mismatches;
              }
            }
          }
        }
      });
  }
  for (auto& th : threads)
  {
    th.join();
  }
  Check(opened && mismatches == 0, "4 threads reading concurrently agree with a serial read");
}

/// Missing, truncated and corrupt files (from VolumesAndTiles' u16.spp and u16-z.spp).
void FileFaults(const std::string& dir)
{
  std::printf("faults:\n");
  const std::string good = dir + "/u16.spp";
  const std::string goodZ = dir + "/u16-z.spp";
  const std::string bad = dir + "/bad.spp";
  strata::PagePoolFile file;
  const bool missing = !file.Open(dir + "/does-not-exist.spp");
  Check(missing && Contains(file.GetErrorMessage(), "cannot open") &&
          Contains(file.GetErrorMessage(), "No such file"),
    "missing file: " + file.GetErrorMessage());

  std::vector<unsigned char> bytes = ReadBytes(good);
  for (size_t cut : { bytes.size() - 1000, size_t(100) })
  {
    WriteBytes(bad, std::vector<unsigned char>(bytes.begin(), bytes.begin() + cut));
    const bool refused = !file.Open(bad);
    Check(refused && Contains(file.GetErrorMessage(), "truncated"),
      "truncated to " + std::to_string(cut) + " bytes: " + file.GetErrorMessage());
  }

  for (const std::string& src : { good, goodZ })
  {
    strata::PagePoolFile ok;
    ok.Open(src);
    const Format::PageEntry e = ok.GetPageEntry(3);
    std::vector<unsigned char> flipped = ReadBytes(src);
    flipped[e.Offset + e.StoredSize / 2] ^= 0x10;
    WriteBytes(bad, flipped);
    std::vector<float> page(ok.GetPageValues());
    std::string error;
    const bool opened = file.Open(bad);
    const bool refused = opened && !file.ReadPage(e.Level, e.Index, page.data(), &error);
    const bool othersFine = opened && file.ReadPage(0, 0, page.data()) &&
                            file.ReadPage(file.GetNumberOfLevels() - 1, 0, page.data());
    Check(refused && Contains(error, "checksum") && othersFine && file.GetLastPageError() == error,
      "flipped byte in a " + std::string(src == good ? "raw" : "zstd") +
        " page refused, others read: " + error);
  }
}

/// Headers and page tables edited one field at a time.
void HeaderFaults(const std::string& dir)
{
  const std::string good = dir + "/u16.spp";
  const std::string bad = dir + "/bad.spp";
  std::string msg = OpenEdited(
    good, bad, [](Format::Header&, std::vector<unsigned char>& b) { b[0] = 'X'; }, false);
  Check(Contains(msg, "magic"), "wrong magic: " + msg);
  msg =
    OpenEdited(good, bad, [](Format::Header& h, std::vector<unsigned char>&) { h.Version = 7; });
  Check(Contains(msg, "version 7"), "wrong version: " + msg);
  // Sets of components (version 2): 2 to 4 brick pools, the file's component among them.
  auto set = [](int components, int component)
  {
    return [=](Format::Header& h, std::vector<unsigned char>&)
    {
      h.Version = Format::ComponentsVersion;
      h.Components = components;
      h.Component = component;
    };
  };
  msg = OpenEdited(good, bad, set(1, 0));
  Check(Contains(msg, "2 to 4"), "version 2 of one component: " + msg);
  msg = OpenEdited(good, bad, set(5, 0));
  Check(Contains(msg, "2 to 4"), "5 components: " + msg);
  msg = OpenEdited(good, bad, set(3, 3));
  Check(Contains(msg, "component 3 of 3"), "component 3 of 3: " + msg);
  {
    strata::PagePoolFile edited;
    OpenEdited(good, bad, set(3, 2));
    Check(
      edited.Open(bad) && edited.GetHeader().Components == 3 && edited.GetHeader().Component == 2,
      "component 2 of 3 opens (version 2)");
    strata::PagePoolFile plain;
    Check(plain.Open(good) && plain.GetHeader().Version == 1 && plain.GetHeader().Components == 1 &&
            plain.GetHeader().Component == 0,
      "a version 1 pool is one component");
  }
  msg = OpenEdited(
    good, bad, [](Format::Header&, std::vector<unsigned char>& b) { b[30] ^= 1; }, false);
  Check(Contains(msg, "header checksum"), "corrupt header bytes: " + msg);
  msg = OpenEdited(
    good, bad, [](Format::Header& h, std::vector<unsigned char>&) { h.Dimensions[0] = 0; });
  Check(Contains(msg, "absurd") && Contains(msg, "dimension 0"), "zero dimension: " + msg);
  msg = OpenEdited(
    good, bad, [](Format::Header& h, std::vector<unsigned char>&) { h.Dimensions[2] = 1 << 21; });
  Check(Contains(msg, "absurd") && Contains(msg, "dimension 2"), "huge dimension: " + msg);
  msg =
    OpenEdited(good, bad, [](Format::Header& h, std::vector<unsigned char>&) { h.PageSize = 4; });
  Check(Contains(msg, "page size 4"), "page size 4: " + msg);
  msg = OpenEdited(
    good, bad, [](Format::Header& h, std::vector<unsigned char>&) { h.Dimensions[0] = 400; });
  Check(Contains(msg, "imply"), "dimensions that do not match the counts: " + msg);
  msg = OpenEdited(good,
    bad,
    [](Format::Header& h, std::vector<unsigned char>&) { h.NumberOfPages = 1ull << 40; });
  Check(Contains(msg, "pages"), "absurd page count: " + msg);
  msg = OpenEdited(
    good,
    bad,
    [](Format::Header&, std::vector<unsigned char>& b) { b[Format::HeaderSize + 5] ^= 1; },
    false);
  Check(Contains(msg, "page table checksum"), "corrupt page table: " + msg);
  msg = OpenEdited(good,
    bad,
    [](Format::Header& h, std::vector<unsigned char>& b)
    {
      // A consistent table (checksum recomputed) whose page 2 lies beyond the end.
      unsigned char* entry = b.data() + Format::HeaderSize + 2 * Format::EntrySize;
      Format::PageEntry e;
      Format::DecodeEntry(entry, e);
      e.Offset = h.FileSize + 64;
      Format::EncodeEntry(e, entry);
      h.TableChecksum = Format::Crc32(
        b.data() + Format::HeaderSize, static_cast<size_t>(h.NumberOfPages) * Format::EntrySize);
    });
  Check(Contains(msg, "outside"), "page offset beyond the file: " + msg);
}

void FailingWriters(const std::string& dir)
{
  std::printf("failing writers:\n");
  const int dims[3] = { 40, 30, 50 };
  const std::vector<int16_t> data = MakeData<int16_t>(dims, 3u);
  const std::string path = dir + "/failed.spp";
  WriteOptions opt;
  opt.FailAtSlab = 33;
  opt.LimitMB = 0.1; // several source calls: pages are already in the temporary file
  strata::PagePoolWriter writer;
  const bool ok = WritePool(data, dims, path, opt, writer);
  Check(!ok && Contains(writer.GetErrorMessage(), "source failed") && !Exists(path) &&
          CountTempFiles(dir) == 0 && writer.GetStatistics().SourceCalls >= 1,
    "source error mid-way: no output, no temporary file: " + writer.GetErrorMessage());
  opt.FailAtSlab = -1;
  opt.PageSize = 600;
  const bool ok2 = WritePool(data, dims, path, opt, writer);
  Check(!ok2 && Contains(writer.GetErrorMessage(), "page size") && !Exists(path),
    "absurd settings refused: " + writer.GetErrorMessage());
  opt.PageSize = 8;
  const int huge[3] = { 1 << 20, 1 << 20, 1 << 20 };
  const bool ok4 = WritePool(data, huge, path, opt, writer);
  Check(!ok4 && Contains(writer.GetErrorMessage(), "2^31 pages") && !Exists(path),
    "2^60 voxels in pages of 8^3 refused before any allocation: " + writer.GetErrorMessage());
  const bool ok3 = WritePool(data, dims, dir + "/no-such-dir/x.spp", opt, writer);
  Check(!ok3 && Contains(writer.GetErrorMessage(), "cannot create"),
    "unwritable location: " + writer.GetErrorMessage());
}

/// Leaves nothing behind.
void RemoveDirectory(const std::string& dir)
{
  if (DIR* d = ::opendir(dir.c_str()))
  {
    while (dirent* e = ::readdir(d))
    {
      if (e->d_name[0] != '.')
      {
        ::unlink((dir + "/" + e->d_name).c_str());
      }
    }
    ::closedir(d);
  }
  ::rmdir(dir.c_str());
}
}

int TestPagePool(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string dir = TestDirectory(paths.Output);
  std::printf("output directory %s\n", dir.c_str());
  strata_test::RunSubTests(
    {
      { "VolumesAndTiles", [&] { VolumesAndTiles(dir); } },
      { "MemoryLimit", [&] { MemoryLimit(dir); } },
      { "ConcurrentReads", [&] { ConcurrentReads(dir); } },
      { "FileFaults", [&] { FileFaults(dir); } },
      { "HeaderFaults", [&] { HeaderFaults(dir); } },
      { "FailingWriters", [&] { FailingWriters(dir); } },
    },
    [] { return Failures; });
  RemoveDirectory(dir);

  std::printf("%s: %d failure(s)\n", Failures ? "FAILED" : "PASSED", Failures);
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
