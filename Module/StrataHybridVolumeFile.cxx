// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataHybridVolumeFile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace strata
{

static_assert(sizeof(HybridVolumeFile::Point) == HybridVolumeFile::PointSize,
  "points are written as they lie in memory");

namespace
{
constexpr char Magic[8] = { 'S', 'T', 'R', 'H', 'Y', 'V', 'O', 'L' };
constexpr size_t ChecksumOffset = 152;

bool LittleEndianHost()
{
  const uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

struct Fnv
{
  uint64_t Hash = 1469598103934665603ull;
  void Add(const void* data, size_t n)
  {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i)
    {
      this->Hash = (this->Hash ^ p[i]) * 1099511628211ull;
    }
  }
};

template<typename T>
void Put(unsigned char* h, size_t offset, T v)
{
  std::memcpy(h + offset, &v, sizeof(T));
}

template<typename T>
T Get(const unsigned char* h, size_t offset)
{
  T v;
  std::memcpy(&v, h + offset, sizeof(T));
  return v;
}

uint8_t Quantize(double v)
{
  // [-1, 1] to [0, 255], rounded to nearest.
  const double q = std::floor((v * 0.5 + 0.5) * 255.0 + 0.5);
  return static_cast<uint8_t>(std::min(255.0, std::max(0.0, q)));
}

double Sign(double v)
{
  return v < 0 ? -1.0 : 1.0;
}
}

int HybridVolumeFile::GetLowResolutionDimension(int n, int f)
{
  if (n <= 1 || f <= 0)
  {
    return 1;
  }
  return (n - 2) / f + 2; // ceil((n - 1) / f) + 1
}

float HybridVolumeFile::GetLowResolutionValue(int i, int j, int k) const
{
  const int* d = this->LowDimensions;
  i = std::min(std::max(i, 0), d[0] - 1);
  j = std::min(std::max(j, 0), d[1] - 1);
  k = std::min(std::max(k, 0), d[2] - 1);
  return this->LowResolution[(static_cast<size_t>(k) * d[1] + j) * d[0] + i];
}

double HybridVolumeFile::Reconstruct(double x, double y, double z) const
{
  const double p[3] = { x, y, z };
  int c[3];
  double t[3];
  for (int a = 0; a < 3; ++a)
  {
    const double u = p[a] / this->Factor[a];
    if (this->LowDimensions[a] < 2)
    {
      c[a] = 0;
      t[a] = 0;
      continue;
    }
    c[a] = std::min(std::max(static_cast<int>(std::floor(u)), 0), this->LowDimensions[a] - 2);
    t[a] = u - c[a];
  }
  double v = 0;
  for (int dz = 0; dz < 2; ++dz)
  {
    for (int dy = 0; dy < 2; ++dy)
    {
      for (int dx = 0; dx < 2; ++dx)
      {
        const double w = (dx ? t[0] : 1 - t[0]) * (dy ? t[1] : 1 - t[1]) * (dz ? t[2] : 1 - t[2]);
        if (w != 0)
        {
          v += w * this->GetLowResolutionValue(c[0] + dx, c[1] + dy, c[2] + dz);
        }
      }
    }
  }
  return v;
}

uint16_t HybridVolumeFile::EncodeNormal(double nx, double ny, double nz)
{
  const double l1 = std::fabs(nx) + std::fabs(ny) + std::fabs(nz);
  if (!(l1 > 0) || !std::isfinite(l1))
  {
    nx = 0;
    ny = 0;
    nz = 1;
  }
  else
  {
    nx /= l1;
    ny /= l1;
    nz /= l1;
  }
  double u = nx, v = ny;
  if (nz < 0)
  {
    u = (1 - std::fabs(ny)) * Sign(nx);
    v = (1 - std::fabs(nx)) * Sign(ny);
  }
  return static_cast<uint16_t>((Quantize(u) << 8) | Quantize(v));
}

void HybridVolumeFile::DecodeNormal(uint16_t code, double n[3])
{
  double x = (code >> 8) / 255.0 * 2 - 1;
  double y = (code & 0xFF) / 255.0 * 2 - 1;
  const double z = 1 - std::fabs(x) - std::fabs(y);
  if (z < 0)
  {
    const double ox = x;
    x = (1 - std::fabs(y)) * Sign(ox);
    y = (1 - std::fabs(ox)) * Sign(y);
  }
  const double l = std::sqrt(x * x + y * y + z * z);
  n[0] = x / l;
  n[1] = y / l;
  n[2] = z / l;
}

std::string HybridVolumeFile::Validate() const
{
  for (int a = 0; a < 3; ++a)
  {
    const std::string axis = std::string(1, static_cast<char>('x' + a));
    const int n = this->Dimensions[a];
    if (n < 1 || n > MaximumDimension)
    {
      return "dimension " + axis + " = " + std::to_string(n) + " is not in [1, 65536]";
    }
    const int f = this->Factor[a];
    if (f != 1 && f != 2 && f != 4 && f != 8)
    {
      return "factor " + axis + " = " + std::to_string(f) + " is not 1, 2, 4 or 8";
    }
    if (this->LowDimensions[a] != GetLowResolutionDimension(n, f))
    {
      return "low-resolution dimension " + axis + " = " + std::to_string(this->LowDimensions[a]) +
             " does not match dimension " + std::to_string(n) + " and factor " + std::to_string(f);
    }
    if (this->ErrorGridStep[a] < 1 || this->ErrorGridStep[a] > n)
    {
      return "error grid step " + axis + " = " + std::to_string(this->ErrorGridStep[a]) +
             " is not in [1, " + std::to_string(n) + "]";
    }
    if (!std::isfinite(this->Spacing[a]) || !(this->Spacing[a] > 0) ||
        !std::isfinite(this->Origin[a]))
    {
      return "spacing or origin along " + axis + " is not finite and positive";
    }
  }
  if (static_cast<uint32_t>(this->Filter) > 3)
  {
    return "unknown filter " + std::to_string(static_cast<uint32_t>(this->Filter));
  }
  if (std::isnan(this->OverestimationBound) || std::isnan(this->Threshold))
  {
    return "over-estimation bound or threshold is NaN";
  }
  return std::string();
}

bool HybridVolumeFile::Write(const std::string& path)
{
  this->ErrorMessage = this->Validate();
  const size_t lowCount =
    static_cast<size_t>(this->LowDimensions[0]) * this->LowDimensions[1] * this->LowDimensions[2];
  if (this->ErrorMessage.empty() && this->LowResolution.size() != lowCount)
  {
    this->ErrorMessage = "low-resolution volume holds " +
                         std::to_string(this->LowResolution.size()) + " values, expected " +
                         std::to_string(lowCount);
  }
  if (this->ErrorMessage.empty() && !LittleEndianHost())
  {
    this->ErrorMessage = "writing on a big-endian host is not supported";
  }
  if (!this->ErrorMessage.empty())
  {
    this->ErrorMessage = "cannot write " + path + ": " + this->ErrorMessage;
    return false;
  }

  unsigned char h[HeaderSize] = {};
  std::memcpy(h, Magic, 8);
  Put<uint32_t>(h, 8, FormatVersion);
  Put<uint32_t>(h, 12, HeaderSize);
  for (int a = 0; a < 3; ++a)
  {
    Put<int32_t>(h, 16 + 4 * a, this->Dimensions[a]);
    Put<int32_t>(h, 28 + 4 * a, this->Factor[a]);
    Put<int32_t>(h, 40 + 4 * a, this->LowDimensions[a]);
    Put<int32_t>(h, 52 + 4 * a, this->ErrorGridStep[a]);
    Put<double>(h, 64 + 8 * a, this->Spacing[a]);
    Put<double>(h, 88 + 8 * a, this->Origin[a]);
  }
  Put<uint32_t>(h, 112, static_cast<uint32_t>(this->Filter));
  Put<uint32_t>(h, 116, PointSize);
  Put<double>(h, 120, this->OverestimationBound);
  Put<double>(h, 128, this->Threshold);
  Put<uint64_t>(h, 136, this->PointBudget);
  Put<uint64_t>(h, 144, static_cast<uint64_t>(this->Points.size()));
  Fnv fnv;
  fnv.Add(h, ChecksumOffset);
  fnv.Add(this->LowResolution.data(), lowCount * sizeof(float));
  fnv.Add(this->Points.data(), this->Points.size() * sizeof(Point));
  Put<uint64_t>(h, ChecksumOffset, fnv.Hash);

  const std::string partial = path + ".partial";
  std::FILE* f = std::fopen(partial.c_str(), "wb");
  if (!f)
  {
    this->ErrorMessage = "cannot create " + partial;
    return false;
  }
  bool ok = std::fwrite(h, 1, HeaderSize, f) == HeaderSize;
  ok = ok && std::fwrite(this->LowResolution.data(), sizeof(float), lowCount, f) == lowCount;
  ok = ok && std::fwrite(this->Points.data(), sizeof(Point), this->Points.size(), f) ==
               this->Points.size();
  ok = (std::fflush(f) == 0) && ok;
  ok = (std::fclose(f) == 0) && ok;
  if (!ok || std::rename(partial.c_str(), path.c_str()) != 0)
  {
    std::remove(partial.c_str());
    this->ErrorMessage = "cannot write " + path + " (disk full or not writable?)";
    return false;
  }
  return true;
}

bool HybridVolumeFile::Read(const std::string& path)
{
  *this = HybridVolumeFile();
  auto fail = [&](const std::string& why)
  {
    const std::string message = path + ": " + why;
    *this = HybridVolumeFile();
    this->ErrorMessage = message;
    return false;
  };
  if (!LittleEndianHost())
  {
    return fail("reading on a big-endian host is not supported");
  }
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f)
  {
    return fail("cannot open");
  }
  struct Closer
  {
    std::FILE* F;
    ~Closer() { std::fclose(this->F); }
  } closer{ f };
  if (std::fseek(f, 0, SEEK_END) != 0)
  {
    return fail("cannot seek");
  }
  const long end = std::ftell(f);
  std::rewind(f);
  if (end < 0)
  {
    return fail("cannot tell its size");
  }
  const uint64_t fileSize = static_cast<uint64_t>(end);
  unsigned char h[HeaderSize];
  if (fileSize < HeaderSize || std::fread(h, 1, HeaderSize, f) != HeaderSize)
  {
    return fail("truncated header (" + std::to_string(fileSize) + " bytes, header needs 160)");
  }
  if (std::memcmp(h, Magic, 8) != 0)
  {
    return fail("not a Strata hybrid volume (bad magic)");
  }
  const uint32_t version = Get<uint32_t>(h, 8);
  if (version != FormatVersion)
  {
    return fail("format version " + std::to_string(version) + " is not supported (expected 1)");
  }
  if (Get<uint32_t>(h, 12) != HeaderSize || Get<uint32_t>(h, 116) != PointSize)
  {
    return fail("header size or point size does not match version 1 (160 and 16 bytes)");
  }
  for (int a = 0; a < 3; ++a)
  {
    this->Dimensions[a] = Get<int32_t>(h, 16 + 4 * a);
    this->Factor[a] = Get<int32_t>(h, 28 + 4 * a);
    this->LowDimensions[a] = Get<int32_t>(h, 40 + 4 * a);
    this->ErrorGridStep[a] = Get<int32_t>(h, 52 + 4 * a);
    this->Spacing[a] = Get<double>(h, 64 + 8 * a);
    this->Origin[a] = Get<double>(h, 88 + 8 * a);
  }
  this->Filter = static_cast<FilterType>(Get<uint32_t>(h, 112));
  this->OverestimationBound = Get<double>(h, 120);
  this->Threshold = Get<double>(h, 128);
  this->PointBudget = Get<uint64_t>(h, 136);
  const uint64_t pointCount = Get<uint64_t>(h, 144);
  const std::string invalid = this->Validate();
  if (!invalid.empty())
  {
    return fail("corrupt header: " + invalid);
  }
  // Dimensions are at most 65536, so lowCount * 4 < 2^51: no overflow. The point count is
  // checked against the file size before it is multiplied.
  const uint64_t lowCount = static_cast<uint64_t>(this->LowDimensions[0]) *
                            static_cast<uint64_t>(this->LowDimensions[1]) *
                            static_cast<uint64_t>(this->LowDimensions[2]);
  const uint64_t lowBytes = lowCount * sizeof(float);
  if (fileSize < HeaderSize + lowBytes ||
      (fileSize - HeaderSize - lowBytes) / PointSize < pointCount ||
      fileSize != HeaderSize + lowBytes + pointCount * PointSize)
  {
    return fail("file is " + std::to_string(fileSize) + " bytes, the header announces " +
                std::to_string(lowCount) + " low-resolution values and " +
                std::to_string(pointCount) + " points (truncated or corrupt)");
  }
  this->LowResolution.resize(static_cast<size_t>(lowCount));
  this->Points.resize(static_cast<size_t>(pointCount));
  if (std::fread(this->LowResolution.data(), sizeof(float), lowCount, f) != lowCount ||
      std::fread(this->Points.data(), sizeof(Point), pointCount, f) != pointCount)
  {
    return fail("read error");
  }
  Fnv fnv;
  fnv.Add(h, ChecksumOffset);
  fnv.Add(this->LowResolution.data(), lowBytes);
  fnv.Add(this->Points.data(), pointCount * PointSize);
  if (fnv.Hash != Get<uint64_t>(h, ChecksumOffset))
  {
    return fail("checksum mismatch (corrupt file)");
  }
  for (const Point& p : this->Points)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (p.Position[a] >= this->Dimensions[a])
      {
        return fail("point outside the volume (corrupt file)");
      }
    }
  }
  return true;
}
}
