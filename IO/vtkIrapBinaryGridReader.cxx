// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkIrapBinaryGridReader.h"

#include "vtkFloatArray.h"
#include "vtkObjectFactory.h"

#include <vtksys/FStream.hxx>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkIrapBinaryGridReader);

namespace
{
// Irap's nominal undefined value. RMS and xtgeo write 1e30 instead; anything at least that large
// in magnitude is a hole as well, since no depth, time or thickness comes anywhere near it.
constexpr float IrapUndefined = 9999900.0f;
constexpr float IrapHugeUndefined = 1e30f;

// Grids of 2^31 nodes or more (8 GiB of float32) are far beyond any mapped horizon; such a header
// is taken as corrupt rather than as a reason to allocate that much.
constexpr long long MaxNodes = 2147483647LL;

// The three header records have fixed payload lengths in every Irap binary file.
constexpr int HeaderRecordLength[3] = { 32, 16, 28 };

uint32_t BigEndianWord(const unsigned char* b)
{
  return (uint32_t(b[0]) << 24) | (uint32_t(b[1]) << 16) | (uint32_t(b[2]) << 8) | uint32_t(b[3]);
}

int32_t BigEndianInt(const unsigned char* b)
{
  const uint32_t u = BigEndianWord(b);
  int32_t v;
  std::memcpy(&v, &u, sizeof(v));
  return v;
}

float BigEndianFloat(const unsigned char* b)
{
  const uint32_t u = BigEndianWord(b);
  float v;
  std::memcpy(&v, &u, sizeof(v));
  return v;
}

struct IrapHeader
{
  int NX = 0;
  int NY = 0;
  double XMin = 0.0, XMax = 0.0, YMin = 0.0, YMax = 0.0;
  double XInc = 0.0, YInc = 0.0;
  double Rotation = 0.0, XOrigin = 0.0, YOrigin = 0.0;
};

/// A file of known size read strictly sequentially, so that no record marker can make us seek or
/// read beyond its end.
struct RecordFile
{
  vtksys::ifstream Stream;
  long long Size = 0;
  long long Position = 0;

  bool Open(const char* fileName, std::string& error)
  {
    if (!fileName || !*fileName)
    {
      error = "no file name set";
      return false;
    }
    if (!vtksys::SystemTools::FileExists(fileName, /*isFile=*/true))
    {
      error = "file does not exist or is not a regular file";
      return false;
    }
    this->Stream.open(fileName, std::ios::in | std::ios::binary);
    if (!this->Stream)
    {
      error = "cannot open file";
      return false;
    }
    this->Stream.seekg(0, std::ios::end);
    this->Size = static_cast<long long>(this->Stream.tellg());
    this->Stream.seekg(0, std::ios::beg);
    if (this->Size < 0 || !this->Stream)
    {
      error = "cannot determine the file size";
      return false;
    }
    return true;
  }

  long long Remaining() const { return this->Size - this->Position; }

  bool Read(void* dst, long long n)
  {
    if (n < 0 || n > this->Remaining())
    {
      return false;
    }
    this->Stream.read(static_cast<char*>(dst), static_cast<std::streamsize>(n));
    if (!this->Stream)
    {
      return false;
    }
    this->Position += n;
    return true;
  }

  bool ReadMarker(int32_t& marker)
  {
    unsigned char b[4];
    if (!this->Read(b, 4))
    {
      return false;
    }
    marker = BigEndianInt(b);
    return true;
  }
};

/// Reads and checks the three header records; on success the file is at the first value record.
bool ReadHeader(RecordFile& file, IrapHeader& h, std::string& error)
{
  unsigned char payload[3][32];
  for (int r = 0; r < 3; ++r)
  {
    const int expected = HeaderRecordLength[r];
    int32_t lead = 0;
    int32_t trail = 0;
    std::ostringstream msg;
    if (!file.ReadMarker(lead))
    {
      msg << "file ends before header record " << (r + 1) << " (file size " << file.Size
          << " bytes)";
      error = msg.str();
      return false;
    }
    if (lead != expected)
    {
      msg << "header record " << (r + 1) << " has length marker " << lead << ", expected "
          << expected << ": not an Irap binary grid (or not a big-endian one)";
      error = msg.str();
      return false;
    }
    if (!file.Read(payload[r], expected) || !file.ReadMarker(trail))
    {
      msg << "file ends inside header record " << (r + 1) << " (file size " << file.Size
          << " bytes)";
      error = msg.str();
      return false;
    }
    if (trail != lead)
    {
      msg << "header record " << (r + 1) << ": leading length marker " << lead
          << " differs from trailing marker " << trail;
      error = msg.str();
      return false;
    }
  }

  const int32_t id = BigEndianInt(payload[0]);
  if (id != -996)
  {
    std::ostringstream msg;
    msg << "first header word is " << id << ", expected -996 (Irap binary grid id)";
    error = msg.str();
    return false;
  }
  h.NY = BigEndianInt(payload[0] + 4);
  h.XMin = BigEndianFloat(payload[0] + 8);
  h.XMax = BigEndianFloat(payload[0] + 12);
  h.YMin = BigEndianFloat(payload[0] + 16);
  h.YMax = BigEndianFloat(payload[0] + 20);
  h.XInc = BigEndianFloat(payload[0] + 24);
  h.YInc = BigEndianFloat(payload[0] + 28);
  h.NX = BigEndianInt(payload[1]);
  h.Rotation = BigEndianFloat(payload[1] + 4);
  h.XOrigin = BigEndianFloat(payload[1] + 8);
  h.YOrigin = BigEndianFloat(payload[1] + 12);
  // Record 3 holds seven zeros in every writer we know of; its contents carry nothing we use, so
  // it is not checked beyond its markers.

  std::ostringstream msg;
  if (h.NX <= 0 || h.NY <= 0 || static_cast<long long>(h.NX) * h.NY > MaxNodes)
  {
    msg << "absurd grid dimensions nx = " << h.NX << ", ny = " << h.NY
        << " (need 0 < nx * ny < 2^31)";
    error = msg.str();
    return false;
  }
  if (!(h.XInc > 0.0) || !(h.YInc > 0.0) || !std::isfinite(h.XInc) || !std::isfinite(h.YInc))
  {
    msg << "invalid grid increments xinc = " << h.XInc << ", yinc = " << h.YInc
        << " (need finite, positive)";
    error = msg.str();
    return false;
  }
  if (!std::isfinite(h.Rotation) || !std::isfinite(h.XOrigin) || !std::isfinite(h.YOrigin))
  {
    msg << "non-finite rotation or origin in header";
    error = msg.str();
    return false;
  }
  // Cheapest complete truncation test before allocating: the values alone need 4 bytes each, plus
  // at least one pair of markers.
  const long long valueBytes = 4LL * h.NX * h.NY;
  if (file.Remaining() < valueBytes + 8)
  {
    msg << "file truncated: " << h.NX << " x " << h.NY << " values need at least "
        << (valueBytes + 8) << " bytes after the header, only " << file.Remaining() << " remain";
    error = msg.str();
    return false;
  }
  return true;
}

/// Reads value record `record` (its markers checked) into `dst`, the place of value `count` of
/// the grid's `total`; `n` is the number of values it held.
bool ReadValueRecord(RecordFile& file,
  int record,
  vtkIdType count,
  vtkIdType total,
  float* dst,
  vtkIdType& n,
  std::string& error)
{
  int32_t lead = 0;
  int32_t trail = 0;
  std::ostringstream msg;
  if (!file.ReadMarker(lead))
  {
    msg << "file truncated: it ends after " << count << " of " << total << " values (before record "
        << record << ")";
  }
  else if (lead < 0 || lead % 4 != 0)
  {
    msg << "record " << record << " at byte " << (file.Position - 4)
        << " has an invalid length marker " << lead << " (need a non-negative multiple of 4)";
  }
  else if ((n = lead / 4) > total - count)
  {
    msg << "record " << record << " holds " << n << " values but only " << (total - count)
        << " of the " << total << " grid values remain";
  }
  else if (!file.Read(dst, lead))
  {
    msg << "file truncated inside record " << record << " (" << lead << " bytes declared, "
        << file.Remaining() << " remain)";
  }
  else if (!file.ReadMarker(trail))
  {
    msg << "file truncated: record " << record << " has no trailing length marker";
  }
  else if (trail != lead)
  {
    msg << "record " << record << ": leading length marker " << lead
        << " differs from trailing marker " << trail;
  }
  error = msg.str();
  return error.empty();
}

/// Turns `n` big-endian floats in place into host floats, holes NaN; returns the holes.
vtkIdType ConvertValues(float* values, vtkIdType n, double nullValue)
{
  const bool hasNull = !std::isnan(nullValue);
  const float null = static_cast<float>(nullValue);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  vtkIdType holes = 0;
  for (vtkIdType k = 0; k < n; ++k)
  {
    float v = BigEndianFloat(reinterpret_cast<const unsigned char*>(values + k));
    // The negated comparison also catches NaN and infinities already in the file.
    if (!(std::fabs(v) < IrapHugeUndefined) || v == IrapUndefined || (hasNull && v == null))
    {
      v = nan;
      ++holes;
    }
    values[k] = v;
  }
  return holes;
}

/// Reads the `total` values that follow the header, over records of any length, into `dst`;
/// `noData` counts the holes. Progress is reported about 50 times per file, never per record:
/// some writers put a handful of values in each record.
bool ReadValueRecords(RecordFile& file,
  vtkIdType total,
  double nullValue,
  const std::function<void(double)>& progress,
  float* dst,
  vtkIdType& noData,
  std::string& error)
{
  const vtkIdType progressStep = std::max<vtkIdType>(total / 50, 1);
  vtkIdType nextProgress = progressStep;
  vtkIdType count = 0;
  noData = 0;
  for (int record = 4; count < total; ++record)
  {
    vtkIdType n = 0;
    if (!ReadValueRecord(file, record, count, total, dst + count, n, error))
    {
      return false;
    }
    noData += ConvertValues(dst + count, n, nullValue);
    count += n;
    if (count >= nextProgress)
    {
      progress(static_cast<double>(count) / total);
      nextProgress = count + progressStep;
    }
  }
  // Bytes after the last value (some writers pad) are not part of the grid and are ignored.
  return true;
}
}

//------------------------------------------------------------------------------
vtkIrapBinaryGridReader::vtkIrapBinaryGridReader() = default;

//------------------------------------------------------------------------------
vtkIrapBinaryGridReader::~vtkIrapBinaryGridReader() = default;

//------------------------------------------------------------------------------
bool vtkIrapBinaryGridReader::CanReadFile(const char* fileName)
{
  RecordFile file;
  std::string error;
  if (!file.Open(fileName, error))
  {
    return false;
  }
  unsigned char b[12];
  return file.Read(b, 12) && BigEndianInt(b) == HeaderRecordLength[0] &&
         BigEndianInt(b + 4) == -996;
}

//------------------------------------------------------------------------------
void vtkIrapBinaryGridReader::ResetResults()
{
  this->Superclass::ResetResults();
  this->XMin = this->XMax = this->YMin = this->YMax = 0.0;
  this->XInc = this->YInc = 0.0;
  this->XOrigin = this->YOrigin = 0.0;
  this->Rotation = 0.0;
}

//------------------------------------------------------------------------------
bool vtkIrapBinaryGridReader::ReadGridInformation(std::string& error)
{
  RecordFile file;
  IrapHeader h;
  if (!file.Open(this->FileName, error) || !ReadHeader(file, h, error))
  {
    return false;
  }
  this->NX = h.NX;
  this->NY = h.NY;
  this->XMin = h.XMin;
  this->XMax = h.XMax;
  this->YMin = h.YMin;
  this->YMax = h.YMax;
  this->XInc = h.XInc;
  this->YInc = h.YInc;
  this->XOrigin = h.XOrigin;
  this->YOrigin = h.YOrigin;
  this->Rotation = h.Rotation;
  this->GridOrigin[0] = h.XOrigin;
  this->GridOrigin[1] = h.YOrigin;
  this->GridSpacing[0] = h.XInc;
  this->GridSpacing[1] = h.YInc;
  this->GridRotation = h.Rotation;
  return true;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDataArray> vtkIrapBinaryGridReader::ReadGridValues(std::string& error)
{
  this->NumberOfNoDataValues = 0;
  // The header is read again rather than trusted from RequestInformation: the file may have
  // changed in between, and the value records must be read from the same open stream anyway.
  RecordFile file;
  IrapHeader h;
  if (!file.Open(this->FileName, error) || !ReadHeader(file, h, error))
  {
    return nullptr;
  }
  if (h.NX != this->NX || h.NY != this->NY)
  {
    error = "grid dimensions changed since the information pass";
    return nullptr;
  }
  const vtkIdType total = static_cast<vtkIdType>(h.NX) * h.NY;
  vtkSmartPointer<vtkDataArray> values = NewValues(VTK_FLOAT, total, error);
  if (!values)
  {
    return nullptr;
  }
  vtkIdType noData = 0;
  this->UpdateProgress(0.0);
  if (!ReadValueRecords(
        file,
        total,
        this->NullValue,
        [this](double fraction) { this->UpdateProgress(fraction); },
        static_cast<vtkFloatArray*>(values.GetPointer())->GetPointer(0),
        noData,
        error))
  {
    return nullptr;
  }
  this->GridOrigin[0] = h.XOrigin;
  this->GridOrigin[1] = h.YOrigin;
  this->GridSpacing[0] = h.XInc;
  this->GridSpacing[1] = h.YInc;
  this->GridRotation = h.Rotation;
  this->NumberOfNoDataValues = noData;
  return values;
}

//------------------------------------------------------------------------------
void vtkIrapBinaryGridReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "XMin: " << this->XMin << "\n";
  os << indent << "XMax: " << this->XMax << "\n";
  os << indent << "YMin: " << this->YMin << "\n";
  os << indent << "YMax: " << this->YMax << "\n";
  os << indent << "XInc: " << this->XInc << "\n";
  os << indent << "YInc: " << this->YInc << "\n";
  os << indent << "XOrigin: " << this->XOrigin << "\n";
  os << indent << "YOrigin: " << this->YOrigin << "\n";
  os << indent << "Rotation: " << this->Rotation << "\n";
}
