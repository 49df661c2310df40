// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataHybridVolumeSource.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkCompositeDataSet.h"
#include "vtkHybridVolumeReader.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include <algorithm>

vtkStandardNewMacro(vtkStrataHybridVolumeSource);

//------------------------------------------------------------------------------
vtkStrataHybridVolumeSource::vtkStrataHybridVolumeSource()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkStrataHybridVolumeSource::~vtkStrataHybridVolumeSource() = default;

//------------------------------------------------------------------------------
void vtkStrataHybridVolumeSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->GetFileName() ? this->GetFileName() : "(none)") << "\n";
}

//------------------------------------------------------------------------------
void vtkStrataHybridVolumeSource::SetFileName(const char* name)
{
  this->Reader->SetFileName(name);
}

//------------------------------------------------------------------------------
const char* vtkStrataHybridVolumeSource::GetFileName()
{
  return this->Reader->GetFileName();
}

//------------------------------------------------------------------------------
vtkMTimeType vtkStrataHybridVolumeSource::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->Reader->GetMTime());
}

//------------------------------------------------------------------------------
int vtkStrataHybridVolumeSource::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  // The reader's errors reach this algorithm's observers as errors of its own.
  vtkNew<vtkCallbackCommand> forward;
  forward->SetClientData(this);
  forward->SetCallback(
    [](vtkObject*, unsigned long, void* self, void* message)
    {
      auto* source = static_cast<vtkStrataHybridVolumeSource*>(self);
      vtkErrorWithObjectMacro(source, << static_cast<const char*>(message));
    });
  const unsigned long tag = this->Reader->AddObserver(vtkCommand::ErrorEvent, forward);
  this->Reader->Update();
  this->Reader->RemoveObserver(tag);
  vtkImageData* volume = this->Reader->GetLowResolutionOutput();
  vtkPolyData* points = this->Reader->GetPointsOutput();
  if (!volume || volume->GetNumberOfPoints() == 0)
  {
    return 0;
  }
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(outputVector, 0);
  vtkNew<vtkImageData> volumeCopy;
  volumeCopy->ShallowCopy(volume);
  vtkNew<vtkPolyData> pointsCopy;
  pointsCopy->ShallowCopy(points);
  output->SetNumberOfBlocks(2);
  output->SetBlock(0, volumeCopy);
  output->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "Volume");
  output->SetBlock(1, pointsCopy);
  output->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), "Points");
  return 1;
}
