// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkPagePoolReader.h"
#include "StrataGridReaderUtilities.h"

#include "StrataPagePoolFile.h"
#include "StrataPagePoolSet.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkInformationIntegerKey.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPagePoolProtocol.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <vtksys/FStream.hxx>
#include <vtksys/SystemInformation.hxx>

#include <algorithm>
#include <map>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPagePoolReader);

namespace
{
using Format = strata::PagePoolFormat;
using Protocol = vtkPagePoolProtocol;
using strata_io::ClearOutput;
}

/// The pools this reader shows, held open (strata::PagePoolFile::OpenShared) from the information
/// pass on, so that the mappers paging them share the reader's files: a step's set stays while
/// the reader names it, and a file replaced on disk is opened afresh (OpenShared compares).
struct vtkPagePoolReader::vtkInternals
{
  std::map<std::string, strata::PagePoolSet> Sets;

  /// The set of `name`, opened or kept; null with `error` when it cannot be opened.
  const strata::PagePoolSet* Open(const std::string& name, std::string& error)
  {
    strata::PagePoolSet set;
    if (!set.Open(name, error))
    {
      this->Sets.erase(name);
      return nullptr;
    }
    return &(this->Sets[name] = std::move(set));
  }
};

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
    return this->FileName ? this->FileName : "";
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
    step = ChooseTimeStep(this->StepTimes.data(),
      this->GetNumberOfTimeSteps(),
      outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()));
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
    const strata::PagePoolSet* set = this->Internals->Open(this->StepFiles[i], error);
    if (!set)
    {
      error = step + ": " + error;
      return false;
    }
    const strata::PagePoolFile& file = set->GetFile();
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
  return Protocol::UPDATE_RESOLUTION();
}

//------------------------------------------------------------------------------
vtkPagePoolReader::vtkPagePoolReader()
  : Internals(new vtkInternals)
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
  Protocol::Identity identity;
  identity.FileName = name;
  identity.Layer = this->IsTilePool ? this->Layer : 0;
  if (this->TimeStepRead >= 0 && this->TimeStepRead < this->GetNumberOfTimeSteps())
  {
    output->GetInformation()->Set(
      vtkDataObject::DATA_TIME_STEP(), this->StepTimes[this->TimeStepRead]);
    identity.TimeStep = this->TimeStepRead;
    identity.Series = this->StepFiles;
  }
  Protocol::SetIdentity(output, identity);
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
  int step = 0;
  const std::string name = this->SelectPool(outInfo, step);
  std::string error;
  const bool series = !this->StepFiles.empty();
  this->Internals->Sets.clear(); // the files of earlier names go, these stay open
  const strata::PagePoolSet* set = nullptr;
  if (!series && name.empty())
    error = "no file name set";
  else if (!series || this->CheckSeries(error))
    set = this->Internals->Open(name, error);
  if (!set)
  {
    ClearOutput(outInfo);
    outInfo->Remove(Protocol::PAGE_POOL());
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
    vtkErrorMacro(
      "Cannot read page pool " << (series ? "series" : "\"" + name + "\"") << ": " << error);
    return 0;
  }
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
  const Format::Header& h = set->GetFile().GetHeader();
  this->NumberOfLevels = set->GetFile().GetNumberOfLevels();
  this->IsTilePool = set->IsTilePool();
  this->NumberOfLayers = this->IsTilePool ? h.Dimensions[2] : 1;
  // The geometry of the level Resolution selects: what a request without UPDATE_RESOLUTION
  // gets, so that every filter (an outline, a surface, a slice) sees the data it is given.
  int extent[6];
  double spacing[3];
  set->GetLevelGeometry(
    Protocol::ResolutionToLevel(this->Resolution, this->NumberOfLevels), extent, spacing);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), h.Origin, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), h.Direction, 9);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  outInfo->Set(Protocol::PAGE_POOL(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, set->GetVTKScalarType(), h.Components);
  return 1;
}

//------------------------------------------------------------------------------
std::string vtkPagePoolReader::DescribeRequest(vtkInformation* outInfo,
  const std::string& name,
  int& level) const
{
  const double r = outInfo->Has(Protocol::UPDATE_RESOLUTION())
                     ? outInfo->Get(Protocol::UPDATE_RESOLUTION())
                     : this->Resolution;
  level = Protocol::ResolutionToLevel(r, this->NumberOfLevels);
  int ue[6] = { 0, -1, 0, -1, 0, -1 };
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ue);
  std::ostringstream request;
  request << name << '|' << level << '|' << this->Layer;
  for (int v : ue)
    request << '|' << v;
  return request.str();
}

//------------------------------------------------------------------------------
double vtkPagePoolReader::GetMemoryLimitMB() const
{
  if (this->MemoryLimit > 0.0)
    return this->MemoryLimit;
  vtksys::SystemInformation system;
  system.RunMemoryCheck();
  return static_cast<double>(system.GetTotalPhysicalMemory()); // MiB; 0 if unknown
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
  auto fail = [&](const std::string& error)
  {
    output->Initialize();
    vtkErrorMacro("Cannot read page pool \"" << name << "\": " << error);
    return 0;
  };
  if (name.empty())
    return fail("no file name set");
  this->TimeStepRead = step;
  // The same request as last time, the reader unchanged: the same output, without reading.
  int level = 0;
  const std::string request = this->DescribeRequest(outInfo, name, level);
  if (this->LastOutput && this->LastRequest == request && this->LastTime >= this->GetMTime())
  {
    output->ShallowCopy(this->LastOutput);
    this->MarkPool(output, name);
    this->LevelRead = level;
    return 1;
  }
  this->LastOutput = nullptr;
  std::string error;
  const strata::PagePoolSet* set = this->Internals->Open(name, error);
  if (!set)
    return fail(error);
  // The update extent is in the indices of the declared level (RequestInformation's).
  const int declared = Protocol::ResolutionToLevel(this->Resolution, this->NumberOfLevels);
  int updateExtent[6];
  double spacing[3];
  set->GetLevelGeometry(declared, updateExtent, spacing);
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), updateExtent);
  strata::PagePoolSet::Read read;
  read.Layer = this->Layer;
  read.ArrayName = this->ArrayName ? this->ArrayName : "values";
  read.MemoryLimitMB = this->GetMemoryLimitMB();
  read.LimitName = "MemoryLimit";
  read.LimitAdvice = std::string(this->MemoryLimit > 0.0 ? "" : " (the physical memory)") +
                     ": ask for a lower Resolution or a smaller update extent";
  read.Progress = [this](double fraction) { this->UpdateProgress(fraction); };
  // Another level asked for (UPDATE_RESOLUTION: a consumer paging the pool itself): the level
  // covering the same region, with that level's extent and spacing.
  vtkSmartPointer<vtkImageData> image;
  if (level == declared)
    image = set->ReadLevelImage(level, updateExtent, read, error);
  else
  {
    int finest[6];
    set->LevelToFinest(declared, updateExtent, finest);
    image = set->ReadImage(level, finest, read, error);
  }
  this->NumberOfPagesRead = read.PagesRead;
  if (!image)
    return fail(error);
  if (image->GetNumberOfPoints() == 0)
    return 1; // an empty request: an empty output, and no error
  this->LevelRead = level;
  output->ShallowCopy(image);
  this->MarkPool(output, name);
  this->LastOutput = vtkSmartPointer<vtkImageData>::New();
  this->LastOutput->ShallowCopy(output);
  this->LastRequest = request;
  this->LastTime = this->GetMTime();
  return 1;
}
