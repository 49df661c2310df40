// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStrataHybridRepresentation
 * @brief   ParaView's "Strata Hybrid" representation: a hybrid point + volume data set (the
 *          Strata Hybrid Volume reader's multiblock) drawn by vtkHybridVolumeMapper.
 *
 * The first image block is the low-resolution volume, the first polydata block its points
 * (vtkStrataHybridVolumeSource's layout). The volume property is ParaView's colour map and
 * opacity of the volume's array (as for its own volume representation); the mapper's point shape,
 * slabs and sample distance are properties. In parallel every process reads the whole data set
 * and draws the box of the view's scene that vtkStrataParaViewUtilities gives it
 * (vtkHybridVolumeMapper::SetRegion: the volume clipped to it, the points inside it).
 */
#ifndef vtkStrataHybridRepresentation_h
#define vtkStrataHybridRepresentation_h

#include "StrataParaViewModule.h" // For export macro
#include "vtkNew.h"               // For vtkNew
#include "vtkVolumeRepresentation.h"

class vtkHybridVolumeMapper;
class vtkTrivialProducer;
class vtkVolume;

class STRATAPARAVIEW_EXPORT vtkStrataHybridRepresentation : public vtkVolumeRepresentation
{
public:
  static vtkStrataHybridRepresentation* New();
  vtkTypeMacro(vtkStrataHybridRepresentation, vtkVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* request,
    vtkInformation* inInfo,
    vtkInformation* outInfo) override;
  void SetVisibility(bool visible) override;

  ///@{
  /// vtkHybridVolumeMapper's options.
  void SetPointShape(int shape); ///< 0 squares, 1 Gaussian splats
  void SetNumberOfSlabs(int slabs);
  void SetPointSpacing(double spacing);
  void SetSampleDistance(double distance);
  /// The volume part's stage: 0 Auto, 1 Fragment, 2 Compute (vtkMultiVolumeRayCastMapper::Stages).
  void SetStage(int stage);
  /// After a render: the stage the volume part was ray cast in (1 Fragment, 2 Compute).
  int GetStageInUse();
  ///@}

  /// Points the last render drew.
  int GetNumberOfPointsDrawn();

  vtkHybridVolumeMapper* GetMapper() { return this->Mapper; }

protected:
  vtkStrataHybridRepresentation();
  ~vtkStrataHybridRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

private:
  vtkStrataHybridRepresentation(const vtkStrataHybridRepresentation&) = delete;
  void operator=(const vtkStrataHybridRepresentation&) = delete;

  vtkNew<vtkHybridVolumeMapper> Mapper;
  vtkNew<vtkVolume> Member;
  vtkNew<vtkTrivialProducer> VolumeProducer;
  vtkNew<vtkTrivialProducer> PointsProducer;
  vtkSmartPointer<vtkDataObject> Cache;
};

#endif
