// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataPooledProducer.h"

#include "vtkDataObject.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkInformationStringKey.h"
#include "vtkInformationStringVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPagePoolReader.h"

vtkStandardNewMacro(vtkStrataPooledProducer);

//------------------------------------------------------------------------------
void vtkStrataPooledProducer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PoolFileName: " << this->PoolFileName << "\n";
  os << indent << "PoolLayer: " << this->PoolLayer << "\n";
  os << indent << "PoolTimeStep: " << this->PoolTimeStep << " of " << this->PoolSeries.size()
     << "\n";
}

//------------------------------------------------------------------------------
void vtkStrataPooledProducer::SetOutput(vtkDataObject* output)
{
  const char* pool = vtkPagePoolReader::GetPoolFileName(output);
  const std::string name = pool ? pool : "";
  const int layer = vtkPagePoolReader::GetPoolLayer(output);
  const int step = vtkPagePoolReader::GetPoolTimeStep(output);
  std::vector<std::string> series = vtkPagePoolReader::GetPoolSeries(output);
  if (name != this->PoolFileName || layer != this->PoolLayer || step != this->PoolTimeStep ||
      series != this->PoolSeries)
  {
    this->PoolFileName = name;
    this->PoolLayer = layer;
    this->PoolTimeStep = step;
    this->PoolSeries = std::move(series);
    this->Modified();
  }
  this->Superclass::SetOutput(output);
}

//------------------------------------------------------------------------------
vtkTypeBool vtkStrataPooledProducer::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inInfo,
  vtkInformationVector* outInfo)
{
  const vtkTypeBool result = this->Superclass::ProcessRequest(request, inInfo, outInfo);
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    vtkInformation* info = outInfo->GetInformationObject(0);
    if (this->PoolFileName.empty())
    {
      info->Remove(vtkPagePoolReader::POOL_FILE_NAME());
      info->Remove(vtkPagePoolReader::POOL_LAYER());
    }
    else
    {
      info->Set(vtkPagePoolReader::POOL_FILE_NAME(), this->PoolFileName.c_str());
      info->Set(vtkPagePoolReader::POOL_LAYER(), this->PoolLayer);
    }
    info->Remove(vtkPagePoolReader::POOL_TIME_STEP());
    info->Remove(vtkPagePoolReader::POOL_SERIES());
    if (!this->PoolFileName.empty() && !this->PoolSeries.empty())
    {
      info->Set(vtkPagePoolReader::POOL_TIME_STEP(), this->PoolTimeStep);
      for (const std::string& file : this->PoolSeries)
        info->Append(vtkPagePoolReader::POOL_SERIES(), file.c_str());
    }
  }
  return result;
}
