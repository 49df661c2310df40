// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * What Strata's ParaView representations do alike: they render their data where it was read
 * (ParaView only learns its size and bounds), ask pools behind their input for the coarsest
 * level only (the mappers page the rest), and carry ParaView's transform of the representation
 * over to the prop they render.
 */
#ifndef vtkStrataParaViewUtilities_h
#define vtkStrataParaViewUtilities_h

class vtkDataObject;
class vtkInformation;
class vtkInformationVector;
class vtkMatrix4x4;
class vtkPVDataRepresentation;
class vtkProp;
class vtkProp3D;
class vtkView;

namespace vtkStrataParaViewUtilities
{
/**
 * REQUEST_UPDATE of a representation that renders where its data is: the piece (never delivered
 * to the client), ordered compositing, its bounds (in the prop's frame when `transform` is given;
 * none when `bounds` is uninitialised) and distributed rendering.
 */
void DeclareLocalPiece(vtkPVDataRepresentation* representation,
  vtkInformation* inInfo,
  vtkInformation* outInfo,
  vtkDataObject* piece,
  unsigned long size,
  const double bounds[6],
  vtkMatrix4x4* transform = nullptr);

/// Asks every input of `inputs` for a pool's coarsest level (other readers ignore the key).
void RequestCoarsestLevels(vtkInformationVector* inputs);

///@{
/// Adds (removes) the prop a representation renders to (from) the renderer of `view`; false
/// when `view` is not a render view.
bool AddProp(vtkView* view, vtkProp* prop);
bool RemoveProp(vtkView* view, vtkProp* prop);
///@}

/// Position, orientation, scale and origin of `from` (ParaView's prop) onto `to` (the rendered
/// one).
void CopyTransform(vtkProp3D* from, vtkProp3D* to);
}

#endif
