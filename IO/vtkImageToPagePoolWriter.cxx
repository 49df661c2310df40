// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkImageToPagePoolWriter.h"

#include "StrataPagePoolWriter.h"
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
using Format = strata::PagePoolFormat;

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

/// The upstream end of a conversion: asks the producer for one extent at a time, counting the
/// requests and the errors the producer reports meanwhile (its observer goes with this object).
class UpstreamSlabs
{
public:
  /// `requests` counts the requests made.
  UpstreamSlabs(vtkAlgorithm* producer, int port, vtkIdType& requests)
    : Requests(requests)
    , Producer(producer)
    , Port(port)
  {
    this->OnError->SetCallback(CountError);
    this->OnError->SetClientData(&this->Errors);
    this->Tag = producer->AddObserver(vtkCommand::ErrorEvent, this->OnError);
  }
  ~UpstreamSlabs() { this->Producer->RemoveObserver(this->Tag); }
  UpstreamSlabs(const UpstreamSlabs&) = delete;
  UpstreamSlabs& operator=(const UpstreamSlabs&) = delete;

  /// The producer's data for `extent`; nullptr with a message when the update fails or reports
  /// an error, or its output is no image, does not cover the extent or has no scalars.
  vtkImageData* Request(const int extent[6], std::string& error)
  {
    vtkNew<vtkInformationVector> requests;
    for (int p = 0; p < this->Producer->GetNumberOfOutputPorts(); ++p)
    {
      vtkNew<vtkInformation> info;
      if (p == this->Port)
      {
        info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent, 6);
      }
      requests->Append(info);
    }
    ++this->Requests;
    if (!this->Producer->Update(this->Port, requests) || this->Errors > 0)
    {
      error = "the upstream pipeline failed";
      return nullptr;
    }
    vtkImageData* data =
      vtkImageData::SafeDownCast(this->Producer->GetOutputDataObject(this->Port));
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
  }

  /// Lets go of the last slab: the conversion must not leave a slab of the input in memory. A
  /// trivial producer's output is the caller's own data set, which is left alone.
  void Release()
  {
    vtkDataObject* data = this->Producer->GetOutputDataObject(this->Port);
    if (data && !this->Producer->IsA("vtkTrivialProducer"))
    {
      data->Initialize();
    }
  }

private:
  vtkIdType& Requests;
  vtkAlgorithm* Producer;
  int Port;
  int Errors = 0;
  vtkNew<vtkCallbackCommand> OnError;
  unsigned long Tag = 0;
};

/// What the pools of one conversion share: the input's geometry, tile or brick pool, the
/// streaming axis (y for tiles, z for bricks), the stored type, the number of components (pool
/// files) and the set's tag.
struct PoolLayout
{
  InputGeometry Geometry;
  bool Tiles = false;
  int Axis = 2;
  Format::ScalarType Type = Format::ScalarType::Float32;
  int Components = 1;
  uint32_t SetTag = 0;
};

/// A page writer for component `k` of `layout` into `file`, its settings from `settings`, fed
/// slab by slab from `upstream` (a failed request's message into `sourceError`).
void SetUpComponentWriter(strata::PagePoolWriter& writer,
  vtkImageToPagePoolWriter* settings,
  const PoolLayout& layout,
  const std::string& file,
  int k,
  UpstreamSlabs& upstream,
  std::string& sourceError)
{
  const InputGeometry& g = layout.Geometry;
  writer.SetFileName(file);
  writer.SetKind(layout.Tiles ? Format::Kind::TilePool : Format::Kind::BrickPool);
  writer.SetScalarType(layout.Type);
  writer.SetDimensions(g.Dims[0], g.Dims[1], g.Dims[2]);
  writer.SetSpacing(g.Spacing[0], g.Spacing[1], g.Spacing[2]);
  writer.SetOrigin(g.First[0], g.First[1], g.First[2]);
  writer.SetDirection(g.Direction);
  writer.SetPageSize(settings->GetPageSize());
  writer.SetCompression(settings->GetCompression());
  writer.SetMemoryLimit(settings->GetMemoryLimit());
  writer.SetComponent(k, layout.Components, layout.SetTag);
  // No no-data value: the page writer always leaves NaN (float holes) out of min/max.
  const int axis = layout.Axis;
  writer.SetSource(
    [&g, &upstream, &sourceError, &layout, axis, k](int firstSlab, int count, void* buffer)
    {
      int ext[6];
      std::copy(g.Whole, g.Whole + 6, ext);
      ext[2 * axis] = g.Whole[2 * axis] + firstSlab;
      ext[2 * axis + 1] = g.Whole[2 * axis] + firstSlab + count - 1;
      vtkImageData* data = upstream.Request(ext, sourceError);
      if (!data)
      {
        return false;
      }
      int have[6];
      data->GetExtent(have);
      CopySlab(PickScalars(data), k, have, ext, layout.Type, buffer);
      return true;
    });
}

/// Learns the stored type and the number of components from one slice of the input (not every
/// reader reports its scalar type in its information), warning about components dropped, and
/// draws the set's tag.
bool ProbeLayout(vtkImageToPagePoolWriter* self,
  UpstreamSlabs& upstream,
  PoolLayout& layout,
  std::string& error)
{
  const InputGeometry& g = layout.Geometry;
  layout.Tiles = g.Dims[2] == 1;
  layout.Axis = layout.Tiles ? 1 : 2;
  int slab[6];
  std::copy(g.Whole, g.Whole + 6, slab);
  slab[2 * layout.Axis + 1] = slab[2 * layout.Axis];
  vtkImageData* probe = upstream.Request(slab, error);
  if (!probe)
  {
    return false;
  }
  vtkDataArray* probeArray = PickScalars(probe);
  layout.Type = PoolType(probeArray->GetDataType());
  const int arrayComponents = probeArray->GetNumberOfComponents();
  if (arrayComponents > Format::MaxComponents || (layout.Tiles && arrayComponents > 1))
  {
    vtkWarningWithObjectMacro(self,
      "Input array \"" << (probeArray->GetName() ? probeArray->GetName() : "") << "\" has "
                       << arrayComponents << " components; only the first "
                       << (layout.Tiles ? "is converted (a tile pool holds one)."
                                        : "4 are converted."));
  }
  layout.Components =
    layout.Tiles ? 1 : std::min(std::max(arrayComponents, 1), int(Format::MaxComponents));
  // One write's tag in every file of a set, so that a reader refuses a set mixed from two.
  layout.SetTag =
    std::random_device{}() ^
    static_cast<uint32_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  return true;
}

/// Pages and bytes over the files of a set.
struct WriteTotals
{
  vtkIdType Pages = 0;
  vtkTypeInt64 Bytes = 0;
};

/// Writes every component of `layout` into its file (component k of `name`:
/// strata::PagePoolFormat::GetComponentFileName), reporting progress through `self` over the whole
/// set. The files of components 1, 2, ... come first, so the set appears under `name` only when
/// complete; a failure removes the components already written.
bool WriteComponents(vtkImageToPagePoolWriter* self,
  const std::string& name,
  UpstreamSlabs& upstream,
  const PoolLayout& layout,
  WriteTotals& totals,
  std::string& error)
{
  const int components = layout.Components;
  double last = 0.0;
  self->UpdateProgress(0.0);
  std::vector<std::string> written;
  for (int k = components - 1; k >= 0; --k)
  {
    const std::string file = Format::GetComponentFileName(name, k);
    const int done = components - 1 - k;
    strata::PagePoolWriter writer;
    std::string sourceError;
    SetUpComponentWriter(writer, self, layout, file, k, upstream, sourceError);
    writer.SetProgressCallback(
      [&](double fraction)
      {
        // Kept strictly non-decreasing and short of 1 until the last file is in place.
        fraction = std::min(std::max((done + fraction) / components, last), 0.999);
        if (fraction > last)
        {
          last = fraction;
          self->UpdateProgress(fraction);
        }
      });
    const bool ok = writer.Write();
    upstream.Release();
    if (!ok)
    {
      error = sourceError.empty() ? writer.GetErrorMessage()
                                  : sourceError + " (" + writer.GetErrorMessage() + ")";
      if (components > 1)
        error = "component " + std::to_string(k) + ": " + error;
      for (const std::string& w : written)
        vtksys::SystemTools::RemoveFile(w);
      return false;
    }
    totals.Pages += static_cast<vtkIdType>(writer.GetStatistics().NumberOfPages);
    totals.Bytes += static_cast<vtkTypeInt64>(writer.GetStatistics().FileSize);
    written.push_back(file);
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
  PoolLayout layout;
  std::string error;
  if (!ReadGeometry(producer->GetOutputInformation(port), layout.Geometry, error))
  {
    return fail(error);
  }
  UpstreamSlabs upstream(producer, port, this->NumberOfSlabRequests);
  WriteTotals totals;
  const bool ok = ProbeLayout(this, upstream, layout, error) &&
                  WriteComponents(this, name, upstream, layout, totals, error);
  this->NumberOfPages = totals.Pages;
  this->FileSize = totals.Bytes;
  if (!ok)
  {
    return fail(error);
  }
  this->UpdateProgress(1.0);
  return true;
}
