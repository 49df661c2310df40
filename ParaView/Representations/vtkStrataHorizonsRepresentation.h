// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStrataHorizonsRepresentation
 * @brief   ParaView's "Strata Horizons" representation: a stack of horizons ray cast in one
 *          pass by vtkStackedHeightFieldMapper.
 *
 * Input: a horizon (vtkImageData) or a stack of them (a multiblock of images, as the Stack
 * Horizons filter or ParaView's Group Datasets make). Each horizon reaches the mapper through a
 * vtkStrataPooledProducer, so horizons read from tile pools are paged by the mapper (every
 * horizon of a stack pooled, or none). The mapper's options are the representation's properties;
 * PagingConverged (an information property) tells a script when the paged stack has settled.
 *
 * The data stays where it was read (it is never delivered to the client): the view renders it
 * where the pipeline ran, as ParaView's own volume representation does.
 */
#ifndef vtkStrataHorizonsRepresentation_h
#define vtkStrataHorizonsRepresentation_h

#include "StrataParaViewModule.h" // For export macro
#include "vtkNew.h"               // For vtkNew
#include "vtkPVDataRepresentation.h"
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <map>    // For std::map
#include <string> // For std::string
#include <vector> // For std::vector

class vtkActor;
class vtkScalarsToColors;
class vtkStackedHeightFieldMapper;
class vtkStrataPooledProducer;

class STRATAPARAVIEW_EXPORT vtkStrataHorizonsRepresentation : public vtkPVDataRepresentation
{
public:
  static vtkStrataHorizonsRepresentation* New();
  vtkTypeMacro(vtkStrataHorizonsRepresentation, vtkPVDataRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* request,
    vtkInformation* inInfo,
    vtkInformation* outInfo) override;
  void SetVisibility(bool visible) override;

  ///@{
  /// The actor's transform and material (as ParaView's surface representation names them).
  void SetScale(double x, double y, double z);
  void SetPosition(double x, double y, double z);
  void SetAmbient(double value);
  void SetDiffuse(double value);
  void SetSpecular(double value);
  void SetSpecularPower(double value);
  void SetOpacity(double value);
  ///@}

  ///@{
  /// vtkStackedHeightFieldMapper's options (its documentation says what each does).
  void SetHeightScale(double scale);
  /**
   * ParaView's Coloring drives the colours (one control: ColorArrayName, shared with the
   * surface representation, and its colour map, LookupTable): no array, one colour per horizon
   * (the mapper's palette); the horizons' heights (their active point scalars), the colour map
   * over the height; another point array of the horizons (a thickness, an amplitude along them),
   * each horizon coloured by it through the colour map (in core only: the mapper warns and colours
   * a paged horizon by its height). A preset of the colour map editor picks the depth colouring.
   */
  void SetLookupTable(vtkScalarsToColors* lut);

  /**
   * Opacity of horizon `index` of the stack (default 1). A translucent horizon is composited by
   * the view's Strata Volume ray cast where rays cross it, in order with the volume samples
   * (vtkMultiVolumeRayCastMapper::AddTranslucentActor): it shows inside the view's Strata
   * Volumes (a view without one draws its opaque horizons only, as the mapper does).
   * RemoveAllHorizonOpacities makes every horizon opaque again.
   */
  void SetHorizonOpacity(int index, double opacity);
  void RemoveAllHorizonOpacities();
  /// Whether a horizon of the stack is translucent.
  bool HasTranslucentHorizons() const;
  void SetNullValue(double value);
  void SetUseNullValue(bool use);
  void SetTileSize(int size);
  void SetLinearSearchStep(double step);
  /// 0 Auto, 1 Fragment, 2 Compute (vtkStackedHeightFieldMapper::Stages).
  void SetStage(int stage);
  /// After a render: the stage the stack was ray cast in (1 Fragment, 2 Compute; 0 before a
  /// render) and Auto's probe of this device, compute / fragment (0 if not probed).
  int GetStageInUse();
  double GetStageProbeRatio();
  void SetPageCacheBudget(double megabytes);
  void SetAtlasBudget(double megabytes);
  void SetPagesPerFrame(int pages);
  void SetPrefetch(bool prefetch);
  void SetMorphFrames(int frames);
  void SetLevelOfDetailFeedback(bool feedback);
  void SetFeedbackScale(int scale);
  void SetLevelOfDetailThreshold(double threshold);
  ///@}

  ///@{
  /// After a render: whether the paged stack has settled (always 1 in core), the number of
  /// horizons drawn and of those paged from pools.
  int GetPagingConverged();
  int GetNumberOfHorizons() const { return static_cast<int>(this->Producers.size()); }
  int GetNumberOfPagedHorizons();
  ///@}

  /// The mapper and the actor, for C++ callers and tests.
  vtkStackedHeightFieldMapper* GetMapper() { return this->Mapper; }
  vtkActor* GetActor() { return this->Actor; }

protected:
  vtkStrataHorizonsRepresentation();
  ~vtkStrataHorizonsRepresentation() override;

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
  vtkStrataHorizonsRepresentation(const vtkStrataHorizonsRepresentation&) = delete;
  void operator=(const vtkStrataHorizonsRepresentation&) = delete;

  /// The mapper's colours from ColorArrayName and LookupTable (see SetLookupTable), set only
  /// when they change (a new table or array rebuilds the mapper's colours).
  void UpdateColoring();

  vtkNew<vtkStackedHeightFieldMapper> Mapper;
  vtkSmartPointer<vtkScalarsToColors> LookupTable;
  std::string ColoredBy; // the array the mapper colours by ("" solid), as last set
  vtkScalarsToColors* ColoredWith = nullptr; // the table it was set with
  size_t ColoredHorizons = 0;                // horizons it was set for
  bool ColoringCurrent = false;              // false after new data
  std::map<int, double> Opacities;           // the horizons set translucent
  vtkNew<vtkActor> Actor;
  std::vector<vtkSmartPointer<vtkStrataPooledProducer>> Producers;
  vtkSmartPointer<vtkDataObject> Cache;
  double DataBounds[6];
  unsigned long DataSize = 0;
};

#endif
