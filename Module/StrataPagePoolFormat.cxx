// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataPagePoolFormat.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace strata
{

namespace
{
const char Magic[8] = { 'S', 'T', 'R', 'A', 'T', 'A', 'P', 'P' };

// Byte-wise little-endian stores and loads: independent of the host's byte order and of
// alignment.
void PutU32(unsigned char* p, uint32_t v)
{
  for (int b = 0; b < 4; ++b)
  {
    p[b] = static_cast<unsigned char>(v >> (8 * b));
  }
}
void PutU64(unsigned char* p, uint64_t v)
{
  for (int b = 0; b < 8; ++b)
  {
    p[b] = static_cast<unsigned char>(v >> (8 * b));
  }
}
void PutF32(unsigned char* p, float v)
{
  uint32_t u;
  std::memcpy(&u, &v, 4);
  PutU32(p, u);
}
void PutF64(unsigned char* p, double v)
{
  uint64_t u;
  std::memcpy(&u, &v, 8);
  PutU64(p, u);
}
uint32_t GetU32(const unsigned char* p)
{
  uint32_t v = 0;
  for (int b = 0; b < 4; ++b)
  {
    v |= static_cast<uint32_t>(p[b]) << (8 * b);
  }
  return v;
}
uint64_t GetU64(const unsigned char* p)
{
  uint64_t v = 0;
  for (int b = 0; b < 8; ++b)
  {
    v |= static_cast<uint64_t>(p[b]) << (8 * b);
  }
  return v;
}
float GetF32(const unsigned char* p)
{
  const uint32_t u = GetU32(p);
  float v;
  std::memcpy(&v, &u, 4);
  return v;
}
double GetF64(const unsigned char* p)
{
  const uint64_t u = GetU64(p);
  double v;
  std::memcpy(&v, &u, 8);
  return v;
}

std::array<uint32_t, 256> MakeCrcTable()
{
  std::array<uint32_t, 256> table{};
  for (uint32_t n = 0; n < 256; ++n)
  {
    uint32_t c = n;
    for (int k = 0; k < 8; ++k)
    {
      c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    }
    table[n] = c;
  }
  return table;
}

int PagesAlong(int n, int stride)
{
  return n <= 1 ? 1 : static_cast<int>((static_cast<int64_t>(n) - 1 + stride - 1) / stride);
}

constexpr size_t HeaderCrcOffset = 252;
}

int PagePoolFormat::GetScalarSize(ScalarType type)
{
  switch (type)
  {
    case ScalarType::UInt8:
      return 1;
    case ScalarType::UInt16:
    case ScalarType::Int16:
      return 2;
    case ScalarType::Float32:
      return 4;
  }
  return 0;
}

const char* PagePoolFormat::GetScalarTypeName(ScalarType type)
{
  switch (type)
  {
    case ScalarType::UInt8:
      return "uint8";
    case ScalarType::UInt16:
      return "uint16";
    case ScalarType::Int16:
      return "int16";
    case ScalarType::Float32:
      return "float32";
  }
  return "unknown";
}

bool PagePoolFormat::ComputeLevels(Kind kind,
  const int dims[3],
  int pageSize,
  std::vector<Level>& levels,
  std::string& error)
{
  levels.clear();
  for (int a = 0; a < 3; ++a)
  {
    if (dims[a] < 1 || dims[a] > MaxDimension)
    {
      error = "dimension " + std::to_string(a) + " is " + std::to_string(dims[a]) +
              ", not in [1, " + std::to_string(MaxDimension) + "]";
      return false;
    }
  }
  if (pageSize < MinPageSize || pageSize > MaxPageSize)
  {
    error = "page size " + std::to_string(pageSize) + " is not in [" + std::to_string(MinPageSize) +
            ", " + std::to_string(MaxPageSize) + "]";
    return false;
  }
  if (kind != Kind::BrickPool && kind != Kind::TilePool)
  {
    error = "unknown pool kind " + std::to_string(static_cast<uint32_t>(kind));
    return false;
  }
  if (GetPageValues(kind, dims, pageSize) * 4 > MaxPageBytes)
  {
    error = "a page of " + std::to_string(pageSize) + "^2 x " + std::to_string(dims[2]) +
            " layers exceeds " + std::to_string(MaxPageBytes) + " bytes";
    return false;
  }
  const int stride = pageSize - 1;
  const int paged = kind == Kind::BrickPool ? 3 : 2;
  int n[3] = { dims[0], dims[1], dims[2] };
  uint64_t first = 0;
  for (;;)
  {
    Level level;
    for (int a = 0; a < 3; ++a)
    {
      level.Dimensions[a] = n[a];
      level.Pages[a] = a < paged ? PagesAlong(n[a], stride) : 1;
    }
    level.FirstPage = first;
    const uint64_t count = static_cast<uint64_t>(level.Pages[0]) * level.Pages[1] * level.Pages[2];
    first += count;
    levels.push_back(level);
    // Page ids are 32-bit in the table and ints in strata::VolumeBrickTree and on the GPU.
    if (first > static_cast<uint64_t>(INT32_MAX))
    {
      error =
        "page size " + std::to_string(pageSize) + " makes more than 2^31 pages; use larger pages";
      levels.clear();
      return false;
    }
    if (count == 1)
    {
      return true;
    }
    for (int a = 0; a < paged; ++a)
    {
      n[a] = n[a] > 1 ? n[a] / 2 + 1 : 1;
    }
  }
}

uint64_t PagePoolFormat::GetPageValues(Kind kind, const int dims[3], int pageSize)
{
  const uint64_t b = static_cast<uint64_t>(pageSize);
  return kind == Kind::BrickPool ? b * b * b : b * b * static_cast<uint64_t>(dims[2]);
}

uint64_t PagePoolFormat::GetNumberOfPages(const std::vector<Level>& levels)
{
  if (levels.empty())
  {
    return 0;
  }
  const Level& last = levels.back();
  return last.FirstPage + static_cast<uint64_t>(last.Pages[0]) * last.Pages[1] * last.Pages[2];
}

uint32_t PagePoolFormat::Crc32(const void* data, size_t size, uint32_t crc)
{
  static const std::array<uint32_t, 256> table = MakeCrcTable();
  const unsigned char* p = static_cast<const unsigned char*>(data);
  uint32_t c = crc ^ 0xFFFFFFFFu;
  for (size_t i = 0; i < size; ++i)
  {
    c = table[(c ^ p[i]) & 0xFFu] ^ (c >> 8);
  }
  return c ^ 0xFFFFFFFFu;
}

void PagePoolFormat::EncodeHeader(const Header& h, unsigned char out[HeaderSize])
{
  std::memset(out, 0, HeaderSize);
  std::memcpy(out, Magic, 8);
  PutU32(out + 8, h.Version);
  PutU32(out + 12, static_cast<uint32_t>(HeaderSize));
  PutU32(out + 16, static_cast<uint32_t>(h.PoolKind));
  PutU32(out + 20, static_cast<uint32_t>(h.Type));
  for (int a = 0; a < 3; ++a)
  {
    PutU32(out + 24 + 4 * a, static_cast<uint32_t>(h.Dimensions[a]));
  }
  PutU32(out + 36, static_cast<uint32_t>(h.PageSize));
  PutU32(out + 40, static_cast<uint32_t>(h.NumberOfLevels));
  PutU32(out + 44, static_cast<uint32_t>(h.PageCompression));
  PutU64(out + 48, h.NumberOfPages);
  PutU64(out + 56, h.TableOffset);
  PutU64(out + 64, h.DataOffset);
  PutU64(out + 72, h.FileSize);
  for (int a = 0; a < 3; ++a)
  {
    PutF64(out + 80 + 8 * a, h.Spacing[a]);
    PutF64(out + 104 + 8 * a, h.Origin[a]);
  }
  for (int a = 0; a < 9; ++a)
  {
    PutF64(out + 128 + 8 * a, h.Direction[a]);
  }
  PutF64(out + 200, h.ValueRange[0]);
  PutF64(out + 208, h.ValueRange[1]);
  PutF64(out + 216, h.NoDataValue);
  PutU32(out + 224, h.HasNoDataValue ? 1u : 0u);
  PutU32(out + 232, h.TableChecksum);
  if (h.Version >= ComponentsVersion)
  {
    PutU32(out + 228, static_cast<uint32_t>(h.Components));
    PutU32(out + 236, static_cast<uint32_t>(h.Component));
    PutU32(out + 240, h.ComponentsTag);
  }
  PutU32(out + HeaderCrcOffset, Crc32(out, HeaderCrcOffset));
}

void PagePoolFormat::DecodeHeader(const unsigned char in[HeaderSize], Header& h)
{
  h.Version = GetU32(in + 8);
  h.PoolKind = static_cast<Kind>(GetU32(in + 16));
  h.Type = static_cast<ScalarType>(GetU32(in + 20));
  for (int a = 0; a < 3; ++a)
  {
    h.Dimensions[a] = static_cast<int>(GetU32(in + 24 + 4 * a));
  }
  h.PageSize = static_cast<int>(GetU32(in + 36));
  h.NumberOfLevels = static_cast<int>(GetU32(in + 40));
  h.PageCompression = static_cast<Compression>(GetU32(in + 44));
  h.NumberOfPages = GetU64(in + 48);
  h.TableOffset = GetU64(in + 56);
  h.DataOffset = GetU64(in + 64);
  h.FileSize = GetU64(in + 72);
  for (int a = 0; a < 3; ++a)
  {
    h.Spacing[a] = GetF64(in + 80 + 8 * a);
    h.Origin[a] = GetF64(in + 104 + 8 * a);
  }
  for (int a = 0; a < 9; ++a)
  {
    h.Direction[a] = GetF64(in + 128 + 8 * a);
  }
  h.ValueRange[0] = GetF64(in + 200);
  h.ValueRange[1] = GetF64(in + 208);
  h.NoDataValue = GetF64(in + 216);
  h.HasNoDataValue = GetU32(in + 224) != 0;
  h.TableChecksum = GetU32(in + 232);
  const bool set = h.Version >= ComponentsVersion;
  h.Components = set ? static_cast<int>(std::min<uint32_t>(GetU32(in + 228), 1u << 30)) : 1;
  h.Component = set ? static_cast<int>(std::min<uint32_t>(GetU32(in + 236), 1u << 30)) : 0;
  h.ComponentsTag = set ? GetU32(in + 240) : 0;
}

void PagePoolFormat::EncodeEntry(const PageEntry& e, unsigned char out[EntrySize])
{
  PutU32(out, e.Level);
  PutU32(out + 4, e.Index);
  PutU64(out + 8, e.Offset);
  PutU64(out + 16, e.StoredSize);
  PutF32(out + 24, e.Min);
  PutF32(out + 28, e.Max);
  PutU32(out + 32, e.Checksum);
  PutU32(out + 36, static_cast<uint32_t>(e.PageEncoding));
}

void PagePoolFormat::DecodeEntry(const unsigned char in[EntrySize], PageEntry& e)
{
  e.Level = GetU32(in);
  e.Index = GetU32(in + 4);
  e.Offset = GetU64(in + 8);
  e.StoredSize = GetU64(in + 16);
  e.Min = GetF32(in + 24);
  e.Max = GetF32(in + 28);
  e.Checksum = GetU32(in + 32);
  e.PageEncoding = static_cast<Encoding>(GetU32(in + 36));
}

bool PagePoolFormat::ValidateHeaderBytes(const unsigned char in[HeaderSize],
  uint64_t fileSize,
  Header& header,
  std::string& error)
{
  if (std::memcmp(in, Magic, 8) != 0)
  {
    error = "not a Strata page pool (bad magic number)";
    return false;
  }
  const uint32_t version = GetU32(in + 8);
  if (version != Version && version != ComponentsVersion)
  {
    error = "unsupported page pool version " + std::to_string(version) + " (this reader reads " +
            std::to_string(Version) + " and " + std::to_string(ComponentsVersion) + ")";
    return false;
  }
  if (GetU32(in + 12) != HeaderSize)
  {
    error =
      "header size " + std::to_string(GetU32(in + 12)) + " is not " + std::to_string(HeaderSize);
    return false;
  }
  const uint32_t stored = GetU32(in + HeaderCrcOffset);
  const uint32_t computed = Crc32(in, HeaderCrcOffset);
  if (stored != computed)
  {
    error = "header checksum mismatch: the header is corrupt";
    return false;
  }
  DecodeHeader(in, header);
  return ValidateHeader(header, fileSize, error);
}

bool PagePoolFormat::ValidateHeader(const Header& h, uint64_t fileSize, std::string& error)
{
  if (h.Version != Version && h.Version != ComponentsVersion)
  {
    error = "unsupported page pool version " + std::to_string(h.Version);
    return false;
  }
  if (h.Version == ComponentsVersion &&
      (h.Components < 2 || h.Components > MaxComponents || h.Component < 0 ||
        h.Component >= h.Components || h.PoolKind != Kind::BrickPool))
  {
    error = "component " + std::to_string(h.Component) + " of " + std::to_string(h.Components) +
            ": a set of components has 2 to " + std::to_string(MaxComponents) + " brick pools";
    return false;
  }
  if (h.Version == Version && (h.Components != 1 || h.Component != 0))
  {
    error = "a version 1 pool has one component";
    return false;
  }
  if (h.PoolKind != Kind::BrickPool && h.PoolKind != Kind::TilePool)
  {
    error = "unknown pool kind " + std::to_string(static_cast<uint32_t>(h.PoolKind));
    return false;
  }
  if (GetScalarSize(h.Type) == 0)
  {
    error = "unknown scalar type " + std::to_string(static_cast<uint32_t>(h.Type));
    return false;
  }
  if (h.PageCompression != Compression::None && h.PageCompression != Compression::Zstd)
  {
    error = "unknown compression " + std::to_string(static_cast<uint32_t>(h.PageCompression));
    return false;
  }
  std::vector<Level> levels;
  std::string why;
  if (!ComputeLevels(h.PoolKind, h.Dimensions, h.PageSize, levels, why))
  {
    error = "absurd header: " + why;
    return false;
  }
  if (static_cast<size_t>(h.NumberOfLevels) != levels.size())
  {
    error = "header says " + std::to_string(h.NumberOfLevels) + " levels, dimensions imply " +
            std::to_string(levels.size());
    return false;
  }
  const uint64_t pages = GetNumberOfPages(levels);
  if (h.NumberOfPages != pages)
  {
    error = "header says " + std::to_string(h.NumberOfPages) + " pages, dimensions imply " +
            std::to_string(pages);
    return false;
  }
  if (h.TableOffset != HeaderSize || h.DataOffset != HeaderSize + pages * EntrySize)
  {
    error = "page table or data offset inconsistent with the page count";
    return false;
  }
  if (h.FileSize != fileSize)
  {
    error = (fileSize < h.FileSize ? "truncated file: " : "file size mismatch: ") +
            std::string("header says ") + std::to_string(h.FileSize) + " bytes, file has " +
            std::to_string(fileSize);
    return false;
  }
  if (h.FileSize < h.DataOffset)
  {
    error = "file size " + std::to_string(h.FileSize) + " is smaller than the page table";
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!(h.Spacing[a] > 0) || !std::isfinite(h.Spacing[a]) || !std::isfinite(h.Origin[a]))
    {
      error = "spacing must be finite and positive, origin finite";
      return false;
    }
  }
  for (double d : h.Direction)
  {
    if (!std::isfinite(d))
    {
      error = "direction matrix is not finite";
      return false;
    }
  }
  return true;
}

std::string PagePoolFormat::GetComponentFileName(const std::string& name, int c)
{
  if (c == 0)
    return name;
  const std::string suffix = ".c" + std::to_string(c);
  const size_t n = name.size();
  return n > 4 && name.compare(n - 4, 4, ".spp") == 0 ? name.substr(0, n - 4) + suffix + ".spp"
                                                      : name + suffix;
}

bool PagePoolFormat::CheckComponent(const Header& first,
  const Header& other,
  int c,
  std::string& error)
{
  const bool sameGeometry = std::equal(first.Spacing, first.Spacing + 3, other.Spacing) &&
                            std::equal(first.Origin, first.Origin + 3, other.Origin) &&
                            std::equal(first.Direction, first.Direction + 9, other.Direction);
  const std::string what = other.Components != first.Components         ? "the number of components"
                           : other.Component != c                       ? "the component it holds"
                           : other.ComponentsTag != first.ComponentsTag ? "the write (its tag)"
                           : other.PoolKind != first.PoolKind           ? "the kind"
                           : other.Type != first.Type                   ? "the scalar type"
                           : !std::equal(first.Dimensions, first.Dimensions + 3, other.Dimensions)
                             ? "the dimensions"
                           : other.PageSize != first.PageSize ? "the page size"
                           : !sameGeometry ? "the geometry (spacing, origin, direction)"
                                           : "";
  if (what.empty())
    return true;
  error = "component " + std::to_string(c) + " differs from component 0 in " + what;
  return false;
}

bool PagePoolFormat::ValidateTable(const Header& h,
  const std::vector<PageEntry>& table,
  std::string& error)
{
  std::vector<Level> levels;
  if (!ComputeLevels(h.PoolKind, h.Dimensions, h.PageSize, levels, error) ||
      table.size() != GetNumberOfPages(levels))
  {
    error = "page table does not match the header";
    return false;
  }
  const uint64_t raw = GetPageValues(h.PoolKind, h.Dimensions, h.PageSize) * GetScalarSize(h.Type);
  size_t id = 0;
  for (size_t l = 0; l < levels.size(); ++l)
  {
    const uint64_t count =
      static_cast<uint64_t>(levels[l].Pages[0]) * levels[l].Pages[1] * levels[l].Pages[2];
    for (uint64_t i = 0; i < count; ++i, ++id)
    {
      const PageEntry& e = table[id];
      const std::string name = "page " + std::to_string(id) + " (level " + std::to_string(l) +
                               ", index " + std::to_string(i) + ")";
      if (e.Level != l || e.Index != i)
      {
        error = name + ": table entry names level " + std::to_string(e.Level) + ", index " +
                std::to_string(e.Index);
        return false;
      }
      if (e.PageEncoding != Encoding::Raw &&
          !(e.PageEncoding == Encoding::Zstd && h.PageCompression == Compression::Zstd))
      {
        error = name + ": unknown or disallowed encoding " +
                std::to_string(static_cast<uint32_t>(e.PageEncoding));
        return false;
      }
      if (e.Offset < h.DataOffset || e.Offset % 8 != 0 || e.StoredSize == 0 ||
          e.StoredSize > h.FileSize || e.Offset > h.FileSize - e.StoredSize)
      {
        error = name + ": offset " + std::to_string(e.Offset) + " + size " +
                std::to_string(e.StoredSize) + " lies outside the data area (file has " +
                std::to_string(h.FileSize) + " bytes)";
        return false;
      }
      if ((e.PageEncoding == Encoding::Raw && e.StoredSize != raw) ||
          (e.PageEncoding == Encoding::Zstd && e.StoredSize > 2 * raw + 1024))
      {
        error = name + ": stored size " + std::to_string(e.StoredSize) +
                " does not fit a page of " + std::to_string(raw) + " bytes";
        return false;
      }
    }
  }
  return true;
}
}
