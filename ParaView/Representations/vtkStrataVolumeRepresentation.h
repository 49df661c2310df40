// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStrataVolumeRepresentation
 * @brief   ParaView's "Strata Volume" representation: every volume shown with it in a view is
 *          ray cast together, overlapping volumes included, by one vtkMultiVolumeRayCastMapper.
 *
 * ParaView makes one representation per data set and view. This one adds its volume (its
 * vtkVolumeProperty: the lookup table and scalar opacity function ParaView's colour-map editor
 * edits, interpolation, scalar opacity unit distance) to a scene shared by all the Strata
 * Volume representations of its view: one mapper, one input port per visible volume (a
 * vtkMultiVolume when there are several; a plain vtkVolume for one), so that overlapping volumes
 * blend sample by sample in one pass, each through its own transfer function, which ParaView's
 * own volume representation cannot do. Settings that belong to the ray cast as a whole
 * (classification, rays per pixel, sample distance, budgets, paging) are taken from the first
 * visible Strata volume of the view, in the order they were shown.
 *
 * A volume read from a page pool (vtkPagePoolReader, whose ParaView source reads only the
 * coarsest level) is paged by the mapper from the pool; PagingConverged says when the cut has
 * settled. The data stays where it was read (never delivered to the client).
 *
 * An array of several components is drawn as ParaView's own volume representation draws it
 * (vtkImageVolumeRepresentation with vtkSmartVolumeMapper): Map Scalars off or Multi Components
 * Mapping on make the components dependent (RGBA, colour + opacity); otherwise the colour map's
 * vector mode chooses. Component k: that component alone, through the colour map and opacity
 * function (the others weigh 0, VTK's component weights). Magnitude: a float volume of the
 * components' Euclidean norm, made here from an in-core volume; a paged volume's components
 * page from separate pools, so its magnitude is not made: its chosen component is drawn, with
 * a warning.
 */
#ifndef vtkStrataVolumeRepresentation_h
#define vtkStrataVolumeRepresentation_h

#include "StrataParaViewModule.h" // For export macro
#include "vtkNew.h"               // For vtkNew
#include "vtkSmartPointer.h"      // For vtkSmartPointer
#include "vtkVolumeRepresentation.h"

#include <string> // For std::string

class vtkMultiVolumeRayCastMapper;
class vtkStrataPooledProducer;
class vtkVolume;

class STRATAPARAVIEW_EXPORT vtkStrataVolumeRepresentation : public vtkVolumeRepresentation
{
public:
  static vtkStrataVolumeRepresentation* New();
  vtkTypeMacro(vtkStrataVolumeRepresentation, vtkVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(vtkInformationRequestKey* request,
    vtkInformation* inInfo,
    vtkInformation* outInfo) override;
  void SetVisibility(bool visible) override;

  /// The ray cast's settings (vtkMultiVolumeRayCastMapper's documentation says what each does).
  struct Settings
  {
    double SampleDistance = 1.0;
    int Classification = 0; ///< 0 post-classification, 1 pre-integrated, 2 its approximation
    int PreIntegrationTableSize = 256;
    int RaysPerPixel = 1;
    bool RayCoherence = false;
    int CompositeOrder = 0; ///< 0 front to back, 1 back to front
    double TerminationOpacity = 0.999;
    bool UseBrickAtlas = true;
    int ScalarStorage = 1; ///< 0 float, 1 R16 for 8- and 16-bit data, 2 R8 for 8-bit (native)
    int BrickSize = 32;
    double AtlasBudget = 256.0;
    bool EmptySpaceSkipping = true;
    int SkipCellSize = 8;
    double PageCacheBudget = 512.0;
    int PagesPerFrame = 64;
    bool Prefetch = false;
    bool LevelOfDetailFeedback = true;
    int FeedbackScale = 4;
    double LevelOfDetailThreshold = 0.0;
    int Stage = 0; ///< 0 Auto, 1 Fragment, 2 Compute (vtkMultiVolumeRayCastMapper::Stages)
  };

  ///@{
  /// Setters of the Settings, one per ParaView property.
  void SetSampleDistance(double value);
  void SetClassification(int value);
  void SetPreIntegrationTableSize(int value);
  void SetRaysPerPixel(int value);
  void SetRayCoherence(bool value);
  void SetCompositeOrder(int value);
  void SetTerminationOpacity(double value);
  void SetUseBrickAtlas(bool value);
  void SetScalarStorage(int value);
  void SetBrickSize(int value);
  void SetAtlasBudget(double value);
  void SetEmptySpaceSkipping(bool value);
  void SetSkipCellSize(int value);
  void SetPageCacheBudget(double value);
  void SetPagesPerFrame(int value);
  void SetPrefetch(bool value);
  void SetLevelOfDetailFeedback(bool value);
  void SetFeedbackScale(int value);
  void SetLevelOfDetailThreshold(double value);
  void SetStage(int value);
  ///@}
  const Settings& GetSettings() const { return this->Options; }

  ///@{
  /// After a render: whether the view's volumes have settled (1 in core), how many volumes the
  /// view's scene ray casts together, whether this one is paged from a pool.
  int GetPagingConverged();
  int GetNumberOfVolumesInScene();
  int GetPaged();
  ///@}

  ///@{
  /// After a render: the stage the view's volumes were ray cast in (1 Fragment, 2 Compute; 0
  /// before a render) and Auto's probe of this device, compute / fragment (0 if not probed).
  int GetStageInUse();
  double GetStageProbeRatio();
  ///@}

  ///@{
  /**
   * After a render, for a paged time series (vtkPagePoolReader's TimeStepFiles): the step the
   * volume shows (0 without a series); the frames the render thread waited on the disk, in all
   * (a step switch whose pages were not prefetched in time); and, of the pages the last frame
   * held, how many of the next step's in playback order are in RAM, against how many it held.
   * Of the view's whole scene, like PagingConverged.
   */
  int GetTimeStep();
  int GetIoWaitFrames();
  int GetNextStepPagesResident();
  int GetNextStepPagesWanted();
  ///@}

  ///@{
  /**
   * Benchmarks (default empty: off): when set on the view's first visible Strata Volume, every
   * process appends to `<StatisticsFile>.<rank>` one CSV line per render, before it, about the
   * render before: rank, ray-cast milliseconds (the mapper's MeasureRenderTime: GPU finished),
   * MB paged from the pools so far, peak RSS in MB, resident bricks, settled (0/1), and the box
   * the process draws (xmin, xmax, ymin, ymax, zmin, zmax: GetProcessBox; nan in one process). In
   * parallel that is the only way to see every rank's figures (ParaView's information
   * properties come from rank 0).
   */
  void SetStatisticsFile(const char* name);
  const char* GetStatisticsFile() const { return this->StatisticsFile.c_str(); }
  ///@}

  /// The mapper of this representation's view (null before it is added to one).
  vtkMultiVolumeRayCastMapper* GetMapper();
  /// The volume this representation contributes to the scene.
  vtkVolume* GetVolume() { return this->Member; }
  /// The producer the mapper reads this volume from.
  vtkStrataPooledProducer* GetProducer() { return this->Producer; }

  class vtkScene;

protected:
  vtkStrataVolumeRepresentation();
  ~vtkStrataVolumeRepresentation() override;

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
  vtkStrataVolumeRepresentation(const vtkStrataVolumeRepresentation&) = delete;
  void operator=(const vtkStrataVolumeRepresentation&) = delete;

  void SettingsChanged();
  void WriteStatistics();
  /// The property's component mapping and the image the mapper reads, from Map Scalars, Multi
  /// Components Mapping and the colour map's vector mode (see the class comment).
  void MapComponents();
  /**
   * The image whose point scalars the mapper maps, as ParaView's Coloring (ColorArrayName)
   * chooses: the input itself when it names the active point scalars or nothing (so that a
   * pool stays paged), else an image of the chosen array alone: a point array as the scalars
   * of the same points, a cell array as the scalars of the cell centres (one point fewer per
   * axis, shifted half a cell), the values exactly as they are.
   */
  vtkImageData* ColoredImage();

  Settings Options;
  vtkNew<vtkVolume> Member;
  vtkNew<vtkStrataPooledProducer> Producer;
  vtkSmartPointer<vtkDataObject> Cache;
  vtkSmartPointer<vtkImageData> Magnitude; // the norm of Cache's components, made on demand
  vtkSmartPointer<vtkImageData> Colored;   // ColoredImage's image of another array than Cache's
  std::string ColoredKey;                  // its array: association and name
  bool MagnitudeWarned = false;
  bool HasData = false;
  std::string StatisticsFile;
  vtkScene* Scene = nullptr; // shared with the view's other Strata volumes; owned by them all
};

#endif
