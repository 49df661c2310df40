// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataParaViewUtilities.h"

#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPVDataRepresentation.h"
#include "vtkPVRenderView.h"
#include "vtkPagePoolProtocol.h"
#include "vtkProp3D.h"
#include "vtkRenderer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <array>
#include <map>

namespace
{
// Per view, the world bounds of its visible Strata representations (DeclareSceneBounds).
std::map<vtkView*, std::map<vtkPVDataRepresentation*, std::array<double, 6>>> SceneBounds;

int NumberOfProcesses()
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return controller ? controller->GetNumberOfProcesses() : 1;
}

int ProcessId()
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return controller ? controller->GetLocalProcessId() : 0;
}

bool SceneBox(vtkView* view, double box[6])
{
  auto it = SceneBounds.find(view);
  if (it == SceneBounds.end() || it->second.empty())
    return false;
  bool first = true;
  for (const auto& entry : it->second)
  {
    const auto& b = entry.second;
    for (int a = 0; a < 3; ++a)
    {
      box[2 * a] = first ? b[2 * a] : std::min(box[2 * a], b[2 * a]);
      box[2 * a + 1] = first ? b[2 * a + 1] : std::max(box[2 * a + 1], b[2 * a + 1]);
    }
    first = false;
  }
  return true;
}
}

void vtkStrataParaViewUtilities::DeclareLocalPiece(vtkPVDataRepresentation* representation,
  vtkInformation* inInfo,
  vtkInformation* outInfo,
  vtkDataObject* piece,
  unsigned long size,
  const double bounds[6],
  vtkMatrix4x4* transform)
{
  vtkPVRenderView::SetPiece(inInfo, representation, piece, size, 0);
  vtkPVRenderView::SetDeliverToClientAndRenderingProcesses(inInfo, representation, false, false, 0);
  outInfo->Set(vtkPVRenderView::NEED_ORDERED_COMPOSITING(), 1);
  if (vtkMath::AreBoundsInitialized(bounds))
  {
    vtkPVRenderView::SetGeometryBounds(inInfo, representation, bounds, transform);
  }
  vtkPVRenderView::SetRequiresDistributedRendering(inInfo, representation, true);
}

void vtkStrataParaViewUtilities::RequestWholeData(vtkInformationVector* inputs)
{
  for (int i = 0; i < inputs->GetNumberOfInformationObjects(); ++i)
  {
    vtkInformation* info = inputs->GetInformationObject(i);
    info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
    info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
    info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
}

void vtkStrataParaViewUtilities::TransformBounds(const double bounds[6],
  vtkMatrix4x4* transform,
  double world[6])
{
  if (!transform)
  {
    std::copy(bounds, bounds + 6, world);
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    world[2 * a] = VTK_DOUBLE_MAX;
    world[2 * a + 1] = -VTK_DOUBLE_MAX;
  }
  for (int c = 0; c < 8; ++c)
  {
    const double p[4] = {
      bounds[c & 1], bounds[2 + ((c >> 1) & 1)], bounds[4 + ((c >> 2) & 1)], 1.0
    };
    double q[4];
    transform->MultiplyPoint(p, q);
    for (int a = 0; a < 3; ++a)
    {
      world[2 * a] = std::min(world[2 * a], q[a] / q[3]);
      world[2 * a + 1] = std::max(world[2 * a + 1], q[a] / q[3]);
    }
  }
}

void vtkStrataParaViewUtilities::PartitionBox(const double bounds[6],
  int count,
  int index,
  double cell[6])
{
  std::copy(bounds, bounds + 6, cell);
  while (count > 1)
  {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      axis = cell[2 * a + 1] - cell[2 * a] > cell[2 * axis + 1] - cell[2 * axis] ? a : axis;
    const int left = count / 2;
    const double split =
      cell[2 * axis] + (cell[2 * axis + 1] - cell[2 * axis]) * left / static_cast<double>(count);
    if (index < left)
    {
      cell[2 * axis + 1] = split;
      count = left;
    }
    else
    {
      cell[2 * axis] = split;
      index -= left;
      count -= left;
    }
  }
}

void vtkStrataParaViewUtilities::DeclareSceneBounds(vtkPVDataRepresentation* representation,
  vtkInformation* inInfo,
  const double worldBounds[6])
{
  vtkView* view = representation->GetView();
  if (!view)
    return;
  if (vtkMath::AreBoundsInitialized(worldBounds))
  {
    auto& entry = SceneBounds[view][representation];
    std::copy(worldBounds, worldBounds + 6, entry.begin());
  }
  else
  {
    ForgetSceneBounds(representation);
  }
  double scene[6], cell[6];
  if (!SceneBox(view, scene))
    return;
  PartitionBox(scene, NumberOfProcesses(), ProcessId(), cell);
  // Every registered representation: the one asking may have grown the scene.
  for (const auto& entry : SceneBounds[view])
  {
    vtkPVRenderView::SetGeometryBounds(inInfo, entry.first, cell);
    vtkPVRenderView::SetOrderedCompositingConfiguration(
      inInfo, entry.first, vtkPVRenderView::USE_BOUNDS_FOR_REDISTRIBUTION);
  }
}

void vtkStrataParaViewUtilities::DeclarePropInScene(vtkPVDataRepresentation* representation,
  vtkInformation* inInfo,
  const double dataBounds[6],
  vtkProp3D* prop)
{
  vtkNew<vtkMatrix4x4> matrix;
  prop->GetMatrix(matrix);
  double world[6];
  vtkMath::UninitializeBounds(world);
  if (vtkMath::AreBoundsInitialized(dataBounds))
    TransformBounds(dataBounds, matrix, world);
  DeclareSceneBounds(representation, inInfo, world);
}

void vtkStrataParaViewUtilities::ForgetSceneBounds(vtkPVDataRepresentation* representation)
{
  for (auto it = SceneBounds.begin(); it != SceneBounds.end();)
  {
    it->second.erase(representation);
    it = it->second.empty() ? SceneBounds.erase(it) : std::next(it);
  }
}

bool vtkStrataParaViewUtilities::GetProcessBox(vtkView* view, double box[6])
{
  const int processes = NumberOfProcesses();
  double scene[6];
  if (processes < 2 || !SceneBox(view, scene))
    return false;
  PartitionBox(scene, processes, ProcessId(), box);
  for (int a = 0; a < 3; ++a)
  {
    const double size = std::max(scene[2 * a + 1] - scene[2 * a], 1.0);
    if (box[2 * a] <= scene[2 * a])
      box[2 * a] -= size;
    if (box[2 * a + 1] >= scene[2 * a + 1])
      box[2 * a + 1] += size;
  }
  return true;
}

void vtkStrataParaViewUtilities::RequestCoarsestLevels(vtkInformationVector* inputs)
{
  for (int i = 0; i < inputs->GetNumberOfInformationObjects(); ++i)
  {
    inputs->GetInformationObject(i)->Set(vtkPagePoolProtocol::UPDATE_RESOLUTION(), 0.0);
  }
}

void vtkStrataParaViewUtilities::CopyTransform(vtkProp3D* from, vtkProp3D* to)
{
  to->SetPosition(from->GetPosition());
  to->SetOrientation(from->GetOrientation());
  to->SetScale(from->GetScale());
  to->SetOrigin(from->GetOrigin());
}

bool vtkStrataParaViewUtilities::AddProp(vtkView* view, vtkProp* prop)
{
  auto* rview = vtkPVRenderView::SafeDownCast(view);
  if (!rview)
  {
    return false;
  }
  rview->GetRenderer()->AddViewProp(prop);
  return true;
}

bool vtkStrataParaViewUtilities::RemoveProp(vtkView* view, vtkProp* prop)
{
  auto* rview = vtkPVRenderView::SafeDownCast(view);
  if (!rview)
  {
    return false;
  }
  rview->GetRenderer()->RemoveViewProp(prop);
  return true;
}
