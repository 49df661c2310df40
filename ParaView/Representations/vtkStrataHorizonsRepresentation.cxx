// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataHorizonsRepresentation.h"

#include "vtkActor.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkObjectFactory.h"
#include "vtkPVRenderView.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkStrataParaViewUtilities.h"
#include "vtkStrataPooledProducer.h"

#include <algorithm>

vtkStandardNewMacro(vtkStrataHorizonsRepresentation);

//------------------------------------------------------------------------------
vtkStrataHorizonsRepresentation::vtkStrataHorizonsRepresentation()
{
  this->Actor->SetMapper(this->Mapper);
  vtkMath::UninitializeBounds(this->DataBounds);
}

//------------------------------------------------------------------------------
vtkStrataHorizonsRepresentation::~vtkStrataHorizonsRepresentation() = default;

//------------------------------------------------------------------------------
void vtkStrataHorizonsRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Horizons: " << this->Producers.size() << "\n";
  os << indent << "Mapper:\n";
  this->Mapper->PrintSelf(os, indent.GetNextIndent());
}

//------------------------------------------------------------------------------
int vtkStrataHorizonsRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMultiBlockDataSet");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkStrataHorizonsRepresentation::RequestUpdateExtent(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestUpdateExtent(request, inputVector, outputVector))
  {
    return 0;
  }
  // A pooled horizon shown directly (no Stack Horizons between) gives its coarsest level, all of
  // it on every process (each draws its box of the scene).
  vtkStrataParaViewUtilities::RequestCoarsestLevels(inputVector[0]);
  vtkStrataParaViewUtilities::RequestWholeData(inputVector[0]);
  return 1;
}

//------------------------------------------------------------------------------
int vtkStrataHorizonsRepresentation::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  std::vector<vtkImageData*> horizons;
  vtkDataObject* input = inputVector[0]->GetNumberOfInformationObjects() == 1
                           ? vtkDataObject::GetData(inputVector[0], 0)
                           : nullptr;
  if (auto* image = vtkImageData::SafeDownCast(input))
  {
    horizons.push_back(image);
  }
  else if (auto* stack = vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(stack->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (auto* block = vtkImageData::SafeDownCast(it->GetCurrentDataObject()))
        horizons.push_back(block);
    }
  }

  // One producer per horizon, kept across updates so the mapper's stack is rebuilt only when
  // the data changes.
  this->Mapper->RemoveAllInputConnections(0);
  this->Producers.resize(horizons.size());
  this->DataSize = 0;
  for (size_t i = 0; i < horizons.size(); ++i)
  {
    if (!this->Producers[i])
      this->Producers[i] = vtkSmartPointer<vtkStrataPooledProducer>::New();
    vtkNew<vtkImageData> copy;
    copy->ShallowCopy(horizons[i]);
    this->Producers[i]->SetOutput(copy);
    this->Mapper->AddInputConnection(this->Producers[i]->GetOutputPort());
    this->DataSize += copy->GetActualMemorySize();
  }
  this->Cache = input;
  this->ColoringCurrent = false; // the horizons' arrays may have changed
  vtkMath::UninitializeBounds(this->DataBounds);
  if (!horizons.empty())
  {
    this->Mapper->GetBounds(this->DataBounds);
  }
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkStrataHorizonsRepresentation::ProcessViewRequest(vtkInformationRequestKey* request,
  vtkInformation* inInfo,
  vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request, inInfo, outInfo))
  {
    return 0;
  }
  if (request == vtkPVView::REQUEST_UPDATE())
  {
    vtkNew<vtkMatrix4x4> matrix;
    this->Actor->GetMatrix(matrix);
    vtkStrataParaViewUtilities::DeclareLocalPiece(
      this, inInfo, outInfo, this->Cache, this->DataSize, this->DataBounds, matrix);
    // The whole scene's box cut into one per process (ordered compositing).
    vtkStrataParaViewUtilities::DeclarePropInScene(this, inInfo, this->DataBounds, this->Actor);
  }
  else if (request == vtkPVView::REQUEST_UPDATE_LOD())
  {
    vtkPVRenderView::SetRequiresDistributedRenderingLOD(inInfo, this, true);
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    this->UpdateColoring();
    // In parallel: this process's box of the scene (all volumes and horizons of the view).
    vtkStrataParaViewUtilities::UseProcessBox(this->GetView(), this->Mapper.GetPointer());
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkStrataHorizonsRepresentation::SetHorizonOpacity(int index, double opacity)
{
  opacity = std::min(1.0, std::max(0.0, opacity));
  if (opacity < 1.0)
    this->Opacities[index] = opacity;
  else
    this->Opacities.erase(index);
  this->Mapper->SetHorizonOpacity(index, opacity);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkStrataHorizonsRepresentation::RemoveAllHorizonOpacities()
{
  for (const auto& entry : this->Opacities)
    this->Mapper->SetHorizonOpacity(entry.first, 1.0);
  this->Opacities.clear();
  this->Modified();
}

//------------------------------------------------------------------------------
bool vtkStrataHorizonsRepresentation::HasTranslucentHorizons() const
{
  const int horizons = static_cast<int>(this->Producers.size());
  for (const auto& entry : this->Opacities)
  {
    if (entry.first < horizons)
      return true;
  }
  return false;
}

//------------------------------------------------------------------------------
void vtkStrataHorizonsRepresentation::UpdateColoring()
{
  vtkInformation* info = this->GetInputArrayInformation(0);
  const std::string name =
    info->Has(vtkDataObject::FIELD_NAME()) ? info->Get(vtkDataObject::FIELD_NAME()) : "";
  vtkScalarsToColors* lut = name.empty() ? nullptr : this->LookupTable.GetPointer();
  const size_t horizons = this->Producers.size();
  if (this->ColoringCurrent && name == this->ColoredBy && lut == this->ColoredWith &&
      horizons == this->ColoredHorizons)
    return;
  // The heights: the horizons' active point scalars (a pool's, a reader's array).
  bool heights = false;
  if (!name.empty() && horizons > 0)
  {
    auto* first = vtkImageData::SafeDownCast(this->Producers[0]->GetOutputDataObject(0));
    vtkDataArray* scalars = first ? first->GetPointData()->GetScalars() : nullptr;
    heights = scalars && scalars->GetName() && name == scalars->GetName();
  }
  // Heights: the colour map over the height for every horizon. Another array: each horizon
  // that has it through the colour map, the others in their palette colour.
  using Modes = vtkStackedHeightFieldMapper::ColorModes;
  this->Mapper->SetColorMode(heights ? Modes::LookupTable : Modes::Solid);
  this->Mapper->SetHeightLookupTable(heights ? lut : nullptr);
  for (size_t i = 0; i < std::max(horizons, this->ColoredHorizons); ++i)
  {
    auto* horizon = i < horizons
                      ? vtkImageData::SafeDownCast(this->Producers[i]->GetOutputDataObject(0))
                      : nullptr;
    const bool attribute = !name.empty() && !heights && horizon &&
                           horizon->GetPointData()->GetArray(name.c_str()) != nullptr;
    this->Mapper->SetHorizonColorArray(static_cast<int>(i), attribute ? name.c_str() : nullptr);
    this->Mapper->SetHorizonLookupTable(static_cast<int>(i), attribute ? lut : nullptr);
  }
  this->ColoredBy = name;
  this->ColoredWith = lut;
  this->ColoredHorizons = horizons;
  this->ColoringCurrent = true;
}

//------------------------------------------------------------------------------
bool vtkStrataHorizonsRepresentation::AddToView(vtkView* view)
{
  return vtkStrataParaViewUtilities::AddProp(view, this->Actor) &&
         this->Superclass::AddToView(view);
}

//------------------------------------------------------------------------------
bool vtkStrataHorizonsRepresentation::RemoveFromView(vtkView* view)
{
  vtkStrataParaViewUtilities::ForgetSceneBounds(this);
  return vtkStrataParaViewUtilities::RemoveProp(view, this->Actor) &&
         this->Superclass::RemoveFromView(view);
}

//------------------------------------------------------------------------------
void vtkStrataHorizonsRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  this->Actor->SetVisibility(visible);
  if (!visible)
    vtkStrataParaViewUtilities::ForgetSceneBounds(this);
}

//------------------------------------------------------------------------------
int vtkStrataHorizonsRepresentation::GetPagingConverged()
{
  return this->Mapper->GetPagingStatistics().Converged ? 1 : 0;
}

//------------------------------------------------------------------------------
int vtkStrataHorizonsRepresentation::GetNumberOfPagedHorizons()
{
  int paged = 0;
  for (const auto& producer : this->Producers)
    paged += *producer->GetPoolFileName() ? 1 : 0;
  return paged;
}

// The actor's and the mapper's settings, passed through.
void vtkStrataHorizonsRepresentation::SetScale(double x, double y, double z)
{
  this->Actor->SetScale(x, y, z);
}
void vtkStrataHorizonsRepresentation::SetPosition(double x, double y, double z)
{
  this->Actor->SetPosition(x, y, z);
}
void vtkStrataHorizonsRepresentation::SetAmbient(double value)
{
  this->Actor->GetProperty()->SetAmbient(value);
}
void vtkStrataHorizonsRepresentation::SetDiffuse(double value)
{
  this->Actor->GetProperty()->SetDiffuse(value);
}
void vtkStrataHorizonsRepresentation::SetSpecular(double value)
{
  this->Actor->GetProperty()->SetSpecular(value);
}
void vtkStrataHorizonsRepresentation::SetSpecularPower(double value)
{
  this->Actor->GetProperty()->SetSpecularPower(value);
}
void vtkStrataHorizonsRepresentation::SetOpacity(double value)
{
  this->Actor->GetProperty()->SetOpacity(value);
}
void vtkStrataHorizonsRepresentation::SetHeightScale(double scale)
{
  this->Mapper->SetHeightScale(scale);
}
void vtkStrataHorizonsRepresentation::SetLookupTable(vtkScalarsToColors* lut)
{
  if (this->LookupTable != lut)
  {
    this->LookupTable = lut;
    this->Modified();
  }
}
void vtkStrataHorizonsRepresentation::SetNullValue(double value)
{
  this->Mapper->SetNullValue(value);
}
void vtkStrataHorizonsRepresentation::SetUseNullValue(bool use)
{
  this->Mapper->SetUseNullValue(use);
}
void vtkStrataHorizonsRepresentation::SetTileSize(int size)
{
  this->Mapper->SetTileSize(size);
}
void vtkStrataHorizonsRepresentation::SetLinearSearchStep(double step)
{
  this->Mapper->SetLinearSearchStep(step);
}
void vtkStrataHorizonsRepresentation::SetStage(int stage)
{
  this->Mapper->SetStage(
    static_cast<vtkStackedHeightFieldMapper::Stages>(std::min(2, std::max(0, stage))));
}
int vtkStrataHorizonsRepresentation::GetStageInUse()
{
  return static_cast<int>(this->Mapper->GetStageInUse());
}
double vtkStrataHorizonsRepresentation::GetStageProbeRatio()
{
  return this->Mapper->GetStageProbeRatio();
}
void vtkStrataHorizonsRepresentation::SetPageCacheBudget(double megabytes)
{
  this->Mapper->SetPageCacheBudget(megabytes);
}
void vtkStrataHorizonsRepresentation::SetAtlasBudget(double megabytes)
{
  this->Mapper->SetAtlasBudget(megabytes);
}
void vtkStrataHorizonsRepresentation::SetPagesPerFrame(int pages)
{
  this->Mapper->SetPagesPerFrame(pages);
}
void vtkStrataHorizonsRepresentation::SetPrefetch(bool prefetch)
{
  this->Mapper->SetPrefetch(prefetch);
}
void vtkStrataHorizonsRepresentation::SetMorphFrames(int frames)
{
  this->Mapper->SetMorphFrames(frames);
}
void vtkStrataHorizonsRepresentation::SetLevelOfDetailFeedback(bool feedback)
{
  this->Mapper->SetLevelOfDetailFeedback(feedback);
}
void vtkStrataHorizonsRepresentation::SetFeedbackScale(int scale)
{
  this->Mapper->SetFeedbackScale(scale);
}
void vtkStrataHorizonsRepresentation::SetLevelOfDetailThreshold(double threshold)
{
  this->Mapper->SetLevelOfDetailThreshold(threshold);
}
