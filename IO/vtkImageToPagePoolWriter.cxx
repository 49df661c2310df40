// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkImageToPagePoolWriter.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPagePoolWriter.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkImageToPagePoolWriter);

namespace
{
using Format = vtkPagePoolFormat;

vtkDataArray* PickScalars(vtkImageData* image)
{
  if (!image)
  {
    return nullptr;
  }
  vtkPointData* pd = image->GetPointData();
  vtkDataArray* a = pd->GetScalars();
  if (!a)
  {
    for (int i = 0; i < pd->GetNumberOfArrays() && !a; ++i)
    {
      a = pd->GetArray(i);
    }
  }
  return a;
}

/// Pool type of a VTK scalar type: the four the format stores as they are, float otherwise.
Format::ScalarType PoolType(int vtkType)
{
  switch (vtkType)
  {
    case VTK_UNSIGNED_CHAR:
      return Format::ScalarType::UInt8;
    case VTK_UNSIGNED_SHORT:
      return Format::ScalarType::UInt16;
    case VTK_SHORT:
      return Format::ScalarType::Int16;
    default:
      return Format::ScalarType::Float32;
  }
}

/// Copies component `c` of `n` tuples starting at tuple `first` into `out`, converting.
template<typename In, typename Out>
void CopyRow(const In* in, int components, int c, vtkIdType first, vtkIdType n, Out* out)
{
  const In* p = in + first * components + c;
  for (vtkIdType i = 0; i < n; ++i)
  {
    out[i] = static_cast<Out>(p[i * components]);
  }
}

template<typename Out>
void CopyRowAny(vtkDataArray* array, int c, vtkIdType first, vtkIdType n, Out* out)
{
  void* data = array->GetVoidPointer(0);
  const int nc = array->GetNumberOfComponents();
  switch (array->GetDataType())
  {
    vtkTemplateMacro(CopyRow(static_cast<const VTK_TT*>(data), nc, c, first, n, out));
  }
}

void CopySlab(vtkDataArray* array,
  int c,
  const int dataExtent[6],
  const int slab[6],
  Format::ScalarType type,
  void* buffer)
{
  const vtkIdType dx = dataExtent[1] - dataExtent[0] + 1;
  const vtkIdType dy = dataExtent[3] - dataExtent[2] + 1;
  const vtkIdType nx = slab[1] - slab[0] + 1;
  vtkIdType row = 0;
  for (int k = slab[4]; k <= slab[5]; ++k)
  {
    for (int j = slab[2]; j <= slab[3]; ++j, ++row)
    {
      const vtkIdType first =
        ((k - dataExtent[4]) * dy + (j - dataExtent[2])) * dx + (slab[0] - dataExtent[0]);
      switch (type)
      {
        case Format::ScalarType::UInt8:
          CopyRowAny(array, c, first, nx, static_cast<uint8_t*>(buffer) + row * nx);
          break;
        case Format::ScalarType::UInt16:
          CopyRowAny(array, c, first, nx, static_cast<uint16_t*>(buffer) + row * nx);
          break;
        case Format::ScalarType::Int16:
          CopyRowAny(array, c, first, nx, static_cast<int16_t*>(buffer) + row * nx);
          break;
        case Format::ScalarType::Float32:
          CopyRowAny(array, c, first, nx, static_cast<float*>(buffer) + row * nx);
          break;
      }
    }
  }
}

/// What a pool takes from its input's information: the whole extent, its dimensions, the
/// spacing and direction, and the world position of the extent's first point (the origin).
struct InputGeometry
{
  int Whole[6] = { 0, -1, 0, -1, 0, -1 };
  int Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  double First[3] = { 0, 0, 0 };
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
};

bool ReadGeometry(vtkInformation* info, InputGeometry& g, std::string& error)
{
  if (!info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    error = "the input reports no whole extent (did its reader fail?)";
    return false;
  }
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), g.Whole);
  for (int a = 0; a < 3; ++a)
    g.Dims[a] = g.Whole[2 * a + 1] - g.Whole[2 * a] + 1;
  if (g.Dims[0] <= 0 || g.Dims[1] <= 0 || g.Dims[2] <= 0)
  {
    error = "the input is empty (did its reader fail?)";
    return false;
  }
  double origin[3] = { 0, 0, 0 };
  if (info->Has(vtkDataObject::SPACING()))
    info->Get(vtkDataObject::SPACING(), g.Spacing);
  if (info->Has(vtkDataObject::ORIGIN()))
    info->Get(vtkDataObject::ORIGIN(), origin);
  if (info->Has(vtkDataObject::DIRECTION()))
    info->Get(vtkDataObject::DIRECTION(), g.Direction);
  for (int r = 0; r < 3; ++r)
  {
    g.First[r] = origin[r];
    for (int c = 0; c < 3; ++c)
      g.First[r] += g.Direction[3 * r + c] * g.Whole[2 * c] * g.Spacing[c];
  }
  return true;
}

/// Counts the errors an upstream algorithm reports: several VTK readers report a missing or
/// short file with vtkErrorMacro and still let the request succeed, with garbage data.
void CountError(vtkObject*, unsigned long, void* clientData, void*)
{
  ++*static_cast<int*>(clientData);
}

bool Contains(const int outer[6], const int inner[6])
{
  for (int a = 0; a < 3; ++a)
  {
    if (inner[2 * a] < outer[2 * a] || inner[2 * a + 1] > outer[2 * a + 1])
    {
      return false;
    }
  }
  return true;
}
}

//------------------------------------------------------------------------------
vtkImageToPagePoolWriter::vtkImageToPagePoolWriter()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(0);
}

//------------------------------------------------------------------------------
vtkImageToPagePoolWriter::~vtkImageToPagePoolWriter()
{
  this->SetFileName(nullptr);
}

//------------------------------------------------------------------------------
void vtkImageToPagePoolWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "PageSize: " << this->PageSize << "\n";
  os << indent << "Compression: " << this->Compression << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MB\n";
  os << indent << "NumberOfPages: " << this->NumberOfPages << "\n";
  os << indent << "FileSize: " << this->FileSize << "\n";
  os << indent << "NumberOfSlabRequests: " << this->NumberOfSlabRequests << "\n";
}

//------------------------------------------------------------------------------
int vtkImageToPagePoolWriter::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector*)
{
  // The conversion drives the upstream pipeline itself, slab by slab (see Write()).
  return 1;
}

//------------------------------------------------------------------------------
bool vtkImageToPagePoolWriter::Write()
{
  this->NumberOfPages = 0;
  this->FileSize = 0;
  this->NumberOfSlabRequests = 0;
  const std::string name = this->FileName ? this->FileName : "";
  auto fail = [&](const std::string& error)
  {
    vtkErrorMacro("Cannot write page pool \"" << name << "\": " << error);
    return false;
  };
  if (name.empty())
  {
    return fail("no file name set");
  }
  vtkAlgorithmOutput* connection =
    this->GetNumberOfInputConnections(0) > 0 ? this->GetInputConnection(0, 0) : nullptr;
  vtkAlgorithm* producer = connection ? connection->GetProducer() : nullptr;
  if (!producer)
  {
    return fail("no input connection");
  }
  const int port = connection->GetIndex();

  // Information only: extent and geometry, no data.
  producer->UpdateInformation();
  InputGeometry geometry;
  std::string geometryError;
  if (!ReadGeometry(producer->GetOutputInformation(port), geometry, geometryError))
  {
    return fail(geometryError);
  }
  const int* whole = geometry.Whole;
  const int* dims = geometry.Dims;
  const double* spacing = geometry.Spacing;
  const double* first = geometry.First;
  const double* direction = geometry.Direction;

  const bool tiles = dims[2] == 1;
  const int axis = tiles ? 1 : 2; // the streaming axis

  int upstreamErrors = 0;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(CountError);
  onError->SetClientData(&upstreamErrors);
  const unsigned long tag = producer->AddObserver(vtkCommand::ErrorEvent, onError);
  struct RemoveObserver
  {
    vtkAlgorithm* Producer;
    unsigned long Tag;
    ~RemoveObserver() { this->Producer->RemoveObserver(this->Tag); }
  } removeObserver{ producer, tag };

  auto request = [&](const int extent[6], std::string& error) -> vtkImageData*
  {
    vtkNew<vtkInformationVector> requests;
    for (int p = 0; p < producer->GetNumberOfOutputPorts(); ++p)
    {
      vtkNew<vtkInformation> info;
      if (p == port)
      {
        info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent, 6);
      }
      requests->Append(info);
    }
    ++this->NumberOfSlabRequests;
    if (!producer->Update(port, requests) || upstreamErrors > 0)
    {
      error = "the upstream pipeline failed";
      return nullptr;
    }
    vtkImageData* data = vtkImageData::SafeDownCast(producer->GetOutputDataObject(port));
    if (!data)
    {
      error = "the input is not a vtkImageData";
      return nullptr;
    }
    int have[6];
    data->GetExtent(have);
    if (!Contains(have, extent))
    {
      error = "the input did not produce the requested extent";
      return nullptr;
    }
    if (!PickScalars(data))
    {
      error = "the input has no point scalars";
      return nullptr;
    }
    return data;
  };

  // One slice first, to learn the scalar type from the data itself (not every reader reports
  // it in its information).
  std::string error;
  int slab[6];
  std::copy(whole, whole + 6, slab);
  slab[2 * axis + 1] = slab[2 * axis];
  vtkImageData* probe = request(slab, error);
  if (!probe)
  {
    return fail(error);
  }
  vtkDataArray* probeArray = PickScalars(probe);
  const Format::ScalarType type = PoolType(probeArray->GetDataType());
  const int arrayComponents = probeArray->GetNumberOfComponents();
  if (arrayComponents > Format::MaxComponents || (tiles && arrayComponents > 1))
  {
    vtkWarningMacro("Input array \""
                    << (probeArray->GetName() ? probeArray->GetName() : "") << "\" has "
                    << arrayComponents << " components; only the first "
                    << (tiles ? "is converted (a tile pool holds one)." : "4 are converted."));
  }
  const int components =
    tiles ? 1 : std::min(std::max(arrayComponents, 1), int(Format::MaxComponents));
  // One write's tag in every file of a set, so that a reader refuses a set mixed from two.
  const uint32_t setTag =
    std::random_device{}() ^
    static_cast<uint32_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  double last = 0.0;
  this->UpdateProgress(0.0);
  // Component k of `components` into `file`; progress over the set's files.
  auto writeComponent = [&](const std::string& file, int k, int done, std::string& error)
  {
    vtkPagePoolWriter writer;
    writer.SetFileName(file);
    writer.SetKind(tiles ? Format::Kind::TilePool : Format::Kind::BrickPool);
    writer.SetScalarType(type);
    writer.SetDimensions(dims[0], dims[1], dims[2]);
    writer.SetSpacing(spacing[0], spacing[1], spacing[2]);
    writer.SetOrigin(first[0], first[1], first[2]);
    writer.SetDirection(direction);
    writer.SetPageSize(this->PageSize);
    writer.SetCompression(this->Compression);
    writer.SetMemoryLimit(this->MemoryLimit);
    writer.SetComponent(k, components, setTag);
    // No no-data value: the page writer always leaves NaN (float holes) out of min/max.
    std::string sourceError;
    writer.SetSource(
      [&](int firstSlab, int count, void* buffer)
      {
        int ext[6];
        std::copy(whole, whole + 6, ext);
        ext[2 * axis] = whole[2 * axis] + firstSlab;
        ext[2 * axis + 1] = whole[2 * axis] + firstSlab + count - 1;
        vtkImageData* data = request(ext, sourceError);
        if (!data)
        {
          return false;
        }
        int have[6];
        data->GetExtent(have);
        CopySlab(PickScalars(data), k, have, ext, type, buffer);
        return true;
      });
    writer.SetProgressCallback(
      [&](double fraction)
      {
        // Kept strictly non-decreasing and short of 1 until the last file is in place.
        fraction = std::min(std::max((done + fraction) / components, last), 0.999);
        if (fraction > last)
        {
          last = fraction;
          this->UpdateProgress(fraction);
        }
      });
    const bool ok = writer.Write();
    // Let go of the last slab: the conversion must not leave a slab of the input in memory. A
    // trivial producer's output is the caller's own data set, which is left alone.
    vtkDataObject* data = producer->GetOutputDataObject(port);
    if (data && !producer->IsA("vtkTrivialProducer"))
    {
      data->Initialize();
    }
    if (!ok)
    {
      error = sourceError.empty() ? writer.GetErrorMessage()
                                  : sourceError + " (" + writer.GetErrorMessage() + ")";
      if (components > 1)
        error = "component " + std::to_string(k) + ": " + error;
      return false;
    }
    this->NumberOfPages += static_cast<vtkIdType>(writer.GetStatistics().NumberOfPages);
    this->FileSize += static_cast<vtkTypeInt64>(writer.GetStatistics().FileSize);
    return true;
  };
  // The files of components 1, 2, ... first: the set appears under `name` only when complete,
  // and a failure removes the components already written.
  std::vector<std::string> written;
  for (int k = components - 1; k >= 0; --k)
  {
    const std::string file = Format::GetComponentFileName(name, k);
    const int done = components - 1 - k;
    std::string error;
    if (!writeComponent(file, k, done, error))
    {
      for (const std::string& w : written)
        vtksys::SystemTools::RemoveFile(w);
      return fail(error);
    }
    written.push_back(file);
  }
  this->UpdateProgress(1.0);
  return true;
}
