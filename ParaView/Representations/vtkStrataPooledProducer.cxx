// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataPooledProducer.h"

#include "vtkDataObject.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPagePoolProtocol.h"

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
  vtkPagePoolProtocol::Identity pool = vtkPagePoolProtocol::GetIdentity(output);
  const std::string& name = pool.FileName;
  const int layer = pool.Layer;
  const int step = pool.TimeStep;
  std::vector<std::string>& series = pool.Series;
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
      info->Remove(vtkPagePoolProtocol::PAGE_POOL());
    else
      info->Set(vtkPagePoolProtocol::PAGE_POOL(), 1);
  }
  return result;
}
