// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataVolumeRepresentation.h"

#include "vtkActor.h"
#include "vtkAlgorithmOutput.h"
#include "vtkArrayDispatch.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleKey.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkObjectFactory.h"
#include "vtkPVLODVolume.h"
#include "vtkPVRenderView.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkStrataHorizonsRepresentation.h"
#include "vtkStrataParaViewUtilities.h"
#include "vtkStrataPooledProducer.h"
#include "vtkView.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <sys/resource.h> // For getrusage (peak RSS in the statistics)

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <vector>

/**
 * The volumes of one view: the mapper, the prop in the renderer (the only volume, or a
 * vtkMultiVolume of them all) and the representations that contribute, in the order shown.
 * Sync() makes the mapper's ports and the prop match the visible members; every member calls
 * it before each render, and it changes nothing when nothing changed.
 */
class vtkStrataVolumeRepresentation::vtkScene
{
public:
  explicit vtkScene(vtkRenderer* renderer)
    : Renderer(renderer)
  {
  }
  ~vtkScene() { this->Show(nullptr); }

  void Sync();
  std::vector<vtkStrataVolumeRepresentation*> Visible() const;
  void Show(vtkProp3D* prop);
  void Apply(const Settings& s);
  /// The actors of the view's Strata Horizons with translucent horizons, to the ray cast.
  void GatherTranslucentHorizons(vtkView* view);
  /// The renderer's UseDepthPeelingForVolumes off while Strata Volumes are shown (restored).
  void KeepVolumesOutOfDepthPeeling(bool shown);

  vtkSmartPointer<vtkRenderer>
    Renderer; // kept: the view may drop its renderer before its representations
  vtkNew<vtkMultiVolumeRayCastMapper> Mapper;
  vtkNew<vtkMultiVolume> Multi;
  std::vector<vtkStrataVolumeRepresentation*> Members;
  vtkProp3D* Shown = nullptr;
  // The view's stacks with translucent horizons given to the ray cast (the mapper holds them).
  std::vector<vtkActor*> Translucent;
  bool PeelingVolumes = false; // the renderer's UseDepthPeelingForVolumes before the scene's
  bool PeelingVolumesSaved = false;
  int Ports = 0;      // input ports connected, 0 .. Ports - 1
  int MultiPorts = 0; // volumes set on Multi
};

namespace
{
std::map<vtkView*, vtkStrataVolumeRepresentation::vtkScene*> Scenes;

/// Fills a float array with the Euclidean norm of each tuple of an array of any type.
struct MagnitudeWorker
{
  template<typename Array>
  void operator()(Array* in, vtkFloatArray* out)
  {
    const auto tuples = vtk::DataArrayTupleRange(in);
    float* values = out->GetPointer(0);
    vtkSMPTools::For(0,
      tuples.size(),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          double sum = 0.0;
          for (const auto v : tuples[i])
            sum += static_cast<double>(v) * static_cast<double>(v);
          values[i] = static_cast<float>(std::sqrt(sum));
        }
      });
  }
};

/// `image`'s geometry with one float scalar: the norm of the components of `scalars`.
vtkSmartPointer<vtkImageData> MakeMagnitude(vtkImageData* image, vtkDataArray* scalars)
{
  vtkNew<vtkFloatArray> norm;
  norm->SetName((std::string(scalars->GetName() ? scalars->GetName() : "") + "_Magnitude").c_str());
  norm->SetNumberOfTuples(scalars->GetNumberOfTuples());
  MagnitudeWorker worker;
  if (!vtkArrayDispatch::Dispatch::Execute(scalars, worker, norm.GetPointer()))
    worker(scalars, norm.GetPointer());
  auto magnitude = vtkSmartPointer<vtkImageData>::New();
  magnitude->CopyStructure(image);
  magnitude->GetPointData()->SetScalars(norm);
  return magnitude;
}
}

//------------------------------------------------------------------------------
std::vector<vtkStrataVolumeRepresentation*> vtkStrataVolumeRepresentation::vtkScene::Visible() const
{
  std::vector<vtkStrataVolumeRepresentation*> shown;
  for (auto* member : this->Members)
  {
    if (member->GetVisibility() && member->HasData)
      shown.push_back(member);
  }
  return shown;
}

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::vtkScene::Show(vtkProp3D* prop)
{
  if (prop == this->Shown)
    return;
  if (this->Shown)
    this->Renderer->RemoveVolume(this->Shown);
  if (prop)
    this->Renderer->AddVolume(prop);
  this->Shown = prop;
}

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::vtkScene::Sync()
{
  const auto shown = this->Visible();
  const int n = static_cast<int>(shown.size());
  for (int port = 0; port < n; ++port)
  {
    vtkAlgorithmOutput* output = shown[port]->Producer->GetOutputPort();
    if (port >= this->Ports || this->Mapper->GetInputConnection(port, 0) != output)
      this->Mapper->SetInputConnection(port, output);
  }
  for (int port = n; port < this->Ports; ++port)
    this->Mapper->RemoveInputConnection(port, 0);
  this->Ports = n;

  // Each volume carries its representation's transform, and its components the mapping
  // ParaView's Map Scalars, Multi Components Mapping and vector mode choose.
  for (auto* member : shown)
  {
    vtkStrataParaViewUtilities::CopyTransform(member->Actor, member->Member);
    member->MapComponents();
  }
  if (n == 1)
  {
    for (int port = 0; port < this->MultiPorts; ++port)
      this->Multi->RemoveVolume(port);
    this->MultiPorts = 0;
    shown[0]->Member->SetMapper(this->Mapper);
    this->Show(shown[0]->Member);
  }
  else if (n > 1)
  {
    for (auto* member : this->Members)
      member->Member->SetMapper(nullptr);
    for (int port = 0; port < n; ++port)
    {
      // (GetVolume reports an error for a port not set yet.)
      if (port >= this->MultiPorts ||
          this->Multi->GetVolume(port) != shown[port]->Member.GetPointer())
        this->Multi->SetVolume(shown[port]->Member, port);
    }
    for (int port = n; port < this->MultiPorts; ++port)
      this->Multi->RemoveVolume(port);
    this->MultiPorts = n;
    this->Multi->SetMapper(this->Mapper);
    this->Show(this->Multi);
  }
  else
  {
    this->Show(nullptr);
  }
  if (n > 0)
  {
    this->Apply(shown[0]->Options);
    this->GatherTranslucentHorizons(shown[0]->GetView());
  }
  this->KeepVolumesOutOfDepthPeeling(n > 0);
  // In parallel: this process's box of the scene (all volumes and horizons of the view).
  vtkStrataParaViewUtilities::UseProcessBox(
    n > 0 ? shown[0]->GetView() : nullptr, this->Mapper.GetPointer());
}

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::vtkScene::KeepVolumesOutOfDepthPeeling(bool shown)
{
  // ParaView peels translucent geometry with VTK's dual depth peeling and, by default
  // (DepthPeelingForVolumes), the volumes with it: a pass that injects code written for VTK's
  // own GPU ray caster into the volume mappers' shaders (see
  // vtkMultiVolumeRayCastMapper::AddTranslucentActor), which garbles a Strata ray cast as soon as
  // the view holds translucent geometry. While Strata Volumes are shown the renderer keeps its
  // volumes out of the peeling; the translucent horizons are composited by the ray cast itself.
  vtkRenderer* renderer = this->Renderer;
  if (shown && !this->PeelingVolumesSaved)
  {
    this->PeelingVolumes = renderer->GetUseDepthPeelingForVolumes();
    this->PeelingVolumesSaved = true;
  }
  if (shown)
    renderer->SetUseDepthPeelingForVolumes(false);
  else if (this->PeelingVolumesSaved)
  {
    renderer->SetUseDepthPeelingForVolumes(this->PeelingVolumes);
    this->PeelingVolumesSaved = false;
  }
}

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::vtkScene::GatherTranslucentHorizons(vtkView* view)
{
  std::vector<vtkActor*> actors;
  for (int i = 0; view && i < view->GetNumberOfRepresentations(); ++i)
  {
    auto* horizons = vtkStrataHorizonsRepresentation::SafeDownCast(view->GetRepresentation(i));
    if (horizons && horizons->GetVisibility() && horizons->HasTranslucentHorizons())
      actors.push_back(horizons->GetActor());
  }
  if (actors == this->Translucent)
    return;
  this->Mapper->RemoveAllTranslucentActors();
  for (vtkActor* actor : actors)
    this->Mapper->AddTranslucentActor(actor);
  this->Translucent = actors;
}

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::vtkScene::Apply(const Settings& s)
{
  vtkMultiVolumeRayCastMapper* m = this->Mapper;
  m->SetSampleDistance(s.SampleDistance);
  m->SetClassification(static_cast<vtkMultiVolumeRayCastMapper::Classifications>(
    std::min(2, std::max(0, s.Classification))));
  m->SetPreIntegrationTableSize(s.PreIntegrationTableSize);
  m->SetRaysPerPixel(s.RaysPerPixel);
  m->SetStage(static_cast<vtkMultiVolumeRayCastMapper::Stages>(std::min(2, std::max(0, s.Stage))));
  m->SetRayCoherence(s.RayCoherence);
  m->SetCompositeOrder(s.CompositeOrder == 1
                         ? vtkMultiVolumeRayCastMapper::CompositeOrders::BackToFront
                         : vtkMultiVolumeRayCastMapper::CompositeOrders::FrontToBack);
  m->SetTerminationOpacity(s.TerminationOpacity);
  m->SetUseBrickAtlas(s.UseBrickAtlas);
  m->SetScalarStorage(static_cast<vtkMultiVolumeRayCastMapper::ScalarStorages>(
    std::min(2, std::max(0, s.ScalarStorage))));
  m->SetBrickSize(s.BrickSize);
  m->SetAtlasBudget(s.AtlasBudget);
  m->SetEmptySpaceSkipping(s.EmptySpaceSkipping);
  m->SetSkipCellSize(s.SkipCellSize);
  m->SetPageCacheBudget(s.PageCacheBudget);
  m->SetPagesPerFrame(s.PagesPerFrame);
  m->SetPrefetch(s.Prefetch);
  m->SetLevelOfDetailFeedback(s.LevelOfDetailFeedback);
  m->SetFeedbackScale(s.FeedbackScale);
  m->SetLevelOfDetailThreshold(s.LevelOfDetailThreshold);
}

vtkStandardNewMacro(vtkStrataVolumeRepresentation);

//------------------------------------------------------------------------------
vtkStrataVolumeRepresentation::vtkStrataVolumeRepresentation()
{
  this->Member->SetProperty(this->Property);
}

//------------------------------------------------------------------------------
vtkStrataVolumeRepresentation::~vtkStrataVolumeRepresentation() = default;

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Paged: " << this->GetPaged() << "\n";
  os << indent << "VolumesInScene: " << (this->Scene ? this->Scene->Members.size() : 0) << "\n";
  os << indent << "StatisticsFile: " << this->StatisticsFile << "\n";
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::RequestUpdateExtent(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestUpdateExtent(request, inputVector, outputVector))
  {
    return 0;
  }
  // A pool gives its coarsest level (the mapper pages the rest), all of it on every process
  // (each draws its box of the scene).
  vtkStrataParaViewUtilities::RequestCoarsestLevels(inputVector[0]);
  vtkStrataParaViewUtilities::RequestWholeData(inputVector[0]);
  return 1;
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkMath::UninitializeBounds(this->DataBounds);
  this->DataSize = 0;
  vtkImageData* input = inputVector[0]->GetNumberOfInformationObjects() == 1
                          ? vtkImageData::GetData(inputVector[0], 0)
                          : nullptr;
  this->HasData = input && input->GetNumberOfPoints() > 0;
  if (this->HasData)
  {
    vtkNew<vtkImageData> cache;
    cache->ShallowCopy(input);
    this->Producer->SetOutput(cache);
    cache->GetBounds(this->DataBounds);
    this->DataSize = cache->GetActualMemorySize();
    this->Cache = cache;
  }
  else
  {
    this->Cache = vtkSmartPointer<vtkImageData>::New();
  }
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::ProcessViewRequest(vtkInformationRequestKey* request,
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
    // The whole scene's box cut into one per process (ordered compositing).
    vtkStrataParaViewUtilities::DeclarePropInScene(this, inInfo, this->DataBounds, this->Actor);
  }
  else if (request == vtkPVView::REQUEST_UPDATE_LOD())
  {
    vtkPVRenderView::SetRequiresDistributedRenderingLOD(inInfo, this, true);
  }
  else if (request == vtkPVView::REQUEST_RENDER() && this->Scene)
  {
    this->Scene->Sync();
    const auto shown = this->Scene->Visible();
    if (!shown.empty() && shown[0] == this)
      this->WriteStatistics();
  }
  return 1;
}

//------------------------------------------------------------------------------
bool vtkStrataVolumeRepresentation::AddToView(vtkView* view)
{
  auto* rview = vtkPVRenderView::SafeDownCast(view);
  if (!rview)
  {
    return false;
  }
  vtkScene*& scene = Scenes[view];
  if (!scene)
    scene = new vtkScene(rview->GetRenderer());
  scene->Members.push_back(this);
  this->Scene = scene;
  return this->Superclass::AddToView(view);
}

//------------------------------------------------------------------------------
bool vtkStrataVolumeRepresentation::RemoveFromView(vtkView* view)
{
  auto it = Scenes.find(view);
  if (it == Scenes.end() || it->second != this->Scene)
  {
    return false;
  }
  auto& members = this->Scene->Members;
  members.erase(std::remove(members.begin(), members.end(), this), members.end());
  vtkStrataParaViewUtilities::ForgetSceneBounds(this);
  this->Member->SetMapper(nullptr);
  if (members.empty())
  {
    delete this->Scene;
    Scenes.erase(it);
  }
  else
  {
    this->Scene->Sync();
  }
  this->Scene = nullptr;
  return this->Superclass::RemoveFromView(view);
}

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  if (!visible)
    vtkStrataParaViewUtilities::ForgetSceneBounds(this);
  if (this->Scene)
    this->Scene->Sync();
}

//------------------------------------------------------------------------------
vtkMultiVolumeRayCastMapper* vtkStrataVolumeRepresentation::GetMapper()
{
  return this->Scene ? this->Scene->Mapper.GetPointer() : nullptr;
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::GetPagingConverged()
{
  return !this->Scene || this->Scene->Mapper->GetPagingStatistics().Converged ? 1 : 0;
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::GetNumberOfVolumesInScene()
{
  return this->Scene ? static_cast<int>(this->Scene->Visible().size()) : 0;
}

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::MapComponents()
{
  // As vtkImageVolumeRepresentation::UpdateMapperParameters: dependent when either says so.
  const bool independent = this->MapScalars && !this->MultiComponentsMapping;
  vtkVolumeProperty* property = this->Property;
  property->SetIndependentComponents(independent ? 1 : 0);
  vtkImageData* image = this->ColoredImage();
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  const int components = scalars ? std::min(4, scalars->GetNumberOfComponents()) : 1;
  vtkColorTransferFunction* color = property->GetRGBTransferFunction(0);
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  const int chosen = color ? std::min(std::max(color->GetVectorComponent(), 0), components - 1) : 0;
  bool magnitude = independent && components > 1 && color &&
                   color->GetVectorMode() == vtkScalarsToColors::MAGNITUDE;
  if (magnitude && this->GetPaged())
  {
    if (!this->MagnitudeWarned)
      vtkWarningMacro("Strata Volume draws no magnitude of a paged volume of several components "
                      "(each pages from its own pool): component "
                      << chosen << " is drawn.");
    this->MagnitudeWarned = true;
    magnitude = false;
  }
  // Component mode (as vtkSmartVolumeMapper::SetupVectorMode): the chosen component alone,
  // through the colour map and opacity function.
  for (int c = 0; c < components; ++c)
  {
    if (independent && c > 0)
    {
      property->SetColor(c, color);
      property->SetScalarOpacity(c, opacity);
    }
    property->SetComponentWeight(c, !independent || magnitude || c == chosen ? 1.0 : 0.0);
  }
  vtkDataObject* shown = image ? image : this->Cache.GetPointer();
  if (magnitude)
  {
    // (Made after the image it is of: older than the image, it is of another.)
    if (!this->Magnitude || this->Magnitude->GetMTime() < image->GetMTime())
      this->Magnitude = MakeMagnitude(image, scalars);
    shown = this->Magnitude;
  }
  if (this->Producer->GetOutputDataObject(0) != shown)
    this->Producer->SetOutput(shown);
}

//------------------------------------------------------------------------------
vtkImageData* vtkStrataVolumeRepresentation::ColoredImage()
{
  auto* image = vtkImageData::SafeDownCast(this->Cache);
  vtkInformation* info = this->GetInputArrayInformation(0);
  const char* name =
    info->Has(vtkDataObject::FIELD_NAME()) ? info->Get(vtkDataObject::FIELD_NAME()) : nullptr;
  if (!image || !name || !*name)
    return image;
  const bool cells =
    info->Has(vtkDataObject::FIELD_ASSOCIATION()) &&
    info->Get(vtkDataObject::FIELD_ASSOCIATION()) == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  vtkDataArray* array =
    cells ? image->GetCellData()->GetArray(name) : image->GetPointData()->GetArray(name);
  if (!array || (!cells && array == image->GetPointData()->GetScalars()))
    return image; // (ParaView's domain offers only the input's arrays: a stale name.)
  const std::string key = (cells ? "cells:" : "points:") + std::string(name);
  if (this->Colored && this->ColoredKey == key && this->Colored->GetMTime() > image->GetMTime())
    return this->Colored;
  auto colored = vtkSmartPointer<vtkImageData>::New();
  if (cells)
  {
    // The cell centres: an axis of n points has n - 1 cells (a flat axis keeps its one point).
    int extent[6];
    image->GetExtent(extent);
    double half[3] = { 0.0, 0.0, 0.0 };
    for (int a = 0; a < 3; ++a)
    {
      if (extent[2 * a + 1] > extent[2 * a])
      {
        --extent[2 * a + 1];
        half[a] = 0.5;
      }
    }
    double origin[3];
    image->TransformContinuousIndexToPhysicalPoint(half, origin);
    colored->SetExtent(extent);
    colored->SetSpacing(image->GetSpacing());
    colored->SetDirectionMatrix(image->GetDirectionMatrix());
    colored->SetOrigin(origin);
  }
  else
  {
    colored->CopyStructure(image);
  }
  colored->GetPointData()->SetScalars(array);
  this->Colored = colored;
  this->ColoredKey = key;
  return colored;
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::GetStageInUse()
{
  return this->Scene ? static_cast<int>(this->Scene->Mapper->GetStageInUse()) : 0;
}

//------------------------------------------------------------------------------
double vtkStrataVolumeRepresentation::GetStageProbeRatio()
{
  return this->Scene ? this->Scene->Mapper->GetStageProbeRatio() : 0.0;
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::GetPaged()
{
  return *this->Producer->GetPoolFileName() ? 1 : 0;
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::GetTimeStep()
{
  return this->Producer->GetPoolTimeStep();
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::GetIoWaitFrames()
{
  return this->Scene ? this->Scene->Mapper->GetPagingStatistics().IoWaitFrames : 0;
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::GetNextStepPagesResident()
{
  return this->Scene ? this->Scene->Mapper->GetPagingStatistics().NextStepPagesResident : 0;
}

//------------------------------------------------------------------------------
int vtkStrataVolumeRepresentation::GetNextStepPagesWanted()
{
  return this->Scene ? this->Scene->Mapper->GetPagingStatistics().NextStepPagesWanted : 0;
}

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::SetStatisticsFile(const char* name)
{
  const std::string value = name ? name : "";
  if (value != this->StatisticsFile)
  {
    this->StatisticsFile = value;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::WriteStatistics()
{
  vtkMultiVolumeRayCastMapper* mapper = this->Scene->Mapper;
  mapper->SetMeasureRenderTime(!this->StatisticsFile.empty());
  if (this->StatisticsFile.empty())
    return;
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const int rank = controller ? controller->GetLocalProcessId() : 0;
  std::ofstream out(this->StatisticsFile + "." + std::to_string(rank), std::ios::app);
  if (!out)
  {
    vtkErrorMacro("Cannot append to " << this->StatisticsFile << "." << rank);
    return;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto st = mapper->GetPagingStatistics();
  out << rank << "," << st.RenderMilliseconds << "," << st.BytesRead / 1048576.0 << ","
      << usage.ru_maxrss / 1024.0 << "," << mapper->GetNumberOfResidentBricks() << ","
      << (st.Converged ? 1 : 0);
  double box[6];
  const bool parallel = vtkStrataParaViewUtilities::GetProcessBox(this->GetView(), box);
  out.precision(17);
  for (int i = 0; i < 6; ++i)
    out << "," << (parallel ? box[i] : vtkMath::Nan());
  out << "\n";
}

//------------------------------------------------------------------------------
void vtkStrataVolumeRepresentation::SettingsChanged()
{
  this->Modified();
  if (this->Scene)
    this->Scene->Sync();
}

#define STRATA_SETTING(type, name)                                                                 \
  void vtkStrataVolumeRepresentation::Set##name(type value)                                        \
  {                                                                                                \
    if (this->Options.name != value)                                                               \
    {                                                                                              \
      this->Options.name = value;                                                                  \
      this->SettingsChanged();                                                                     \
    }                                                                                              \
  }
STRATA_SETTING(double, SampleDistance)
STRATA_SETTING(int, Classification)
STRATA_SETTING(int, PreIntegrationTableSize)
STRATA_SETTING(int, RaysPerPixel)
STRATA_SETTING(int, Stage)
STRATA_SETTING(bool, RayCoherence)
STRATA_SETTING(int, CompositeOrder)
STRATA_SETTING(double, TerminationOpacity)
STRATA_SETTING(bool, UseBrickAtlas)
STRATA_SETTING(int, ScalarStorage)
STRATA_SETTING(int, BrickSize)
STRATA_SETTING(double, AtlasBudget)
STRATA_SETTING(bool, EmptySpaceSkipping)
STRATA_SETTING(int, SkipCellSize)
STRATA_SETTING(double, PageCacheBudget)
STRATA_SETTING(int, PagesPerFrame)
STRATA_SETTING(bool, Prefetch)
STRATA_SETTING(bool, LevelOfDetailFeedback)
STRATA_SETTING(int, FeedbackScale)
STRATA_SETTING(double, LevelOfDetailThreshold)
#undef STRATA_SETTING
