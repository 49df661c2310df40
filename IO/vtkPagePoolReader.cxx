// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkPagePoolReader.h"
#include "vtkStrataGridReaderUtilities.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkInformationIntegerKey.h"
#include "vtkInformationStringKey.h"
#include "vtkInformationStringVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPagePoolFile.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkType.h"

#include <vtksys/FStream.hxx>
#include <vtksys/SystemInformation.hxx>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPagePoolReader);

namespace
{
using Format = vtkPagePoolFormat;
using strata_io::ClearOutput;

/// The resolution key travels upstream with the update extent, like UPDATE_EXTENT itself, so a
/// filter between the consumer and the reader need not know about it.
class vtkPagePoolResolutionKey : public vtkInformationDoubleKey
{
public:
  vtkPagePoolResolutionKey(const char* name, const char* location)
    : vtkInformationDoubleKey(name, location)
  {
  }
  void CopyDefaultInformation(vtkInformation* request,
    vtkInformation* fromInfo,
    vtkInformation* toInfo) override
  {
    if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
    {
      this->ShallowCopy(fromInfo, toInfo);
    }
  }
};

vtkInformationDoubleKey* ResolutionKey =
  new vtkPagePoolResolutionKey("UPDATE_RESOLUTION", "vtkPagePoolReader");

int ToVTKType(Format::ScalarType type)
{
  switch (type)
  {
    case Format::ScalarType::UInt8:
      return VTK_UNSIGNED_CHAR;
    case Format::ScalarType::UInt16:
      return VTK_UNSIGNED_SHORT;
    case Format::ScalarType::Int16:
      return VTK_SHORT;
    case Format::ScalarType::Float32:
      return VTK_FLOAT;
  }
  return VTK_VOID;
}

/// First page whose points include level index p (pages share their last point with the next
/// page's first, so p = i S belongs to page i - 1 as well; the lower one is taken).
// The files of the set of components whose component 0 is `name` (one file for a pool of one
// component); false, with `error`, when one is missing, foreign, or `name` is not component 0.
bool OpenSet(const std::string& name,
  std::vector<std::unique_ptr<vtkPagePoolFile>>& files,
  std::string& error)
{
  files.clear();
  files.push_back(std::make_unique<vtkPagePoolFile>());
  if (!files[0]->Open(name))
  {
    error = files[0]->GetErrorMessage();
    return false;
  }
  const Format::Header& h = files[0]->GetHeader();
  if (h.Component != 0)
  {
    error = "the file is component " + std::to_string(h.Component) + " of a set of " +
            std::to_string(h.Components) + ": open its component 0 (the name without \".c" +
            std::to_string(h.Component) + "\")";
    return false;
  }
  for (int c = 1; c < h.Components; ++c)
  {
    files.push_back(std::make_unique<vtkPagePoolFile>());
    if (!files.back()->OpenComponent(*files[0], c))
    {
      error = files.back()->GetErrorMessage();
      return false;
    }
  }
  return true;
}

// The part of page `at` (page indices; B values a side) inside the output `extent` (level
// indices) into component `c` of `nc` of `dst`. Tile pages are x, y, layer (`layer` >= 0),
// brick pages x, y, z.
void CopyPage(const unsigned char* page,
  const int at[3],
  int B,
  int layer,
  const int extent[6],
  int c,
  int nc,
  int valueSize,
  unsigned char* dst)
{
  const bool tiles = layer >= 0;
  const int S = B - 1;
  const int base[3] = { at[0] * S, at[1] * S, tiles ? 0 : at[2] * S };
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    const int pageHi = a < (tiles ? 2 : 3) ? base[a] + B - 1 : 0;
    lo[a] = std::max(extent[2 * a], base[a]);
    hi[a] = std::min(extent[2 * a + 1], pageHi);
  }
  const vtkIdType ox = extent[1] - extent[0] + 1;
  const vtkIdType oy = extent[3] - extent[2] + 1;
  const int n = hi[0] - lo[0] + 1;
  for (int z = lo[2]; z <= hi[2]; ++z)
  {
    for (int y = lo[1]; y <= hi[1]; ++y)
    {
      const size_t pz = tiles ? static_cast<size_t>(layer) : size_t(z - base[2]);
      const size_t src = ((pz * B + size_t(y - base[1])) * B + size_t(lo[0] - base[0]));
      const vtkIdType out =
        ((vtkIdType(z - extent[4]) * oy + (y - extent[2])) * ox + (lo[0] - extent[0]));
      if (nc == 1)
      {
        std::memcpy(dst + out * valueSize, page + src * valueSize, size_t(n) * valueSize);
        continue;
      }
      for (int i = 0; i < n; ++i)
        std::memcpy(
          dst + ((out + i) * nc + c) * valueSize, page + (src + i) * valueSize, valueSize);
    }
  }
}

int PageOf(int p, int stride, int pages)
{
  const int i = p <= 0 ? 0 : (p - 1) / stride;
  return std::min(i, pages - 1);
}
}

//------------------------------------------------------------------------------
const char* const vtkPagePoolReader::PoolFileNameArray = "PagePoolFileName";
const char* const vtkPagePoolReader::PoolLayerArray = "PagePoolLayer";
const char* const vtkPagePoolReader::PoolSeriesArray = "PagePoolSeries";
const char* const vtkPagePoolReader::PoolTimeStepArray = "PagePoolTimeStep";
vtkInformationKeyMacro(vtkPagePoolReader, POOL_FILE_NAME, String);
vtkInformationKeyMacro(vtkPagePoolReader, POOL_LAYER, Integer);
vtkInformationKeyMacro(vtkPagePoolReader, POOL_TIME_STEP, Integer);
vtkInformationKeyMacro(vtkPagePoolReader, POOL_SERIES, StringVector);

//------------------------------------------------------------------------------
void vtkPagePoolReader::AddTimeStep(const char* fileName, double time)
{
  this->StepFiles.emplace_back(fileName ? fileName : "");
  this->StepTimes.push_back(time);
  this->Modified();
}

void vtkPagePoolReader::RemoveAllTimeSteps()
{
  if (this->StepFiles.empty())
    return;
  this->StepFiles.clear();
  this->StepTimes.clear();
  this->Modified();
}

const char* vtkPagePoolReader::GetTimeStepFileName(int step) const
{
  return step >= 0 && step < this->GetNumberOfTimeSteps() ? this->StepFiles[step].c_str() : nullptr;
}

double vtkPagePoolReader::GetTimeStepValue(int step) const
{
  return step >= 0 && step < this->GetNumberOfTimeSteps() ? this->StepTimes[step] : 0.0;
}

int vtkPagePoolReader::ChooseTimeStep(const double* times, int count, double t)
{
  // The last step at or below t: upper_bound finds the first above it.
  const int above = static_cast<int>(std::upper_bound(times, times + count, t) - times);
  return std::max(0, std::min(above - 1, count - 1));
}

std::string vtkPagePoolReader::SelectPool(vtkInformation* outInfo, int& step)
{
  step = 0;
  if (this->StepFiles.empty())
  {
    outInfo->Remove(POOL_TIME_STEP());
    outInfo->Remove(POOL_SERIES());
    return this->FileName ? this->FileName : "";
  }
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
    step = ChooseTimeStep(this->StepTimes.data(),
      this->GetNumberOfTimeSteps(),
      outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()));
  outInfo->Set(POOL_TIME_STEP(), step);
  outInfo->Remove(POOL_SERIES());
  for (const std::string& file : this->StepFiles)
    outInfo->Append(POOL_SERIES(), file.c_str());
  return this->StepFiles[step];
}

bool vtkPagePoolReader::CheckSeries(std::string& error) const
{
  Format::Header first;
  int firstLevels = 0;
  for (int i = 0; i < this->GetNumberOfTimeSteps(); ++i)
  {
    const std::string step = "time step " + std::to_string(i) + " (\"" + this->StepFiles[i] + "\")";
    if (i > 0 && !(this->StepTimes[i] > this->StepTimes[i - 1]))
    {
      error = step + ": times must increase (" + std::to_string(this->StepTimes[i]) + " after " +
              std::to_string(this->StepTimes[i - 1]) + ")";
      return false;
    }
    std::vector<std::unique_ptr<vtkPagePoolFile>> set;
    if (!OpenSet(this->StepFiles[i], set, error))
    {
      error = step + ": " + error;
      return false;
    }
    const vtkPagePoolFile& file = *set[0];
    const Format::Header& h = file.GetHeader();
    if (i == 0)
    {
      first = h;
      firstLevels = file.GetNumberOfLevels();
      continue;
    }
    std::ostringstream msg;
    if (h.PoolKind != first.PoolKind || h.Type != first.Type || h.PageSize != first.PageSize ||
        file.GetNumberOfLevels() != firstLevels || h.Components != first.Components)
      msg << "its kind, scalar type, page size, levels or components differ from step 0's";
    for (int a = 0; a < 3 && msg.str().empty(); ++a)
      if (h.Dimensions[a] != first.Dimensions[a])
        msg << "dimensions " << h.Dimensions[0] << " x " << h.Dimensions[1] << " x "
            << h.Dimensions[2] << " differ from step 0's " << first.Dimensions[0] << " x "
            << first.Dimensions[1] << " x " << first.Dimensions[2];
    if (!msg.str().empty())
    {
      error = step + ": " + msg.str();
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
vtkInformationDoubleKey* vtkPagePoolReader::UPDATE_RESOLUTION()
{
  return ResolutionKey;
}

//------------------------------------------------------------------------------
vtkPagePoolReader::vtkPagePoolReader()
{
  this->SetNumberOfInputPorts(0);
  this->SetArrayName("values");
}

//------------------------------------------------------------------------------
vtkPagePoolReader::~vtkPagePoolReader()
{
  this->SetFileName(nullptr);
  this->SetArrayName(nullptr);
}

//------------------------------------------------------------------------------
void vtkPagePoolReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ArrayName: " << (this->ArrayName ? this->ArrayName : "(none)") << "\n";
  os << indent << "Layer: " << this->Layer << "\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MB\n";
  os << indent << "NumberOfLevels: " << this->NumberOfLevels << "\n";
  os << indent << "NumberOfLayers: " << this->NumberOfLayers << "\n";
  os << indent << "IsTilePool: " << this->IsTilePool << "\n";
  os << indent << "NumberOfPagesRead: " << this->NumberOfPagesRead << "\n";
  os << indent << "LevelRead: " << this->LevelRead << "\n";
  os << indent << "TimeSteps: " << this->StepFiles.size() << "\n";
  for (size_t i = 0; i < this->StepFiles.size(); ++i)
    os << indent.GetNextIndent() << this->StepTimes[i] << ": " << this->StepFiles[i] << "\n";
  os << indent << "TimeStepRead: " << this->TimeStepRead << "\n";
}

//------------------------------------------------------------------------------
void vtkPagePoolReader::MarkPool(vtkImageData* output, const std::string& name)
{
  output->GetInformation()->Set(POOL_FILE_NAME(), name.c_str());
  vtkNew<vtkStringArray> file;
  file->SetName(PoolFileNameArray);
  file->InsertNextValue(name);
  vtkNew<vtkIntArray> layer;
  layer->SetName(PoolLayerArray);
  layer->InsertNextValue(this->IsTilePool ? this->Layer : 0);
  output->GetFieldData()->AddArray(file);
  output->GetFieldData()->AddArray(layer);
  if (this->TimeStepRead >= 0 && this->TimeStepRead < this->GetNumberOfTimeSteps())
  {
    output->GetInformation()->Set(
      vtkDataObject::DATA_TIME_STEP(), this->StepTimes[this->TimeStepRead]);
    vtkNew<vtkStringArray> series;
    series->SetName(PoolSeriesArray);
    for (const std::string& step : this->StepFiles)
      series->InsertNextValue(step);
    vtkNew<vtkIntArray> shown;
    shown->SetName(PoolTimeStepArray);
    shown->InsertNextValue(this->TimeStepRead);
    output->GetFieldData()->AddArray(series);
    output->GetFieldData()->AddArray(shown);
  }
}

//------------------------------------------------------------------------------
const char* vtkPagePoolReader::GetPoolFileName(vtkDataObject* data)
{
  vtkFieldData* fd = data ? data->GetFieldData() : nullptr;
  auto* file = fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(PoolFileNameArray)) : nullptr;
  return file && file->GetNumberOfValues() == 1 && !file->GetValue(0).empty()
           ? file->GetValue(0).c_str()
           : nullptr;
}

//------------------------------------------------------------------------------
int vtkPagePoolReader::GetPoolLayer(vtkDataObject* data)
{
  vtkFieldData* fd = data ? data->GetFieldData() : nullptr;
  auto* layer = fd ? vtkIntArray::SafeDownCast(fd->GetAbstractArray(PoolLayerArray)) : nullptr;
  return layer && layer->GetNumberOfValues() == 1 ? layer->GetValue(0) : 0;
}

//------------------------------------------------------------------------------
std::vector<std::string> vtkPagePoolReader::GetPoolSeries(vtkDataObject* data)
{
  vtkFieldData* fd = data ? data->GetFieldData() : nullptr;
  auto* series = fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(PoolSeriesArray)) : nullptr;
  std::vector<std::string> files;
  for (vtkIdType i = 0; series && i < series->GetNumberOfValues(); ++i)
    files.push_back(series->GetValue(i));
  return files;
}

//------------------------------------------------------------------------------
int vtkPagePoolReader::GetPoolTimeStep(vtkDataObject* data)
{
  vtkFieldData* fd = data ? data->GetFieldData() : nullptr;
  auto* step = fd ? vtkIntArray::SafeDownCast(fd->GetAbstractArray(PoolTimeStepArray)) : nullptr;
  return step && step->GetNumberOfValues() == 1 ? step->GetValue(0) : 0;
}

//------------------------------------------------------------------------------
bool vtkPagePoolReader::RequestCoarsestLevel(vtkInformation* inputInfo)
{
  if (!inputInfo || !inputInfo->Has(POOL_FILE_NAME()))
    return false;
  inputInfo->Set(UPDATE_RESOLUTION(), 0.0);
  return true;
}

void vtkPagePoolReader::RequestCoarsestLevels(vtkInformation* request,
  vtkInformationVector** inputVector,
  int ports)
{
  if (!request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
    return;
  for (int port = 0; port < ports; ++port)
    for (int c = 0; c < inputVector[port]->GetNumberOfInformationObjects(); ++c)
      RequestCoarsestLevel(inputVector[port]->GetInformationObject(c));
}

int vtkPagePoolReader::ResolutionToLevel(double r, int levels)
{
  if (levels <= 1)
  {
    return 0;
  }
  if (!(r > 0.0))
  {
    return levels - 1;
  }
  r = std::min(r, 1.0);
  // The small tolerance keeps exact powers of two (0.5, 0.25) on their own level.
  const int l = static_cast<int>(std::floor(std::log2(1.0 / r) + 1e-9));
  return std::max(0, std::min(l, levels - 1));
}

//------------------------------------------------------------------------------
bool vtkPagePoolReader::CanReadFile(const char* fileName)
{
  if (!fileName || !*fileName)
  {
    return false;
  }
  vtksys::ifstream in(fileName, std::ios::in | std::ios::binary);
  if (!in)
  {
    return false;
  }
  in.seekg(0, std::ios::end);
  const auto size = static_cast<long long>(in.tellg());
  in.seekg(0, std::ios::beg);
  unsigned char bytes[Format::HeaderSize];
  if (size < static_cast<long long>(Format::HeaderSize) ||
      !in.read(reinterpret_cast<char*>(bytes), Format::HeaderSize))
  {
    return false;
  }
  Format::Header header;
  std::string error;
  return Format::ValidateHeaderBytes(bytes, static_cast<uint64_t>(size), header, error);
}

//------------------------------------------------------------------------------
int vtkPagePoolReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  this->NumberOfLevels = 0;
  this->NumberOfLayers = 0;
  this->IsTilePool = false;
  std::vector<std::unique_ptr<vtkPagePoolFile>> set;
  int step = 0;
  const std::string name = this->SelectPool(outInfo, step);
  std::string error;
  const bool series = !this->StepFiles.empty();
  if (series ? !this->CheckSeries(error) : (name.empty() || !OpenSet(name, set, error)))
  {
    if (!series && name.empty())
      error = "no file name set";
    ClearOutput(outInfo);
    outInfo->Remove(POOL_FILE_NAME());
    outInfo->Remove(POOL_LAYER());
    outInfo->Remove(POOL_TIME_STEP());
    outInfo->Remove(POOL_SERIES());
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
    vtkErrorMacro(
      "Cannot read page pool " << (series ? "series" : "\"" + name + "\"") << ": " << error);
    return 0;
  }
  if (series && !OpenSet(name, set, error))
  {
    vtkErrorMacro("Cannot read page pool \"" << name << "\": " << error);
    return 0;
  }
  const vtkPagePoolFile& file = *set[0];
  if (series)
  {
    const double range[2] = { this->StepTimes.front(), this->StepTimes.back() };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(),
      this->StepTimes.data(),
      this->GetNumberOfTimeSteps());
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  else
  {
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  }
  const Format::Header& h = file.GetHeader();
  this->NumberOfLevels = file.GetNumberOfLevels();
  this->IsTilePool = h.PoolKind == Format::Kind::TilePool;
  this->NumberOfLayers = this->IsTilePool ? h.Dimensions[2] : 1;
  const int nz = this->IsTilePool ? 1 : h.Dimensions[2];
  const int extent[6] = { 0, h.Dimensions[0] - 1, 0, h.Dimensions[1] - 1, 0, nz - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), h.Spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), h.Origin, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), h.Direction, 9);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  outInfo->Set(POOL_FILE_NAME(), name.c_str());
  outInfo->Set(POOL_LAYER(), this->IsTilePool ? this->Layer : 0);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, ToVTKType(h.Type), h.Components);
  return 1;
}

//------------------------------------------------------------------------------
int vtkPagePoolReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  this->NumberOfPagesRead = 0;
  this->LevelRead = -1;
  this->TimeStepRead = -1;
  if (!output)
  {
    vtkErrorMacro("No vtkImageData output to fill.");
    return 0;
  }
  output->Initialize();
  int step = 0;
  const std::string name = this->SelectPool(outInfo, step);
  if (!name.empty())
    outInfo->Set(POOL_FILE_NAME(), name.c_str()); // the step this request shows
  auto fail = [&](const std::string& error)
  {
    output->Initialize();
    vtkErrorMacro("Cannot read page pool \"" << name << "\": " << error);
    return 0;
  };

  if (name.empty())
  {
    return fail("no file name set");
  }
  this->TimeStepRead = step;
  // The same request as last time, the reader unchanged: the same output, without reading.
  std::ostringstream request;
  {
    double r = this->Resolution;
    if (outInfo->Has(UPDATE_RESOLUTION()))
      r = outInfo->Get(UPDATE_RESOLUTION());
    int ue[6] = { 0, -1, 0, -1, 0, -1 };
    if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
      outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ue);
    request << name << '|' << ResolutionToLevel(r, this->NumberOfLevels) << '|' << this->Layer;
    for (int v : ue)
      request << '|' << v;
  }
  if (this->LastOutput && this->LastRequest == request.str() && this->LastTime >= this->GetMTime())
  {
    output->ShallowCopy(this->LastOutput);
    this->MarkPool(output, name);
    this->LevelRead = ResolutionToLevel(
      outInfo->Has(UPDATE_RESOLUTION()) ? outInfo->Get(UPDATE_RESOLUTION()) : this->Resolution,
      this->NumberOfLevels);
    return 1;
  }
  this->LastOutput = nullptr;

  // Opened again rather than kept from the information pass: the object holds a descriptor,
  // and a reader that sits in a pipeline for hours should not pin a file that may be replaced.
  std::vector<std::unique_ptr<vtkPagePoolFile>> set;
  std::string openError;
  if (!OpenSet(name, set, openError))
  {
    return fail(openError);
  }
  const vtkPagePoolFile& file = *set[0];
  const Format::Header& h = file.GetHeader();
  const int nc = h.Components;
  const bool tiles = h.PoolKind == Format::Kind::TilePool;
  const int layers = tiles ? h.Dimensions[2] : 1;
  if (tiles && (this->Layer < 0 || this->Layer >= layers))
  {
    std::ostringstream msg;
    msg << "layer " << this->Layer << " out of range [0, " << layers - 1 << "]";
    return fail(msg.str());
  }

  double resolution = this->Resolution;
  if (outInfo->Has(UPDATE_RESOLUTION()))
  {
    resolution = outInfo->Get(UPDATE_RESOLUTION());
  }
  const int level = ResolutionToLevel(resolution, file.GetNumberOfLevels());
  const Format::Level& lv = file.GetLevel(level);

  int updateExtent[6] = {
    0, h.Dimensions[0] - 1, 0, h.Dimensions[1] - 1, 0, tiles ? 0 : h.Dimensions[2] - 1
  };
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), updateExtent);
  }
  const int axes = tiles ? 2 : 3;
  int extent[6] = { 0, 0, 0, 0, 0, 0 };
  double spacing[3];
  for (int a = 0; a < 3; ++a)
  {
    const int n0 = a < axes ? h.Dimensions[a] : 1;
    const int nl = a < axes ? lv.Dimensions[a] : 1;
    const int lo = std::max(updateExtent[2 * a], 0);
    const int hi = std::min(updateExtent[2 * a + 1], n0 - 1);
    if (lo > hi)
    {
      // An empty request: an empty output, and no error.
      return 1;
    }
    if (nl > 1)
    {
      const double ratio = static_cast<double>(n0 - 1) / (nl - 1);
      spacing[a] = h.Spacing[a] * ratio;
      // The 1e-9 guards floor/ceil of exact quotients against rounding.
      extent[2 * a] = std::max(0, static_cast<int>(std::floor(lo / ratio + 1e-9)));
      extent[2 * a + 1] = std::min(nl - 1, static_cast<int>(std::ceil(hi / ratio - 1e-9)));
    }
    else
    {
      spacing[a] = h.Spacing[a];
      extent[2 * a] = extent[2 * a + 1] = 0;
    }
  }

  // Before allocating: the output of this level and extent must fit the memory limit.
  double outputMB = double(nc) * Format::GetScalarSize(h.Type) / 1048576.0;
  for (int a = 0; a < 3; ++a)
  {
    outputMB *= extent[2 * a + 1] - extent[2 * a] + 1;
  }
  double limitMB = this->MemoryLimit;
  if (limitMB <= 0.0)
  {
    vtksys::SystemInformation system;
    system.RunMemoryCheck();
    limitMB = static_cast<double>(system.GetTotalPhysicalMemory()); // MiB; 0 if unknown
  }
  if (limitMB > 0.0 && outputMB > limitMB)
  {
    std::ostringstream msg;
    msg << "level " << level << ", extent " << extent[0] << " " << extent[1] << " " << extent[2]
        << " " << extent[3] << " " << extent[4] << " " << extent[5] << ", needs " << outputMB
        << " MB of " << Format::GetScalarTypeName(h.Type)
        << " values, more than the MemoryLimit of " << limitMB << " MB"
        << (this->MemoryLimit > 0.0 ? "" : " (the physical memory)")
        << ": ask for a lower Resolution or a smaller update extent";
    return fail(msg.str());
  }

  output->SetExtent(extent);
  this->MarkPool(output, name);
  output->SetSpacing(spacing);
  output->SetOrigin(h.Origin);
  output->SetDirectionMatrix(h.Direction);
  const int vtkType = ToVTKType(h.Type);
  output->AllocateScalars(vtkType, nc);
  vtkDataArray* scalars = output->GetPointData()->GetScalars();
  if (!scalars || scalars->GetNumberOfTuples() != output->GetNumberOfPoints())
  {
    return fail("cannot allocate " + std::to_string(outputMB) + " MB for the output");
  }
  scalars->SetName(this->ArrayName);
  const int valueSize = Format::GetScalarSize(h.Type);
  auto* dst = static_cast<unsigned char*>(scalars->GetVoidPointer(0));

  const int B = h.PageSize;
  const int S = B - 1;
  int p0[3], p1[3];
  for (int a = 0; a < 3; ++a)
  {
    if (a < axes)
    {
      p0[a] = PageOf(extent[2 * a], S, lv.Pages[a]);
      p1[a] = PageOf(extent[2 * a + 1], S, lv.Pages[a]);
    }
    else
    {
      p0[a] = p1[a] = 0;
    }
  }
  const vtkIdType total =
    vtkIdType(p1[0] - p0[0] + 1) * (p1[1] - p0[1] + 1) * (p1[2] - p0[2] + 1) * nc;
  std::vector<unsigned char> page(file.GetPageBytes());
  this->LevelRead = level;
  this->UpdateProgress(0.0);
  std::string error;
  for (int pk = p0[2]; pk <= p1[2]; ++pk)
  {
    for (int pj = p0[1]; pj <= p1[1]; ++pj)
    {
      for (int pi = p0[0]; pi <= p1[0]; ++pi)
      {
        const uint64_t index =
          uint64_t(pi) + uint64_t(lv.Pages[0]) * (uint64_t(pj) + uint64_t(lv.Pages[1]) * pk);
        for (int c = 0; c < nc; ++c)
        {
          if (!set[c]->ReadPageNative(level, index, page.data(), &error))
          {
            return fail(error);
          }
          ++this->NumberOfPagesRead;
          const int pageAt[3] = { pi, pj, pk };
          CopyPage(page.data(), pageAt, B, tiles ? this->Layer : -1, extent, c, nc, valueSize, dst);
          this->UpdateProgress(static_cast<double>(this->NumberOfPagesRead) / total);
        }
      }
    }
  }
  this->LastOutput = vtkSmartPointer<vtkImageData>::New();
  this->LastOutput->ShallowCopy(output);
  this->LastRequest = request.str();
  this->LastTime = this->GetMTime();
  return 1;
}
