// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkMultiVolumeRayCastMapper's settings and introspection: classification and order, cuts and
// fixed cuts, per-input blend modes and cropping, shader sources, translucent actors (the frame
// itself is in vtkMultiVolumeRayCastMapper.cxx).
#include "vtkMultiVolumeRayCastMapper.h"

#include "StrataBrickAtlasFormat.h"
#include "vtkMultiVolumeRayCastMapperInternals.h"

#include "StrataBrickAtlasAllocator.h"

#include "vtkActor.h"
#include "vtkIntArray.h"

#include <algorithm>

void vtkMultiVolumeRayCastMapper::SetClassification(Classifications classification)
{
  if (classification != this->Classification)
  {
    this->Classification = classification;
    this->Modified();
  }
}

void vtkMultiVolumeRayCastMapper::SetCompositeOrder(CompositeOrders order)
{
  if (order != this->CompositeOrder)
  {
    this->CompositeOrder = order;
    this->Modified();
  }
}

void vtkMultiVolumeRayCastMapper::SetScalarStorage(ScalarStorages storage)
{
  if (storage != this->ScalarStorage)
  {
    this->ScalarStorage = storage;
    this->Modified();
  }
}

int vtkMultiVolumeRayCastMapper::GetNumberOfResidentBricks() const
{
  return this->Internals->ResidentBricks;
}

std::vector<int> vtkMultiVolumeRayCastMapper::GetResidentBricksPerLevel(int port) const
{
  return this->Internals->Pager.GetResidentBricksPerLevel(port);
}

int vtkMultiVolumeRayCastMapper::GetNumberOfAtlasSlots() const
{
  return this->Internals->Pager.GetAtlas().GetNumberOfSlots();
}

int vtkMultiVolumeRayCastMapper::GetAtlasBytesPerBrick() const
{
  const int B = this->Internals->Pager.GetAtlas().GetBrickSize();
  return B * B * B * strata::BrickAtlasFormat::GetTexelSize(this->Internals->Pager.GetAtlasType());
}

const char* vtkMultiVolumeRayCastMapper::GetAtlasScalarTypeName() const
{
  return strata::BrickAtlasFormat::GetName(this->Internals->Pager.GetAtlasType());
}

std::vector<std::array<int, 2>> vtkMultiVolumeRayCastMapper::GetCutBricks(int port) const
{
  return this->Internals->Pager.GetCutBricks(port);
}

void vtkMultiVolumeRayCastMapper::SetFixedCut(int port,
  const std::vector<std::array<int, 2>>& bricks)
{
  // A volume of several components in the atlas is a volume per component: the same cut each.
  for (int c = 0; c < strata::VolumePager::MaxComponents; ++c)
    this->Internals->Pager.SetFixedCut(strata::VolumePager::GetChannel(port, c), bricks);
  this->Modified();
}

void vtkMultiVolumeRayCastMapper::GetCutBricks(int port, vtkIntArray* bricks) const
{
  if (!bricks)
  {
    return;
  }
  const std::vector<std::array<int, 2>> cut = this->GetCutBricks(port);
  bricks->SetNumberOfComponents(2);
  bricks->SetNumberOfTuples(static_cast<vtkIdType>(cut.size()));
  for (size_t i = 0; i < cut.size(); ++i)
  {
    bricks->SetTypedTuple(static_cast<vtkIdType>(i), cut[i].data());
  }
}

void vtkMultiVolumeRayCastMapper::SetFixedCut(int port, vtkIntArray* bricks)
{
  if (!bricks || bricks->GetNumberOfComponents() != 2)
  {
    vtkErrorMacro("SetFixedCut needs an array of two components (level, brick), not "
                  << (bricks ? bricks->GetNumberOfComponents() : 0));
    return;
  }
  std::vector<std::array<int, 2>> cut(static_cast<size_t>(bricks->GetNumberOfTuples()));
  for (size_t i = 0; i < cut.size(); ++i)
  {
    bricks->GetTypedTuple(static_cast<vtkIdType>(i), cut[i].data());
  }
  this->SetFixedCut(port, cut);
}

void vtkMultiVolumeRayCastMapper::RemoveAllFixedCuts()
{
  if (!this->Internals->Pager.HasFixedCuts())
    return;
  this->Internals->Pager.RemoveAllFixedCuts();
  this->Modified();
}

int vtkMultiVolumeRayCastMapper::GetNumberOfFragments() const
{
  return this->Internals->LastFragments;
}

int vtkMultiVolumeRayCastMapper::GetNumberOfShaderSourcesBuilt() const
{
  return this->Internals->Composer.GetNumberOfSourcesBuilt();
}

int vtkMultiVolumeRayCastMapper::GetNumberOfShaderCompilations() const
{
  return this->Internals->Composer.GetNumberOfCompilations();
}

void vtkMultiVolumeRayCastMapper::SetInputBlendMode(int port, int mode)
{
  auto it = this->InputBlendModes.find(port);
  if (mode < 0 ? it == this->InputBlendModes.end()
               : it != this->InputBlendModes.end() && it->second == mode)
    return;
  if (mode < 0)
    this->InputBlendModes.erase(it);
  else
    this->InputBlendModes[port] = mode;
  this->Modified();
}

void vtkMultiVolumeRayCastMapper::SetInputCropping(int port,
  bool cropping,
  const double planes[6],
  int flags)
{
  InputCrop crop;
  crop.Cropping = cropping;
  std::copy(planes, planes + 6, crop.Planes);
  crop.Flags = flags;
  auto it = this->InputCroppings.find(port);
  if (it != this->InputCroppings.end() && it->second.Cropping == crop.Cropping &&
      it->second.Flags == crop.Flags && std::equal(planes, planes + 6, it->second.Planes))
    return;
  this->InputCroppings[port] = crop;
  this->Modified();
}

void vtkMultiVolumeRayCastMapper::RemoveInputCropping(int port)
{
  if (this->InputCroppings.erase(port))
    this->Modified();
}

bool vtkMultiVolumeRayCastMapper::GetEffectiveCropping(int port, double planes[6], int& flags) const
{
  auto it = this->InputCroppings.find(port);
  const bool own = it != this->InputCroppings.end();
  std::copy(own ? it->second.Planes : this->CroppingRegionPlanes,
    (own ? it->second.Planes : this->CroppingRegionPlanes) + 6,
    planes);
  flags = own ? it->second.Flags : this->CroppingRegionFlags;
  return own ? it->second.Cropping : this->Cropping != 0;
}

int vtkMultiVolumeRayCastMapper::GetInputBlendMode(int port) const
{
  auto it = this->InputBlendModes.find(port);
  return it == this->InputBlendModes.end() ? -1 : it->second;
}

int vtkMultiVolumeRayCastMapper::GetEffectiveBlendMode(int port) const
{
  const int mode = this->GetInputBlendMode(port);
  return mode < 0 ? this->BlendMode : mode;
}

std::string vtkMultiVolumeRayCastMapper::GetReductionShaderSource(int blendMode) const
{
  const vtkInternals& in = *this->Internals;
  auto it = in.LastReduceKeys.find(blendMode);
  if (it == in.LastReduceKeys.end())
    return std::string();
  return this->GetStageInUse() == Stages::Compute ? in.Composer.GetComputeSource(it->second)
                                                  : in.Composer.GetFragmentSource(it->second);
}

std::string vtkMultiVolumeRayCastMapper::GetShaderSource(int numberOfVolumes) const
{
  return this->GetStageInUse() == Stages::Compute ? this->GetComputeShaderSource(numberOfVolumes)
                                                  : this->GetFragmentShaderSource(numberOfVolumes);
}

std::string vtkMultiVolumeRayCastMapper::GetFragmentShaderSource(int numberOfVolumes) const
{
  auto it = this->Internals->LastKeys.find(numberOfVolumes);
  return it == this->Internals->LastKeys.end()
           ? std::string()
           : this->Internals->Composer.GetFragmentSource(it->second);
}

std::string vtkMultiVolumeRayCastMapper::GetComputeShaderSource(int numberOfVolumes) const
{
  auto it = this->Internals->LastKeys.find(numberOfVolumes);
  return it == this->Internals->LastKeys.end()
           ? std::string()
           : this->Internals->Composer.GetComputeSource(it->second);
}

void vtkMultiVolumeRayCastMapper::GetReductionRatio(double ratio[3])
{
  ratio[0] = ratio[1] = ratio[2] = 1.0;
}

void vtkMultiVolumeRayCastMapper::AddTranslucentActor(vtkActor* actor)
{
  this->Internals->SurfaceLayers.AddActor(actor);
  this->Modified();
}

void vtkMultiVolumeRayCastMapper::RemoveAllTranslucentActors()
{
  this->Internals->SurfaceLayers.RemoveAllActors();
  this->Modified();
}

int vtkMultiVolumeRayCastMapper::GetNumberOfTranslucentActors() const
{
  return this->Internals->SurfaceLayers.GetNumberOfActors();
}
