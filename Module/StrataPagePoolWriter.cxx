// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataPagePoolWriter.h"

#include "StrataVolumeBrickTree.h"

#include <zstd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <limits>
#include <type_traits>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace strata
{

namespace
{
using Format = strata::PagePoolFormat;

bool HostIsLittleEndian()
{
  const uint16_t probe = 1;
  unsigned char first;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

bool WriteAll(int fd, const void* data, size_t size, uint64_t offset, std::string& error)
{
  const char* p = static_cast<const char*>(data);
  while (size > 0)
  {
    const ssize_t n = ::pwrite(fd, p, size, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      error = std::string("write failed: ") + (n < 0 ? std::strerror(errno) : "no progress");
      return false;
    }
    p += n;
    size -= static_cast<size_t>(n);
    offset += static_cast<uint64_t>(n);
  }
  return true;
}

// Same rounding as strata::VolumeBrickTree: half up for integers, a plain cast for float.
template<typename T>
T FromDouble(double v)
{
  if constexpr (std::is_floating_point<T>::value)
  {
    return static_cast<T>(v);
  }
  else
  {
    return static_cast<T>(std::floor(v + 0.5));
  }
}

// The temporary output: removed unless committed by a successful rename.
struct TempFile
{
  std::string Path;
  int Fd = -1;
  bool Committed = false;
  ~TempFile()
  {
    if (this->Fd >= 0)
    {
      ::close(this->Fd);
    }
    if (!this->Committed && !this->Path.empty())
    {
      ::unlink(this->Path.c_str());
    }
  }
};

/**
 * The one-pass cascade described in the class documentation. Internal axes: (0, 1, 2) =
 * (x, y, z) for bricks and (x, layer, y) for tiles, so that axis 2 is always the streaming
 * axis and a slice is the contiguous g0 * g1 values the source delivers per slab.
 */
template<typename T>
struct Converter
{
  struct LevelState
  {
    int D[3];
    int Pages[3];
    uint64_t FirstPage;
    std::deque<std::vector<T>> Window;
    int WindowFirst = 0;
    int Received = 0;
    int NextRow = 0;
    int NextCoarse = 0;
  };

  bool Tiles = false;
  int B = 0;
  int Stride = 0;
  bool HasNoData = false;
  double NoData = 0;
  bool Compress = false;
  int CompressionLevel = 3;
  int Fd = -1;
  uint64_t Cursor = 0; // next page offset
  std::vector<LevelState> Levels;
  std::vector<Format::PageEntry> Table;
  std::vector<T> Page;
  std::vector<unsigned char> Packed;
  std::vector<double> FilteredX;
  std::vector<double> FilteredWeight; ///< weights of the taps holding data (with holes)
  std::vector<double> AccWeight;
  std::vector<double> Acc;
  double Range[2] = { std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity() };
  uint64_t PagesWritten = 0;
  uint64_t Buffered = 0; // bytes in all windows now
  PagePoolWriter::Statistics* Stats = nullptr;
  std::string Error;

  bool Skip(T v) const
  {
    const double d = static_cast<double>(v);
    return std::isnan(d) || (this->HasNoData && d == this->NoData);
  }

  const T* Slice(const LevelState& s, int z) const
  {
    z = std::clamp(z, 0, s.D[2] - 1);
    return s.Window[static_cast<size_t>(z - s.WindowFirst)].data();
  }

  bool Push(size_t l, std::vector<T>&& slice)
  {
    LevelState& s = this->Levels[l];
    if (l == 0)
    {
      for (T v : slice)
      {
        if (!this->Skip(v))
        {
          this->Range[0] = std::min(this->Range[0], static_cast<double>(v));
          this->Range[1] = std::max(this->Range[1], static_cast<double>(v));
        }
      }
    }
    this->Buffered += slice.size() * sizeof(T);
    this->Stats->MeasuredPeakSlabBytes =
      std::max(this->Stats->MeasuredPeakSlabBytes, this->Buffered);
    s.Window.push_back(std::move(slice));
    ++s.Received;
    while (s.NextRow < s.Pages[2] &&
           s.Received > std::min(s.NextRow * this->Stride + this->Stride, s.D[2] - 1))
    {
      if (!this->EmitRow(l, s.NextRow))
      {
        return false;
      }
      ++s.NextRow;
    }
    if (l + 1 < this->Levels.size())
    {
      const int coarseCount = this->Levels[l + 1].D[2];
      while (s.NextCoarse < coarseCount && s.Received > std::min(2 * s.NextCoarse + 1, s.D[2] - 1))
      {
        std::vector<T> coarse = this->Downsample(l, s.NextCoarse);
        ++s.NextCoarse;
        if (!this->Push(l + 1, std::move(coarse)))
        {
          return false;
        }
      }
    }
    // Oldest slice still needed: the first of the next page row, the lowest tap of the next
    // coarse slice.
    int keep = std::numeric_limits<int>::max();
    if (s.NextRow < s.Pages[2])
    {
      keep = s.NextRow * this->Stride;
    }
    if (l + 1 < this->Levels.size() && s.NextCoarse < this->Levels[l + 1].D[2])
    {
      keep = std::min(keep, std::max(2 * s.NextCoarse - 1, 0));
    }
    keep = std::min(keep, s.Received - 1);
    while (s.WindowFirst < keep)
    {
      this->Buffered -= s.Window.front().size() * sizeof(T);
      s.Window.pop_front();
      ++s.WindowFirst;
    }
    return true;
  }

  // Exactly strata::VolumeBrickTree::Downsample's arithmetic, one coarse slice at a time; tiles
  // skip the (layer) axis 1. Holes (NaN, the no-data value) take no part: a coarse value is the
  // weighted mean of the taps that hold data, and a hole only where none does, so every level
  // covers at least what the finer one covers (a coarse cut of horizons with holes shows no
  // hole the data do not have, and the rays that hit it ask for its detail).
  std::vector<T> Downsample(size_t l, int cz)
  {
    const LevelState& fine = this->Levels[l];
    const int* fd = fine.D;
    const int* cd = this->Levels[l + 1].D;
    auto tap = [](int v, int d, int n) { return std::clamp(2 * v + d, 0, n - 1); };
    const bool holes = this->HasNoData || std::numeric_limits<T>::has_quiet_NaN;
    const size_t cslice = static_cast<size_t>(cd[0]) * cd[1];
    this->Acc.assign(cslice, 0.0);
    this->AccWeight.assign(holes ? cslice : 0, 0.0);
    for (int dz = -1; dz <= 1; ++dz)
    {
      const double wz = dz == 0 ? 2.0 : 1.0;
      const T* slice = this->Slice(fine, tap(cz, dz, fd[2]));
      this->FilteredX.resize(static_cast<size_t>(cd[0]) * fd[1]);
      this->FilteredWeight.resize(holes ? this->FilteredX.size() : 0);
      for (int y = 0; y < fd[1]; ++y)
      {
        const T* row = slice + static_cast<size_t>(y) * fd[0];
        double* fx = this->FilteredX.data() + static_cast<size_t>(y) * cd[0];
        if (!holes)
        {
          for (int cx = 0; cx < cd[0]; ++cx)
          {
            fx[cx] = static_cast<double>(row[tap(cx, -1, fd[0])]) +
                     2.0 * static_cast<double>(row[tap(cx, 0, fd[0])]) +
                     static_cast<double>(row[tap(cx, 1, fd[0])]);
          }
          continue;
        }
        double* fw = this->FilteredWeight.data() + static_cast<size_t>(y) * cd[0];
        for (int cx = 0; cx < cd[0]; ++cx)
          fx[cx] = strata::VolumeBrickTree::FilterTaps(
            row, cx, fd[0], [this](T t) { return this->Skip(t); }, fw[cx]);
      }
      auto accumulate = [&](const std::vector<double>& filtered, std::vector<double>& acc)
      {
        for (int cy = 0; cy < cd[1]; ++cy)
        {
          double* a = acc.data() + static_cast<size_t>(cy) * cd[0];
          if (this->Tiles)
          {
            const double* r = filtered.data() + static_cast<size_t>(cy) * cd[0];
            for (int cx = 0; cx < cd[0]; ++cx)
            {
              a[cx] += wz * r[cx];
            }
            continue;
          }
          const double* r0 = filtered.data() + static_cast<size_t>(tap(cy, -1, fd[1])) * cd[0];
          const double* r1 = filtered.data() + static_cast<size_t>(tap(cy, 0, fd[1])) * cd[0];
          const double* r2 = filtered.data() + static_cast<size_t>(tap(cy, 1, fd[1])) * cd[0];
          for (int cx = 0; cx < cd[0]; ++cx)
          {
            a[cx] += wz * (r0[cx] + 2.0 * r1[cx] + r2[cx]);
          }
        }
      };
      accumulate(this->FilteredX, this->Acc);
      if (holes)
        accumulate(this->FilteredWeight, this->AccWeight);
    }
    const double norm = this->Tiles ? 16.0 : 64.0;
    std::vector<T> out(cslice);
    for (size_t q = 0; q < cslice; ++q)
    {
      if (!holes)
        out[q] = FromDouble<T>(this->Acc[q] / norm);
      else if (this->AccWeight[q] > 0.0)
        out[q] = FromDouble<T>(this->Acc[q] / this->AccWeight[q]);
      else
        out[q] =
          this->HasNoData ? static_cast<T>(this->NoData) : std::numeric_limits<T>::quiet_NaN();
    }
    return out;
  }

  bool EmitRow(size_t l, int k)
  {
    const LevelState& s = this->Levels[l];
    const int B = this->B;
    const int e1 = this->Tiles ? s.D[1] : B; // page extent along internal axis 1
    for (int j = 0; j < s.Pages[1]; ++j)
    {
      for (int i = 0; i < s.Pages[0]; ++i)
      {
        this->Page.resize(static_cast<size_t>(B) * B * e1);
        float mn = std::numeric_limits<float>::infinity();
        float mx = -std::numeric_limits<float>::infinity();
        for (int c = 0; c < B; ++c)
        {
          const T* slice = this->Slice(s, k * this->Stride + c);
          for (int b = 0; b < e1; ++b)
          {
            const int y = std::min(j * this->Stride + b, s.D[1] - 1);
            const T* row = slice + static_cast<size_t>(y) * s.D[0];
            // Output layout: x fastest, then y, then z (bricks) or layer (tiles).
            T* out = this->Page.data() + (this->Tiles ? (static_cast<size_t>(b) * B + c) * B
                                                      : (static_cast<size_t>(c) * B + b) * B);
            for (int a = 0; a < B; ++a)
            {
              const T v = row[std::min(i * this->Stride + a, s.D[0] - 1)];
              out[a] = v;
              if (!this->Skip(v))
              {
                const float f = static_cast<float>(v);
                mn = std::min(mn, f);
                mx = std::max(mx, f);
              }
            }
          }
        }
        const uint64_t index = (static_cast<uint64_t>(k) * s.Pages[1] + j) * s.Pages[0] + i;
        if (!this->Store(static_cast<uint32_t>(l), index, s.FirstPage + index, mn, mx))
        {
          return false;
        }
      }
    }
    return true;
  }

  bool Store(uint32_t level, uint64_t index, uint64_t id, float mn, float mx)
  {
    const size_t raw = this->Page.size() * sizeof(T);
    const unsigned char* data = reinterpret_cast<const unsigned char*>(this->Page.data());
    size_t size = raw;
    Format::PageEntry& e = this->Table[id];
    e.PageEncoding = Format::Encoding::Raw;
    if (this->Compress)
    {
      this->Packed.resize(ZSTD_compressBound(raw));
      const size_t n =
        ZSTD_compress(this->Packed.data(), this->Packed.size(), data, raw, this->CompressionLevel);
      if (ZSTD_isError(n))
      {
        this->Error = std::string("zstd compression failed: ") + ZSTD_getErrorName(n);
        return false;
      }
      if (n < raw)
      {
        data = this->Packed.data();
        size = n;
        e.PageEncoding = Format::Encoding::Zstd;
        ++this->Stats->CompressedPages;
      }
    }
    e.Level = level;
    e.Index = static_cast<uint32_t>(index);
    e.Offset = this->Cursor;
    e.StoredSize = size;
    e.Min = mn;
    e.Max = mx;
    e.Checksum = Format::Crc32(data, size);
    if (!WriteAll(this->Fd, data, size, this->Cursor, this->Error))
    {
      return false;
    }
    const size_t padded = (size + 7) & ~size_t(7);
    if (padded > size)
    {
      const unsigned char zeros[8] = {};
      if (!WriteAll(this->Fd, zeros, padded - size, this->Cursor + size, this->Error))
      {
        return false;
      }
    }
    this->Cursor += padded;
    this->Stats->RawBytes += raw;
    this->Stats->StoredBytes += size;
    ++this->PagesWritten;
    return true;
  }
};
}

void PagePoolWriter::SetDimensions(int nx, int ny, int nz)
{
  this->Dimensions[0] = nx;
  this->Dimensions[1] = ny;
  this->Dimensions[2] = nz;
}

void PagePoolWriter::SetSpacing(double x, double y, double z)
{
  this->Spacing[0] = x;
  this->Spacing[1] = y;
  this->Spacing[2] = z;
}

void PagePoolWriter::SetOrigin(double x, double y, double z)
{
  this->Origin[0] = x;
  this->Origin[1] = y;
  this->Origin[2] = z;
}

void PagePoolWriter::SetDirection(const double direction[9])
{
  std::copy(direction, direction + 9, this->Direction);
}

void PagePoolWriter::SetNoDataValue(double value)
{
  this->HasNoData = true;
  this->NoDataValue = value;
}

bool PagePoolWriter::Write()
{
  this->ErrorMessage.clear();
  this->Stats = Statistics();
  bool ok = false;
  switch (this->Type)
  {
    case ScalarType::UInt8:
      ok = this->WriteTyped<uint8_t>();
      break;
    case ScalarType::UInt16:
      ok = this->WriteTyped<uint16_t>();
      break;
    case ScalarType::Int16:
      ok = this->WriteTyped<int16_t>();
      break;
    case ScalarType::Float32:
      ok = this->WriteTyped<float>();
      break;
    default:
      this->ErrorMessage = "unknown scalar type";
      return false;
  }
  if (!ok && !this->FileName.empty())
  {
    this->ErrorMessage = "cannot write page pool '" + this->FileName + "': " + this->ErrorMessage;
  }
  return ok;
}

namespace
{
// Streams the source's slabs through the converter, perCall at a time (tile pools: a block
// is x, row, layer and a slice x, layer), reporting progress; false with `error` set.
template<typename T>
bool PushSlabs(Converter<T>& conv,
  int slabs,
  int perCall,
  uint64_t pages,
  const PagePoolWriter::SourceCallback& source,
  const PagePoolWriter::ProgressCallback& progress,
  PagePoolWriter::Statistics& stats,
  std::string& error)
{
  const bool tiles = conv.Tiles;
  const int g0 = conv.Levels[0].D[0];
  const int g1 = conv.Levels[0].D[1];
  std::vector<T> block(static_cast<size_t>(perCall) * g0 * g1);
  for (int first = 0; first < slabs; first += perCall)
  {
    const int count = std::min(perCall, slabs - first);
    if (!source(first, count, block.data()))
    {
      error = "the source failed to deliver slabs [" + std::to_string(first) + ", " +
              std::to_string(first + count) + ")";
      return false;
    }
    ++stats.SourceCalls;
    for (int r = 0; r < count; ++r)
    {
      std::vector<T> slice(static_cast<size_t>(g0) * g1);
      if (tiles)
      {
        // Block layout: x, row, layer; slice layout: x, layer.
        for (int layer = 0; layer < g1; ++layer)
        {
          std::copy_n(block.data() + (static_cast<size_t>(layer) * count + r) * g0,
            g0,
            slice.data() + static_cast<size_t>(layer) * g0);
        }
      }
      else
      {
        std::copy_n(block.data() + static_cast<size_t>(r) * g0 * g1, slice.size(), slice.data());
      }
      if (!conv.Push(0, std::move(slice)))
      {
        error = conv.Error;
        return false;
      }
    }
    if (progress)
    {
      progress(0.99 * static_cast<double>(conv.PagesWritten) / pages);
    }
  }
  if (conv.PagesWritten != pages)
  {
    error = "internal error: " + std::to_string(conv.PagesWritten) + " of " +
            std::to_string(pages) + " pages produced";
    return false;
  }

  return true;
}

// Writes the page table and the header into the temporary file, flushes it and renames it
// onto `fileName`; false with `error` set (the temporary file is then removed).
bool Commit(TempFile& temp,
  Format::Header& header,
  const std::vector<Format::PageEntry>& entries,
  uint64_t cursor,
  const double range[2],
  const std::string& fileName,
  std::string& error)
{
  std::vector<unsigned char> table(header.NumberOfPages * Format::EntrySize);
  for (size_t id = 0; id < entries.size(); ++id)
  {
    Format::EncodeEntry(entries[id], table.data() + id * Format::EntrySize);
  }
  header.TableChecksum = Format::Crc32(table.data(), table.size());
  header.FileSize = cursor;
  header.ValueRange[0] = range[0];
  header.ValueRange[1] = range[1];
  unsigned char head[Format::HeaderSize];
  Format::EncodeHeader(header, head);
  if (!WriteAll(temp.Fd, table.data(), table.size(), header.TableOffset, error) ||
      !WriteAll(temp.Fd, head, sizeof(head), 0, error))
  {
    return false;
  }
  if (::fdatasync(temp.Fd) != 0 || ::close(temp.Fd) != 0)
  {
    temp.Fd = -1;
    error = std::string("cannot flush the page pool: ") + std::strerror(errno);
    return false;
  }
  temp.Fd = -1;
  if (::rename(temp.Path.c_str(), fileName.c_str()) != 0)
  {
    error = "cannot rename '" + temp.Path + "': " + std::strerror(errno);
    return false;
  }
  temp.Committed = true;
  return true;
}

}

// The pool's header and levels for the writer's settings; false with ErrorMessage set when a
// setting is missing or absurd.
bool PagePoolWriter::MakeHeader(Format::Header& header, std::vector<Format::Level>& levels)
{
  if (this->FileName.empty())
  {
    this->ErrorMessage = "no file name set";
    return false;
  }
  if (!this->Source)
  {
    this->ErrorMessage = "no source callback set";
    return false;
  }
  if (!HostIsLittleEndian())
  {
    this->ErrorMessage = "big-endian hosts are not supported";
    return false;
  }
  if (!Format::ComputeLevels(
        this->PoolKind, this->Dimensions, this->PageSize, levels, this->ErrorMessage))
  {
    return false;
  }
  if (this->Components < 1 || this->Components > Format::MaxComponents || this->Component < 0 ||
      this->Component >= this->Components ||
      (this->Components > 1 && this->PoolKind != Kind::BrickPool))
  {
    this->ErrorMessage = "component " + std::to_string(this->Component) + " of " +
                         std::to_string(this->Components) + ": a set has 1 to " +
                         std::to_string(Format::MaxComponents) + " brick pools";
    return false;
  }
  header.PoolKind = this->PoolKind;
  header.Type = this->Type;
  header.Version = this->Components > 1 ? Format::ComponentsVersion : Format::Version;
  header.Components = this->Components;
  header.Component = this->Component;
  header.ComponentsTag = this->ComponentsTag;
  std::copy(this->Dimensions, this->Dimensions + 3, header.Dimensions);
  header.PageSize = this->PageSize;
  header.NumberOfLevels = static_cast<int>(levels.size());
  header.PageCompression = this->Compress ? Format::Compression::Zstd : Format::Compression::None;
  header.NumberOfPages = Format::GetNumberOfPages(levels);
  header.TableOffset = Format::HeaderSize;
  header.DataOffset = Format::HeaderSize + header.NumberOfPages * Format::EntrySize;
  std::copy(this->Spacing, this->Spacing + 3, header.Spacing);
  std::copy(this->Origin, this->Origin + 3, header.Origin);
  std::copy(this->Direction, this->Direction + 9, header.Direction);
  header.HasNoDataValue = this->HasNoData;
  header.NoDataValue = this->HasNoData ? this->NoDataValue : 0.0;
  std::string why;
  header.FileSize = header.DataOffset; // provisional, for the geometry checks
  if (!Format::ValidateHeader(header, header.FileSize, why))
  {
    this->ErrorMessage = why;
    return false;
  }

  return true;
}

template<typename T>
bool PagePoolWriter::WriteTyped()
{
  std::vector<Format::Level> levels;
  Format::Header header;
  if (!this->MakeHeader(header, levels))
  {
    return false;
  }
  Converter<T> conv;
  conv.Tiles = this->PoolKind == Kind::TilePool;
  conv.B = this->PageSize;
  conv.Stride = this->PageSize - 1;
  conv.HasNoData = this->HasNoData;
  conv.NoData = this->NoDataValue;
  conv.Compress = this->Compress;
  conv.CompressionLevel = this->CompressionLevel;
  conv.Stats = &this->Stats;
  // Budget of the writer's own buffers (see the class documentation).
  uint64_t fixed = header.NumberOfPages * (sizeof(Format::PageEntry) + Format::EntrySize);
  for (const Format::Level& level : levels)
  {
    typename Converter<T>::LevelState s;
    s.D[0] = level.Dimensions[0];
    s.D[1] = conv.Tiles ? level.Dimensions[2] : level.Dimensions[1];
    s.D[2] = conv.Tiles ? level.Dimensions[1] : level.Dimensions[2];
    s.Pages[0] = level.Pages[0];
    s.Pages[1] = conv.Tiles ? 1 : level.Pages[1];
    s.Pages[2] = conv.Tiles ? level.Pages[1] : level.Pages[2];
    s.FirstPage = level.FirstPage;
    const uint64_t slice = static_cast<uint64_t>(s.D[0]) * s.D[1];
    fixed += (static_cast<uint64_t>(this->PageSize) + 2) * slice * sizeof(T);
    conv.Levels.push_back(std::move(s));
  }
  if (levels.size() > 1)
  {
    // Filter temporaries, reused by every level, so sized by level 0 -> 1.
    const int* fd = conv.Levels[0].D;
    const int* cd = conv.Levels[1].D;
    fixed += (static_cast<uint64_t>(cd[0]) * fd[1] + static_cast<uint64_t>(cd[0]) * cd[1]) *
             sizeof(double);
  }
  const uint64_t pageBytes =
    Format::GetPageValues(this->PoolKind, this->Dimensions, this->PageSize) * sizeof(T);
  fixed += pageBytes + (this->Compress ? ZSTD_compressBound(pageBytes) : 0);
  const int slabs = conv.Levels[0].D[2];
  const uint64_t slabBytes =
    static_cast<uint64_t>(conv.Levels[0].D[0]) * conv.Levels[0].D[1] * sizeof(T);
  const double limit = this->MemoryLimitMB * 1048576.0;
  if (!(limit >= static_cast<double>(fixed + slabBytes)))
  {
    char text[160];
    std::snprintf(text,
      sizeof(text),
      "memory limit %.3f MB is below the %.3f MB this data set needs with page size %d",
      this->MemoryLimitMB,
      static_cast<double>(fixed + slabBytes) / 1048576.0,
      this->PageSize);
    this->ErrorMessage = text;
    return false;
  }
  const int perCall = static_cast<int>(std::min<double>(
    slabs, std::floor((limit - static_cast<double>(fixed)) / static_cast<double>(slabBytes))));
  this->Stats.SlabsPerCall = perCall;
  this->Stats.EstimatedPeakBytes = fixed + static_cast<uint64_t>(perCall) * slabBytes;
  this->Stats.NumberOfPages = header.NumberOfPages;
  conv.Table.resize(header.NumberOfPages);

  TempFile temp;
  temp.Path = this->FileName + ".tmp-" + std::to_string(static_cast<long>(::getpid()));
  temp.Fd = ::open(temp.Path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (temp.Fd < 0)
  {
    this->ErrorMessage = "cannot create '" + temp.Path + "': " + std::strerror(errno);
    temp.Path.clear(); // nothing of ours to remove
    return false;
  }
  conv.Fd = temp.Fd;
  conv.Cursor = header.DataOffset;

  if (!PushSlabs(conv,
        slabs,
        perCall,
        header.NumberOfPages,
        this->Source,
        this->Progress,
        this->Stats,
        this->ErrorMessage))
  {
    return false;
  }
  if (!Commit(
        temp, header, conv.Table, conv.Cursor, conv.Range, this->FileName, this->ErrorMessage))
  {
    return false;
  }
  this->Stats.FileSize = header.FileSize;
  if (this->Progress)
  {
    this->Progress(1.0);
  }
  return true;
}
}
