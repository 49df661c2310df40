// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStreamingMetaImageReader.h"
#include "StrataGridReaderUtilities.h"

#include "vtkByteSwap.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkEndian.h" // For VTK_WORDS_BIGENDIAN
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <vtksys/FStream.hxx>
#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkStreamingMetaImageReader);

namespace
{
/// A header is text; a "line" longer than this is binary data, never a key.
constexpr size_t MaxHeaderLine = 1 << 16;
// Bounds that keep the data's byte count in 64 bits; no volume comes near them.
constexpr int MaxChannels = 1 << 16;
constexpr double MaxDataBytes = 4611686018427387904.0; // 2^62

std::string Trim(const std::string& s)
{
  const size_t first = s.find_first_not_of(" \t\r\n");
  const size_t last = s.find_last_not_of(" \t\r\n");
  return first == std::string::npos ? std::string() : s.substr(first, last - first + 1);
}

bool IsTrue(const std::string& value)
{
  std::string v = value;
  std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return std::tolower(c); });
  return v == "true" || v == "1";
}

/// VTK type and size of a MetaImage ElementType; VTK_VOID for an unknown one.
int ScalarType(const std::string& element, int& size)
{
  static const struct
  {
    const char* Name;
    int Type;
    int Size;
  } types[] = { { "MET_UCHAR", VTK_UNSIGNED_CHAR, 1 },
    { "MET_CHAR", VTK_SIGNED_CHAR, 1 },
    { "MET_USHORT", VTK_UNSIGNED_SHORT, 2 },
    { "MET_SHORT", VTK_SHORT, 2 },
    { "MET_UINT", VTK_UNSIGNED_INT, 4 },
    { "MET_INT", VTK_INT, 4 },
    { "MET_FLOAT", VTK_FLOAT, 4 },
    { "MET_DOUBLE", VTK_DOUBLE, 8 } };
  for (const auto& t : types)
  {
    if (element == t.Name)
    {
      size = t.Size;
      return t.Type;
    }
  }
  size = 0;
  return VTK_VOID;
}
}

/// The parsed header: where the samples are and what they are.
class vtkStreamingMetaImageReader::vtkInternals
{
public:
  int Dimensions[3] = { 1, 1, 1 };
  double Spacing[3] = { 1, 1, 1 };
  double Origin[3] = { 0, 0, 0 };
  int Type = VTK_VOID;
  int TypeSize = 0;
  int Channels = 1;
  bool BigEndian = false;
  bool Compressed = false;
  bool OneFile = true;
  std::string DataPath;
  long long DataOffset = 0;

  /// Reads the header of `path`; false with `error` if it is not a MetaImage this reader knows.
  bool Parse(const std::string& path, std::string& error);
  bool Streamable() const { return !this->Compressed && this->OneFile; }
  /// Bytes of the samples, or -1 beyond 2^62 (no file is that large, and nothing overflows).
  long long DataBytes() const
  {
    constexpr long long limit = 1LL << 62;
    long long bytes = static_cast<long long>(this->Channels) * this->TypeSize;
    for (int a = 0; a < 3; ++a)
    {
      if (bytes > limit / this->Dimensions[a])
      {
        return -1;
      }
      bytes *= this->Dimensions[a];
    }
    return bytes;
  }
};

//------------------------------------------------------------------------------
bool vtkStreamingMetaImageReader::vtkInternals::Parse(const std::string& path, std::string& error)
{
  *this = vtkInternals();
  vtksys::ifstream in(path.c_str(), std::ios::in | std::ios::binary);
  if (!in)
  {
    error = "cannot open it";
    return false;
  }
  int dims = 0;
  std::vector<long long> sizes;
  bool haveSpacing = false;
  long long headerSize = 0;
  std::string element, dataFile;
  std::string line;
  while (dataFile.empty() && std::getline(in, line) && line.size() < MaxHeaderLine)
  {
    const size_t eq = line.find('=');
    if (eq == std::string::npos)
    {
      continue;
    }
    const std::string key = Trim(line.substr(0, eq));
    const std::string value = Trim(line.substr(eq + 1));
    std::istringstream v(value);
    if (key == "NDims")
    {
      v >> dims;
    }
    else if (key == "DimSize")
    {
      for (long long n; v >> n;)
      {
        sizes.push_back(n);
      }
    }
    else if (key == "ElementType")
    {
      element = value;
    }
    else if (key == "ElementNumberOfChannels")
    {
      v >> this->Channels;
    }
    else if (key == "ElementSpacing" || (key == "ElementSize" && !haveSpacing))
    {
      haveSpacing = key == "ElementSpacing";
      for (int a = 0; a < 3 && v >> this->Spacing[a]; ++a)
      {
      }
    }
    else if (key == "Offset" || key == "Position" || key == "Origin")
    {
      for (int a = 0; a < 3 && v >> this->Origin[a]; ++a)
      {
      }
    }
    else if (key == "BinaryDataByteOrderMSB" || key == "ElementByteOrderMSB")
    {
      this->BigEndian = IsTrue(value);
    }
    else if (key == "CompressedData")
    {
      this->Compressed = IsTrue(value);
    }
    else if (key == "HeaderSize")
    {
      v >> headerSize;
    }
    else if (key == "ElementDataFile")
    {
      // The last key: with LOCAL, the data start right after this line.
      dataFile = value.empty() ? std::string("?") : value;
      this->DataOffset = static_cast<long long>(in.tellg());
    }
  }
  if (dataFile.empty())
  {
    error = "no ElementDataFile key (not a MetaImage header?)";
    return false;
  }
  if (dims < 2 || dims > 3 || static_cast<int>(sizes.size()) != dims)
  {
    error = "NDims must be 2 or 3 and DimSize must give as many sizes";
    return false;
  }
  for (int a = 0; a < dims; ++a)
  {
    if (sizes[a] < 1 || sizes[a] > INT_MAX)
    {
      error = "DimSize " + std::to_string(sizes[a]) + " is out of range";
      return false;
    }
    this->Dimensions[a] = static_cast<int>(sizes[a]);
  }
  this->Type = ScalarType(element, this->TypeSize);
  if (this->Type == VTK_VOID || this->Channels < 1 || this->Channels > MaxChannels)
  {
    error = "ElementType \"" + element + "\" or ElementNumberOfChannels is not supported";
    return false;
  }
  // DataBytes() multiplies in 64 bits: sizes up to 2^31 each would overflow it.
  const double bytes = static_cast<double>(this->Dimensions[0]) * this->Dimensions[1] *
                       (dims > 2 ? this->Dimensions[2] : 1) * this->Channels * this->TypeSize;
  if (bytes > MaxDataBytes)
  {
    std::ostringstream msg;
    msg << "DimSize";
    for (int a = 0; a < dims; ++a)
    {
      msg << " " << this->Dimensions[a];
    }
    msg << " of " << this->Channels << " x " << this->TypeSize << "-byte values is " << bytes
        << " bytes, more than 2^62 bytes (beyond any file)";
    error = msg.str();
    return false;
  }
  // A list ("LIST") or a pattern ("slice%03d.raw 1 40 1") names several data files.
  this->OneFile = dataFile != "LIST" && dataFile.find('%') == std::string::npos;
  if (dataFile == "LOCAL")
  {
    this->DataPath = path;
    return true;
  }
  this->DataPath =
    vtksys::SystemTools::FileIsFullPath(dataFile)
      ? dataFile
      : vtksys::SystemTools::CollapseFullPath(dataFile, vtksys::SystemTools::GetFilenamePath(path));
  const long long fileSize =
    static_cast<long long>(vtksys::SystemTools::FileLength(this->DataPath));
  this->DataOffset = headerSize >= 0 ? headerSize : fileSize - this->DataBytes();
  return true;
}

//------------------------------------------------------------------------------
vtkStreamingMetaImageReader::vtkStreamingMetaImageReader()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkStreamingMetaImageReader::~vtkStreamingMetaImageReader()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
void vtkStreamingMetaImageReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

//------------------------------------------------------------------------------
bool vtkStreamingMetaImageReader::IsStreamable(const char* fileName)
{
  vtkInternals header;
  std::string error;
  return fileName && header.Parse(fileName, error) && header.Streamable();
}

//------------------------------------------------------------------------------
int vtkStreamingMetaImageReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInternals& in = *this->Internals;
  const std::string name = this->FileName ? this->FileName : "";
  std::string error;
  if (name.empty())
  {
    error = "no file name set";
  }
  else if (in.Parse(name, error) && !in.Streamable())
  {
    error = "its data are compressed or in several files, which cannot be read slab by slab "
            "(read it whole with vtkMetaImageReader)";
  }
  else if (error.empty() && (in.DataOffset < 0 ||
                              static_cast<long long>(vtksys::SystemTools::FileLength(in.DataPath)) <
                                in.DataOffset + in.DataBytes()))
  {
    error = "data file \"" + in.DataPath + "\" is shorter than the " +
            std::to_string(in.DataBytes()) + " bytes the header describes";
  }
  if (!error.empty())
  {
    strata_io::ClearOutput(outInfo);
    vtkErrorMacro("Cannot read MetaImage \"" << name << "\": " << error);
    return 0;
  }
  const int extent[6] = {
    0, in.Dimensions[0] - 1, 0, in.Dimensions[1] - 1, 0, in.Dimensions[2] - 1
  };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), in.Spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), in.Origin, 3);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, in.Type, in.Channels);
  return 1;
}

//------------------------------------------------------------------------------
int vtkStreamingMetaImageReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  const vtkInternals& in = *this->Internals;
  int extent[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent);
  output->Initialize();
  if (extent[0] > extent[1] || extent[2] > extent[3] || extent[4] > extent[5])
  {
    return 1;
  }
  output->SetExtent(extent);
  output->SetSpacing(in.Spacing);
  output->SetOrigin(in.Origin);
  output->AllocateScalars(in.Type, in.Channels);
  vtkDataArray* scalars = output->GetPointData()->GetScalars();
  scalars->SetName("MetaImage");

  vtksys::ifstream file(in.DataPath.c_str(), std::ios::in | std::ios::binary);
  const long long value = static_cast<long long>(in.TypeSize) * in.Channels;
  const long long row = (extent[1] - extent[0] + 1) * value;
  auto* out = static_cast<char*>(scalars->GetVoidPointer(0));
  for (int z = extent[4]; z <= extent[5] && file; ++z)
  {
    for (int y = extent[2]; y <= extent[3] && file; ++y, out += row)
    {
      const long long index =
        (static_cast<long long>(z) * in.Dimensions[1] + y) * in.Dimensions[0] + extent[0];
      file.seekg(in.DataOffset + index * value);
      file.read(out, row);
    }
    this->UpdateProgress(static_cast<double>(z - extent[4] + 1) / (extent[5] - extent[4] + 1));
  }
  if (!file)
  {
    output->Initialize();
    vtkErrorMacro("Cannot read MetaImage \"" << this->FileName << "\": reading \"" << in.DataPath
                                             << "\" failed");
    return 0;
  }
#ifdef VTK_WORDS_BIGENDIAN
  const bool hostBigEndian = true;
#else
  const bool hostBigEndian = false;
#endif
  if (in.TypeSize > 1 && in.BigEndian != hostBigEndian)
  {
    vtkByteSwap::SwapVoidRange(
      scalars->GetVoidPointer(0), scalars->GetNumberOfValues(), in.TypeSize);
  }
  return 1;
}
