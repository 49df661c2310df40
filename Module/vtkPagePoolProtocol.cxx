// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkPagePoolProtocol.h"

#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkInformationIntegerKey.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkPagePoolProtocol);

namespace
{
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
  new vtkPagePoolResolutionKey("UPDATE_RESOLUTION", "vtkPagePoolProtocol");

template<typename Array>
Array* FieldArray(vtkDataObject* data, const char* name)
{
  vtkFieldData* fd = data ? data->GetFieldData() : nullptr;
  return fd ? Array::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
}

void AddValue(vtkFieldData* fd, const char* name, int value)
{
  vtkNew<vtkIntArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  fd->AddArray(array);
}
}

const char* const vtkPagePoolProtocol::FileNameArray = "PagePoolFileName";
const char* const vtkPagePoolProtocol::LayerArray = "PagePoolLayer";
const char* const vtkPagePoolProtocol::SeriesArray = "PagePoolSeries";
const char* const vtkPagePoolProtocol::TimeStepArray = "PagePoolTimeStep";
vtkInformationKeyMacro(vtkPagePoolProtocol, PAGE_POOL, Integer);

//------------------------------------------------------------------------------
vtkInformationDoubleKey* vtkPagePoolProtocol::UPDATE_RESOLUTION()
{
  return ResolutionKey;
}

//------------------------------------------------------------------------------
void vtkPagePoolProtocol::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Arrays: " << FileNameArray << ", " << LayerArray << ", " << SeriesArray << ", "
     << TimeStepArray << "\n";
}

//------------------------------------------------------------------------------
void vtkPagePoolProtocol::SetIdentity(vtkDataObject* data, const Identity& identity)
{
  vtkFieldData* fd = data ? data->GetFieldData() : nullptr;
  if (!fd)
    return;
  for (const char* name : { FileNameArray, LayerArray, SeriesArray, TimeStepArray })
    fd->RemoveArray(name);
  if (!identity.IsValid())
    return;
  vtkNew<vtkStringArray> file;
  file->SetName(FileNameArray);
  file->InsertNextValue(identity.FileName);
  fd->AddArray(file);
  AddValue(fd, LayerArray, identity.Layer);
  if (identity.Series.empty())
    return;
  vtkNew<vtkStringArray> series;
  series->SetName(SeriesArray);
  for (const std::string& step : identity.Series)
    series->InsertNextValue(step);
  fd->AddArray(series);
  AddValue(fd, TimeStepArray, identity.TimeStep);
}

//------------------------------------------------------------------------------
vtkPagePoolProtocol::Identity vtkPagePoolProtocol::GetIdentity(vtkDataObject* data)
{
  Identity identity;
  auto* file = FieldArray<vtkStringArray>(data, FileNameArray);
  if (!file || file->GetNumberOfValues() != 1 || file->GetValue(0).empty())
    return identity;
  identity.FileName = file->GetValue(0);
  auto* layer = FieldArray<vtkIntArray>(data, LayerArray);
  identity.Layer = layer && layer->GetNumberOfValues() == 1 ? layer->GetValue(0) : 0;
  auto* series = FieldArray<vtkStringArray>(data, SeriesArray);
  for (vtkIdType i = 0; series && i < series->GetNumberOfValues(); ++i)
    identity.Series.push_back(series->GetValue(i));
  auto* step = FieldArray<vtkIntArray>(data, TimeStepArray);
  identity.TimeStep = step && step->GetNumberOfValues() == 1 ? step->GetValue(0) : 0;
  return identity;
}

//------------------------------------------------------------------------------
bool vtkPagePoolProtocol::IsPagePool(vtkInformation* info)
{
  return info && info->Has(PAGE_POOL()) && info->Get(PAGE_POOL()) != 0;
}

//------------------------------------------------------------------------------
vtkPagePoolProtocol::Identity vtkPagePoolProtocol::GetInputPool(vtkInformation* inputInfo,
  vtkDataObject* data)
{
  return IsPagePool(inputInfo) ? GetIdentity(data) : Identity();
}

//------------------------------------------------------------------------------
bool vtkPagePoolProtocol::RequestCoarsestLevel(vtkInformation* inputInfo)
{
  if (!IsPagePool(inputInfo))
    return false;
  inputInfo->Set(UPDATE_RESOLUTION(), 0.0);
  return true;
}

//------------------------------------------------------------------------------
void vtkPagePoolProtocol::RequestCoarsestLevels(vtkInformation* request,
  vtkInformationVector** inputVector,
  int ports)
{
  if (!request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
    return;
  for (int port = 0; port < ports; ++port)
    for (int c = 0; c < inputVector[port]->GetNumberOfInformationObjects(); ++c)
      RequestCoarsestLevel(inputVector[port]->GetInformationObject(c));
}

//------------------------------------------------------------------------------
int vtkPagePoolProtocol::ResolutionToLevel(double r, int levels)
{
  if (levels <= 1)
    return 0;
  if (!(r > 0.0))
    return levels - 1;
  r = std::min(r, 1.0);
  // The small tolerance keeps exact powers of two (0.5, 0.25) on their own level.
  const int l = static_cast<int>(std::floor(std::log2(1.0 / r) + 1e-9));
  return std::max(0, std::min(l, levels - 1));
}
