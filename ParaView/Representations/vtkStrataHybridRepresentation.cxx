// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataHybridRepresentation.h"

#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkHybridVolumeMapper.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkObjectFactory.h"
#include "vtkPVLODVolume.h"
#include "vtkPVRenderView.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkStrataParaViewUtilities.h"
#include "vtkTrivialProducer.h"
#include "vtkVolume.h"

#include <algorithm>

vtkStandardNewMacro(vtkStrataHybridRepresentation);

//------------------------------------------------------------------------------
vtkStrataHybridRepresentation::vtkStrataHybridRepresentation()
{
  this->Member->SetProperty(this->Property);
  this->Member->SetMapper(this->Mapper);
}

//------------------------------------------------------------------------------
vtkStrataHybridRepresentation::~vtkStrataHybridRepresentation() = default;

//------------------------------------------------------------------------------
void vtkStrataHybridRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mapper:\n";
  this->Mapper->PrintSelf(os, indent.GetNextIndent());
}

//------------------------------------------------------------------------------
int vtkStrataHybridRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkStrataHybridRepresentation::RequestUpdateExtent(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestUpdateExtent(request, inputVector, outputVector))
  {
    return 0;
  }
  // All of it on every process: each draws its box of the view's scene.
  vtkStrataParaViewUtilities::RequestWholeData(inputVector[0]);
  return 1;
}

//------------------------------------------------------------------------------
int vtkStrataHybridRepresentation::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkMath::UninitializeBounds(this->DataBounds);
  this->DataSize = 0;
  vtkImageData* volume = nullptr;
  vtkPolyData* points = nullptr;
  auto* input = inputVector[0]->GetNumberOfInformationObjects() == 1
                  ? vtkCompositeDataSet::GetData(inputVector[0], 0)
                  : nullptr;
  if (input)
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(input->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      vtkDataObject* block = it->GetCurrentDataObject();
      if (!volume)
        volume = vtkImageData::SafeDownCast(block);
      if (!points)
        points = vtkPolyData::SafeDownCast(block);
    }
  }
  if (volume && points)
  {
    vtkNew<vtkImageData> volumeCopy;
    volumeCopy->ShallowCopy(volume);
    vtkNew<vtkPolyData> pointsCopy;
    pointsCopy->ShallowCopy(points);
    this->VolumeProducer->SetOutput(volumeCopy);
    this->PointsProducer->SetOutput(pointsCopy);
    this->Mapper->SetInputConnection(this->VolumeProducer->GetOutputPort());
    this->Mapper->SetPointsInputConnection(this->PointsProducer->GetOutputPort());
    volumeCopy->GetBounds(this->DataBounds);
    this->DataSize = volumeCopy->GetActualMemorySize() + pointsCopy->GetActualMemorySize();
  }
  else if (input)
  {
    vtkErrorMacro("Strata Hybrid needs a hybrid volume: an image block and a polydata block "
                  "(the Strata Hybrid Volume reader's output).");
  }
  this->Cache = input;
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkStrataHybridRepresentation::ProcessViewRequest(vtkInformationRequestKey* request,
  vtkInformation* inInfo,
  vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request, inInfo, outInfo))
  {
    return 0;
  }
  if (request == vtkPVView::REQUEST_UPDATE())
  {
    vtkStrataParaViewUtilities::DeclareLocalPiece(
      this, inInfo, outInfo, this->Cache, this->DataSize, this->DataBounds);
    // A box of the view's scene per process (ordered compositing).
    vtkStrataParaViewUtilities::DeclarePropInScene(this, inInfo, this->DataBounds, this->Actor);
  }
  else if (request == vtkPVView::REQUEST_UPDATE_LOD())
  {
    vtkPVRenderView::SetRequiresDistributedRenderingLOD(inInfo, this, true);
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    vtkStrataParaViewUtilities::CopyTransform(this->Actor, this->Member);
    // In parallel: this process's box of the scene (the points and volume inside it).
    vtkStrataParaViewUtilities::UseProcessBox(this->GetView(), this->Mapper.GetPointer());
  }
  return 1;
}

//------------------------------------------------------------------------------
bool vtkStrataHybridRepresentation::AddToView(vtkView* view)
{
  return vtkStrataParaViewUtilities::AddProp(view, this->Member) &&
         this->Superclass::AddToView(view);
}

//------------------------------------------------------------------------------
bool vtkStrataHybridRepresentation::RemoveFromView(vtkView* view)
{
  vtkStrataParaViewUtilities::ForgetSceneBounds(this);
  return vtkStrataParaViewUtilities::RemoveProp(view, this->Member) &&
         this->Superclass::RemoveFromView(view);
}

//------------------------------------------------------------------------------
void vtkStrataHybridRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  this->Member->SetVisibility(visible);
  if (!visible)
    vtkStrataParaViewUtilities::ForgetSceneBounds(this);
}

void vtkStrataHybridRepresentation::SetPointShape(int shape)
{
  this->Mapper->SetPointShape(shape == 1 ? vtkHybridVolumeMapper::PointShapes::GaussianSplats
                                         : vtkHybridVolumeMapper::PointShapes::Squares);
}
void vtkStrataHybridRepresentation::SetNumberOfSlabs(int slabs)
{
  this->Mapper->SetNumberOfSlabs(slabs);
}
void vtkStrataHybridRepresentation::SetPointSpacing(double spacing)
{
  this->Mapper->SetPointSpacing(spacing);
}
void vtkStrataHybridRepresentation::SetSampleDistance(double distance)
{
  this->Mapper->GetVolumeMapper()->SetSampleDistance(distance);
}
void vtkStrataHybridRepresentation::SetStage(int stage)
{
  this->Mapper->GetVolumeMapper()->SetStage(
    static_cast<vtkMultiVolumeRayCastMapper::Stages>(std::min(2, std::max(0, stage))));
}
int vtkStrataHybridRepresentation::GetStageInUse()
{
  return static_cast<int>(this->Mapper->GetVolumeMapper()->GetStageInUse());
}
int vtkStrataHybridRepresentation::GetNumberOfPointsDrawn()
{
  return static_cast<int>(this->Mapper->GetNumberOfPointsDrawn());
}
