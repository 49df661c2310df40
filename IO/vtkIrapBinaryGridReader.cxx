// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkIrapBinaryGridReader.h"
#include "vtkStrataGridReaderUtilities.h"

#include "vtkDataObject.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <vtksys/FStream.hxx>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkIrapBinaryGridReader);

namespace
{
using strata_io::ClearOutput;
using strata_io::SetGridGeometry;
using strata_io::SetGridInformation;
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

}

//------------------------------------------------------------------------------
vtkIrapBinaryGridReader::vtkIrapBinaryGridReader()
  : NullValue(std::numeric_limits<double>::quiet_NaN())
{
  this->SetNumberOfInputPorts(0);
  this->SetArrayName("depth");
}

//------------------------------------------------------------------------------
vtkIrapBinaryGridReader::~vtkIrapBinaryGridReader()
{
  this->SetFileName(nullptr);
  this->SetArrayName(nullptr);
}

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
void vtkIrapBinaryGridReader::ResetHeader()
{
  this->NX = 0;
  this->NY = 0;
  this->XMin = this->XMax = this->YMin = this->YMax = 0.0;
  this->XInc = this->YInc = 0.0;
  this->XOrigin = this->YOrigin = 0.0;
  this->Rotation = 0.0;
}

//------------------------------------------------------------------------------
int vtkIrapBinaryGridReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  RecordFile file;
  IrapHeader h;
  std::string error;
  if (!file.Open(this->FileName, error) || !ReadHeader(file, h, error))
  {
    this->ResetHeader();
    this->NumberOfNoDataValues = 0;
    ClearOutput(outInfo);
    vtkErrorMacro("Cannot read Irap binary grid \"" << (this->FileName ? this->FileName : "")
                                                    << "\": " << error);
    return 0;
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

  const double origin[2] = { h.XOrigin, h.YOrigin };
  const double spacing[2] = { h.XInc, h.YInc };
  SetGridInformation(outInfo, h.NX, h.NY, origin, spacing, h.Rotation, VTK_FLOAT);
  return 1;
}

//------------------------------------------------------------------------------
int vtkIrapBinaryGridReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  this->NumberOfNoDataValues = 0;
  if (!output)
  {
    vtkErrorMacro("No vtkImageData output to fill.");
    return 0;
  }
  output->Initialize();

  const char* name = this->FileName ? this->FileName : "";
  auto fail = [&](const std::string& error)
  {
    ClearOutput(outInfo);
    vtkErrorMacro("Cannot read Irap binary grid \"" << name << "\": " << error);
    return 0;
  };

  // The header is read again rather than trusted from RequestInformation: the file may have
  // changed in between, and the value records must be read from the same open stream anyway.
  RecordFile file;
  IrapHeader h;
  std::string error;
  if (!file.Open(this->FileName, error) || !ReadHeader(file, h, error))
  {
    return fail(error);
  }
  if (h.NX != this->NX || h.NY != this->NY)
  {
    return fail("grid dimensions changed since the information pass");
  }

  const vtkIdType total = static_cast<vtkIdType>(h.NX) * h.NY;
  vtkNew<vtkFloatArray> values;
  values->SetName(this->ArrayName);
  values->SetNumberOfTuples(total);
  if (values->GetNumberOfTuples() != total)
  {
    return fail("cannot allocate the grid values");
  }
  float* dst = values->GetPointer(0);

  const bool hasNull = !std::isnan(this->NullValue);
  const float nullValue = static_cast<float>(this->NullValue);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  vtkIdType count = 0;
  vtkIdType noData = 0;
  int record = 3;
  // Progress is reported about 50 times per file, never per record: some writers put a handful
  // of values in each record.
  const vtkIdType progressStep = std::max<vtkIdType>(total / 50, 1);
  vtkIdType nextProgress = progressStep;
  this->UpdateProgress(0.0);
  while (count < total)
  {
    ++record;
    int32_t lead = 0;
    int32_t trail = 0;
    std::ostringstream msg;
    if (!file.ReadMarker(lead))
    {
      msg << "file truncated: it ends after " << count << " of " << total
          << " values (before record " << record << ")";
      return fail(msg.str());
    }
    if (lead < 0 || lead % 4 != 0)
    {
      msg << "record " << record << " at byte " << (file.Position - 4)
          << " has an invalid length marker " << lead << " (need a non-negative multiple of 4)";
      return fail(msg.str());
    }
    const vtkIdType n = lead / 4;
    if (n > total - count)
    {
      msg << "record " << record << " holds " << n << " values but only " << (total - count)
          << " of the " << total << " grid values remain";
      return fail(msg.str());
    }
    if (!file.Read(dst + count, lead))
    {
      msg << "file truncated inside record " << record << " (" << lead << " bytes declared, "
          << file.Remaining() << " remain)";
      return fail(msg.str());
    }
    if (!file.ReadMarker(trail))
    {
      msg << "file truncated: record " << record << " has no trailing length marker";
      return fail(msg.str());
    }
    if (trail != lead)
    {
      msg << "record " << record << ": leading length marker " << lead
          << " differs from trailing marker " << trail;
      return fail(msg.str());
    }
    for (vtkIdType k = count; k < count + n; ++k)
    {
      float v = BigEndianFloat(reinterpret_cast<const unsigned char*>(dst + k));
      // The negated comparison also catches NaN and infinities already in the file.
      if (!(std::fabs(v) < IrapHugeUndefined) || v == IrapUndefined || (hasNull && v == nullValue))
      {
        v = nan;
        ++noData;
      }
      dst[k] = v;
    }
    count += n;
    if (count >= nextProgress)
    {
      this->UpdateProgress(static_cast<double>(count) / total);
      nextProgress = count + progressStep;
    }
  }
  // Bytes after the last value (some writers pad) are not part of the grid and are ignored.

  const double gridOrigin[2] = { h.XOrigin, h.YOrigin };
  const double gridSpacing[2] = { h.XInc, h.YInc };
  SetGridGeometry(output, h.NX, h.NY, gridOrigin, gridSpacing, h.Rotation);
  output->GetPointData()->SetScalars(values);
  this->NumberOfNoDataValues = noData;
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkIrapBinaryGridReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ArrayName: " << (this->ArrayName ? this->ArrayName : "(none)") << "\n";
  os << indent << "NullValue: " << this->NullValue << "\n";
  os << indent << "NX: " << this->NX << "\n";
  os << indent << "NY: " << this->NY << "\n";
  os << indent << "XMin: " << this->XMin << "\n";
  os << indent << "XMax: " << this->XMax << "\n";
  os << indent << "YMin: " << this->YMin << "\n";
  os << indent << "YMax: " << this->YMax << "\n";
  os << indent << "XInc: " << this->XInc << "\n";
  os << indent << "YInc: " << this->YInc << "\n";
  os << indent << "XOrigin: " << this->XOrigin << "\n";
  os << indent << "YOrigin: " << this->YOrigin << "\n";
  os << indent << "Rotation: " << this->Rotation << "\n";
  os << indent << "NumberOfNoDataValues: " << this->NumberOfNoDataValues << "\n";
}
