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

/**
 * Asks every input of `inputs` for the whole data set on every process (piece 0 of 1, no ghost
 * levels) instead of ParaView's piece of it: in parallel each process draws one box of the
 * whole scene (ProcessBox), not the piece its reader would have split off, and pages only what
 * that box needs.
 */
void RequestWholeData(vtkInformationVector* inputs);

///@{
/**
 * Sort-last parallel rendering (pvbatch or pvserver over MPI, IceT's ordered compositing). The
 * Strata representations of a view register their world bounds (DeclareSceneBounds, in their
 * REQUEST_UPDATE; uninitialised bounds or Forget drop them). Their union, the scene's box, is
 * cut into one box per process by recursive bisection (the longest axis of a box holding n
 * processes splits at floor(n/2) / n of its length), and every registered representation
 * declares this process's box as its geometry bounds with USE_BOUNDS_FOR_REDISTRIBUTION:
 * ParaView gathers them as its ordered-compositing boxes and IceT blends the processes'
 * premultiplied images in the order of those boxes from the camera, so a box must be exactly
 * what the process draws. Every process computes the same cut from the same whole data
 * (RequestWholeData), so no message is needed. The union of the boxes is the scene's box: the
 * view's bounds (camera reset, clipping range, hence the ray casters' sample lattice) are
 * those of one process.
 */
void DeclareSceneBounds(vtkPVDataRepresentation* representation,
  vtkInformation* inInfo,
  const double worldBounds[6]);
void ForgetSceneBounds(vtkPVDataRepresentation* representation);
/// DeclareSceneBounds of `dataBounds` moved by `prop`'s matrix (ParaView's Position,
/// Orientation, Scale and Origin); uninitialised bounds drop the representation.
void DeclarePropInScene(vtkPVDataRepresentation* representation,
  vtkInformation* inInfo,
  const double dataBounds[6],
  vtkProp3D* prop);
/**
 * The box the mappers of this process draw (SetRegion): its cell of the cut, with the faces on
 * the scene's box pushed out by the scene's size (nothing outside the scene is cut off, and an
 * outer face moves no ray's steps). False with one process or nothing registered: draw
 * everything.
 */
bool GetProcessBox(vtkView* view, double box[6]);
/// A mapper with SetRegion / RemoveRegion draws this process's box of `view` (none: all).
template<typename Mapper>
void UseProcessBox(vtkView* view, Mapper* mapper)
{
  double box[6];
  if (view && GetProcessBox(view, box))
    mapper->SetRegion(box);
  else
    mapper->RemoveRegion();
}
/// Cell `index` of `count` of the recursive bisection of `bounds` (see DeclareSceneBounds).
void PartitionBox(const double bounds[6], int count, int index, double cell[6]);
/// The world bounds of `bounds` moved by `transform` (its 8 corners' box); a copy when null.
void TransformBounds(const double bounds[6], vtkMatrix4x4* transform, double world[6]);
///@}

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
