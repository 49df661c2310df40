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
  os << indent << "PoolFileName: " << this->Pool.FileName << "\n";
  os << indent << "PoolLayer: " << this->Pool.Layer << "\n";
  os << indent << "PoolTimeStep: " << this->Pool.TimeStep << " of " << this->Pool.Series.size()
     << "\n";
}

//------------------------------------------------------------------------------
void vtkStrataPooledProducer::SetOutput(vtkDataObject* output)
{
  vtkPagePoolProtocol::Identity pool = vtkPagePoolProtocol::GetIdentity(output);
  if (pool != this->Pool)
  {
    this->Pool = std::move(pool);
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
    if (!this->Pool.IsValid())
      info->Remove(vtkPagePoolProtocol::PAGE_POOL());
    else
      info->Set(vtkPagePoolProtocol::PAGE_POOL(), 1);
  }
  return result;
}
