// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataParaViewUtilities.h"

#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkPVRenderView.h"
#include "vtkPagePoolReader.h"
#include "vtkProp3D.h"
#include "vtkRenderer.h"

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

void vtkStrataParaViewUtilities::RequestCoarsestLevels(vtkInformationVector* inputs)
{
  for (int i = 0; i < inputs->GetNumberOfInformationObjects(); ++i)
  {
    inputs->GetInformationObject(i)->Set(vtkPagePoolReader::UPDATE_RESOLUTION(), 0.0);
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
