// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStackedHeightFieldMapper.h"
#include "vtkStackedHeightFieldMapperInternals.h"

#include "StrataComputeStage.h"
#include "StrataFeedbackBuffer.h"
#include "StrataFeedbackReduction.h"
#include "StrataGraphicsResources.h"
#include "StrataHeightFieldPager.h"
#include "StrataHeightFieldShaderComposer.h"
#include "StrataHeightFieldStack.h"
#include "StrataHeightFieldStackBuffers.h"
#include "StrataHeightFieldTileAtlas.h"
#include "StrataMinMaxQuadtree.h"
#include "StrataRenderUtilities.h"
#include "StrataVolumeCut.h"
#include "StrataVolumeSurfaceLayers.h"
#include "vtkPagePoolProtocol.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkInformationStringKey.h"
#include "vtkInformationVector.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLState.h"
#include "vtkOrderIndependentTranslucentPass.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <vector>

vtkStandardNewMacro(vtkStackedHeightFieldMapper);

namespace
{
// Distinct colours for horizons without one of their own (after Paul Tol's "bright" scheme).
const double DefaultPalette[8][3] = { { 0.93, 0.40, 0.47 },
  { 0.27, 0.47, 0.67 },
  { 0.13, 0.53, 0.20 },
  { 0.80, 0.73, 0.27 },
  { 0.40, 0.80, 0.93 },
  { 0.67, 0.20, 0.47 },
  { 0.73, 0.73, 0.73 },
  { 0.90, 0.55, 0.20 } };

// The paper's default depth colour map: deep blue through cyan, green and yellow to red.
void DefaultDepthColor(double s, double rgb[3])
{
  static const double stops[5][3] = { { 0.15, 0.20, 0.75 },
    { 0.10, 0.70, 0.90 },
    { 0.20, 0.80, 0.30 },
    { 0.95, 0.85, 0.20 },
    { 0.85, 0.20, 0.15 } };
  s = std::min(std::max(s, 0.0), 1.0) * 4.0;
  const int k = std::min(static_cast<int>(s), 3);
  const double f = s - k;
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = stops[k][c] * (1.0 - f) + stops[k + 1][c] * f;
  }
}

}

vtkStackedHeightFieldMapper::vtkStackedHeightFieldMapper()
  : Internals(new vtkInternals(this))
{
  this->SetNumberOfInputPorts(1);
  this->Static = 0;
  this->Internals->ColorsModified.Modified();
  this->Stage = static_cast<Stages>(strata::ComputeStage::DefaultStage());
}

vtkStackedHeightFieldMapper::~vtkStackedHeightFieldMapper()
{
  // GL names die in their own context: the callback makes it current if the window lives.
  this->Internals->GraphicsResources.Release();
}

int vtkStackedHeightFieldMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  return 1;
}

void vtkStackedHeightFieldMapper::SetColorMode(ColorModes mode)
{
  if (this->ColorMode != mode)
  {
    this->ColorMode = mode;
    this->Modified();
  }
}

void vtkStackedHeightFieldMapper::SetOutputMode(OutputModes mode)
{
  if (this->OutputMode != mode)
  {
    this->OutputMode = mode;
    this->Modified();
  }
}

void vtkStackedHeightFieldMapper::SetHorizonColor(int index, double r, double g, double b)
{
  this->Internals->HorizonColors[index] = { r, g, b };
  this->Internals->ColorsModified.Modified();
  this->Modified();
}

void vtkStackedHeightFieldMapper::SetHorizonOpacity(int index, double opacity)
{
  opacity = std::min(std::max(opacity, 0.0), 1.0);
  if (this->GetHorizonOpacity(index) == opacity)
    return;
  if (opacity < 1.0)
    this->Internals->HorizonOpacities[index] = opacity;
  else
    this->Internals->HorizonOpacities.erase(index);
  this->Internals->ColorsModified.Modified();
  this->Modified();
}

double vtkStackedHeightFieldMapper::GetHorizonOpacity(int index) const
{
  return this->Internals->Opacity(index);
}

double vtkStackedHeightFieldMapper::vtkInternals::Opacity(int horizon) const
{
  auto it = this->HorizonOpacities.find(horizon);
  return it != this->HorizonOpacities.end() ? it->second : 1.0;
}

// Over the horizons the stack has (before the first read, over the opacities set).
bool vtkStackedHeightFieldMapper::vtkInternals::AnyTranslucent() const
{
  return std::any_of(this->HorizonOpacities.begin(),
    this->HorizonOpacities.end(),
    [this](const std::pair<const int, double>& e)
    { return !this->Valid || e.first < this->Layers; });
}

bool vtkStackedHeightFieldMapper::vtkInternals::AnyOpaque() const
{
  if (!this->Valid)
    return true;
  for (int k = 0; k < this->Layers; ++k)
    if (this->Opacity(k) >= 1.0)
      return true;
  return false;
}

bool vtkStackedHeightFieldMapper::HasOpaqueGeometry()
{
  return this->OutputMode != OutputModes::Shaded || this->Internals->AnyOpaque();
}

bool vtkStackedHeightFieldMapper::HasTranslucentPolygonalGeometry()
{
  return this->OutputMode == OutputModes::Shaded && this->Internals->AnyTranslucent();
}

void vtkStackedHeightFieldMapper::SetHorizonColorArray(int index, const char* name)
{
  auto& arrays = this->Internals->ColorArrays;
  const std::string value = name ? name : "";
  auto it = arrays.find(index);
  if ((it == arrays.end() ? std::string() : it->second) == value)
    return;
  if (value.empty())
    arrays.erase(index);
  else
    arrays[index] = value;
  this->Modified(); // the attribute grids are read with the inputs
}

void vtkStackedHeightFieldMapper::SetHorizonLookupTable(int index, vtkScalarsToColors* lut)
{
  if (lut)
    this->Internals->HorizonLuts[index] = lut;
  else
    this->Internals->HorizonLuts.erase(index);
  this->Internals->ColorsModified.Modified();
  this->Modified();
}

void vtkStackedHeightFieldMapper::SetHeightLookupTable(vtkScalarsToColors* lut)
{
  this->Internals->Lut = lut;
  this->Internals->ColorsModified.Modified();
  this->Modified();
}

std::string vtkStackedHeightFieldMapper::GetShaderSource() const
{
  return this->GetStageInUse() == Stages::Compute ? this->GetComputeShaderSource()
                                                  : this->GetFragmentShaderSource();
}

std::string vtkStackedHeightFieldMapper::GetFragmentShaderSource() const
{
  const vtkInternals& in = *this->Internals;
  return in.HasLastKey ? in.Composer.GetFragmentSource(in.LastKey) : std::string();
}

std::string vtkStackedHeightFieldMapper::GetComputeShaderSource() const
{
  const vtkInternals& in = *this->Internals;
  return in.HasLastKey ? in.Composer.GetComputeSource(in.LastKey) : std::string();
}

int vtkStackedHeightFieldMapper::GetNumberOfShaderSourcesBuilt() const
{
  return this->Internals->Composer.GetNumberOfSourcesBuilt();
}

int vtkStackedHeightFieldMapper::GetNumberOfShaderCompilations() const
{
  return this->Internals->Composer.GetNumberOfCompilations();
}

void vtkStackedHeightFieldMapper::GetGridToWorld(double m[16])
{
  this->UpdateStack();
  vtkMatrix4x4::DeepCopy(m, this->Internals->GridToWorld);
}

const strata::HeightFieldStack* vtkStackedHeightFieldMapper::GetStack()
{
  return this->UpdateStack() && !this->Internals->Paged ? &this->Internals->Stack : nullptr;
}

bool vtkStackedHeightFieldMapper::UpdateStack()
{
  vtkInternals& in = *this->Internals;
  const int n = this->GetNumberOfInputConnections(0);
  if (n == 0)
  {
    in.Valid = false;
    return false;
  }
  this->SetPooledInputsToCoarsest();
  this->GetExecutive()->Update();
  vtkMTimeType newest = this->GetMTime();
  std::vector<vtkImageData*> images;
  for (int i = 0; i < n; ++i)
  {
    auto* image = vtkImageData::SafeDownCast(this->GetInputDataObject(0, i));
    if (!image)
    {
      vtkErrorMacro("Input " << i << " is not vtkImageData.");
      in.Valid = false;
      return false;
    }
    newest = std::max(newest, image->GetMTime());
    images.push_back(image);
  }
  if (in.BuildTime >= newest && in.BuildTime != 0)
  {
    return in.Valid;
  }
  in.BuildTime = newest;
  in.Valid = false;
  in.Arrays.clear();
  int pooled = 0;
  for (int i = 0; i < n; ++i)
  {
    pooled +=
      vtkPagePoolProtocol::GetInputPool(this->GetInputInformation(0, i), images[i]).IsValid() ? 1
                                                                                              : 0;
  }
  if (pooled > 0 && pooled < n)
  {
    vtkErrorMacro(<< pooled << " of " << n
                  << " horizons come from page pools: page all horizons of a stack or none.");
    return false;
  }
  in.Paged = pooled > 0;
  in.AttributeLayer.assign(n, -1);
  in.Attributes.Initialize(1, 1);
  if (in.Paged)
  {
    if (!in.ColorArrays.empty())
    {
      vtkWarningMacro("Paged horizons carry heights only: the horizons given colour arrays are "
                      "coloured by their depth.");
    }
    return this->UpdatePagedStack(images);
  }

  int dims[3];
  images[0]->GetDimensions(dims);
  if (dims[2] != 1 || dims[0] < 1 || dims[1] < 1)
  {
    vtkErrorMacro("Height fields must be nx x ny x 1 images; input 0 is "
                  << dims[0] << " x " << dims[1] << " x " << dims[2] << ".");
    return false;
  }
  if (!in.Stack.Initialize(dims[0], dims[1]))
  {
    vtkErrorMacro("Cannot use the height-field grid: " << in.Stack.GetErrorMessage() << ".");
    return false;
  }
  const double* origin = images[0]->GetOrigin();
  const double* spacing = images[0]->GetSpacing();
  for (int i = 0; i < n; ++i)
  {
    int d[3];
    images[i]->GetDimensions(d);
    if (d[0] != dims[0] || d[1] != dims[1] || d[2] != 1)
    {
      vtkErrorMacro("Input " << i << " has " << d[0] << " x " << d[1] << " x " << d[2]
                             << " points; every horizon of a stack must share input 0's grid of "
                             << dims[0] << " x " << dims[1] << ".");
      return false;
    }
    const double* o = images[i]->GetOrigin();
    const double* s = images[i]->GetSpacing();
    for (int a = 0; a < 2; ++a)
    {
      if (std::abs(o[a] - origin[a]) >
            1e-6 * std::max(1.0, std::abs(spacing[a])) *
              std::max(1.0, std::abs(origin[a]) / std::max(1e-300, std::abs(spacing[a])) * 1e-3) ||
          std::abs(s[a] - spacing[a]) > 1e-9 * std::abs(spacing[a]))
      {
        vtkErrorMacro("Input " << i
                               << " lies on another lateral grid (origin or spacing differ "
                                  "from input 0).");
        return false;
      }
    }
    vtkDataArray* array = this->HeightArrayName.empty()
                            ? images[i]->GetPointData()->GetScalars()
                            : images[i]->GetPointData()->GetArray(this->HeightArrayName.c_str());
    if (!array || array->GetNumberOfComponents() != 1 ||
        array->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1])
    {
      vtkErrorMacro(
        "Input " << i << " has no single-component height array"
                 << (this->HeightArrayName.empty() ? "" : " named " + this->HeightArrayName)
                 << " with one value per point.");
      return false;
    }
    bool ok;
    if (auto* f = vtkFloatArray::FastDownCast(array))
    {
      ok = in.Stack.AddLayer(f->GetPointer(0), this->UseNullValue, this->NullValue);
      in.Arrays.emplace_back(f);
    }
    else if (auto* dbl = vtkDoubleArray::FastDownCast(array))
    {
      ok = in.Stack.AddLayer(dbl->GetPointer(0), this->UseNullValue, this->NullValue);
    }
    else
    {
      vtkNew<vtkDoubleArray> copy;
      copy->DeepCopy(array);
      ok = in.Stack.AddLayer(copy->GetPointer(0), this->UseNullValue, this->NullValue);
    }
    if (!ok)
    {
      vtkErrorMacro("Cannot add horizon " << i << ": " << in.Stack.GetErrorMessage());
      return false;
    }
  }
  if (!in.ReadAttributes(this, images))
  {
    return false;
  }
  in.Tree.Build(in.Stack, this->TileSize);
  in.NX = in.Stack.GetNX();
  in.NY = in.Stack.GetNY();
  in.Layers = in.Stack.GetNumberOfLayers();
  in.Stack.GetZRange(in.ZRange);
  in.Holes = in.Stack.HasHoles();

  // Grid space (x, y in cells of the effective grid, z = value) to world: image index
  // i = x + offset, then origin + D diag(sx, sy, HeightScale) (i, j, z).
  const double* dir = images[0]->GetDirectionMatrix()->GetData();
  const double scale[3] = { spacing[0], spacing[1], this->HeightScale };
  const double offset[2] = { in.Stack.GetIndexOffset(0), in.Stack.GetIndexOffset(1) };
  in.GridToWorld->Identity();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      in.GridToWorld->SetElement(r, c, dir[3 * r + c] * scale[c]);
    }
    in.GridToWorld->SetElement(
      r, 3, origin[r] + dir[3 * r] * scale[0] * offset[0] + dir[3 * r + 1] * scale[1] * offset[1]);
  }
  this->ComputeBounds();
  in.Valid = true;
  return true;
}

// --- The colour arrays of the horizons that have one, as a second stack on the same grid (the
// same ribbon expansion), one layer per coloured horizon.
bool vtkStackedHeightFieldMapper::vtkInternals::ReadAttributes(Self* self,
  const std::vector<vtkImageData*>& images)
{
  const int n = static_cast<int>(images.size());
  this->AttributeLayer.assign(n, -1);
  if (!this->Attributes.Initialize(this->Stack.GetInputNX(), this->Stack.GetInputNY()))
    return false;
  const vtkIdType points =
    static_cast<vtkIdType>(this->Stack.GetInputNX()) * this->Stack.GetInputNY();
  for (const auto& entry : this->ColorArrays)
  {
    const int k = entry.first;
    if (k < 0 || k >= n)
    {
      vtkWarningWithObjectMacro(self,
        "Horizon " << k << " has a colour array (" << entry.second << ") but the stack has " << n
                   << " horizons.");
      continue;
    }
    vtkDataArray* array = images[k]->GetPointData()->GetArray(entry.second.c_str());
    if (!array || array->GetNumberOfComponents() != 1 || array->GetNumberOfTuples() != points)
    {
      vtkErrorWithObjectMacro(self,
        "Horizon " << k << " has no single-component point array " << entry.second
                   << " with one value per point.");
      return false;
    }
    bool ok;
    if (auto* f = vtkFloatArray::FastDownCast(array))
    {
      ok = this->Attributes.AddLayer(f->GetPointer(0));
      this->Arrays.emplace_back(f);
    }
    else
    {
      vtkNew<vtkDoubleArray> copy;
      copy->DeepCopy(array);
      ok = this->Attributes.AddLayer(copy->GetPointer(0));
    }
    if (!ok)
    {
      vtkErrorWithObjectMacro(self,
        "Cannot read horizon " << k << "'s colour array " << entry.second << ": "
                               << this->Attributes.GetErrorMessage());
      return false;
    }
    this->AttributeLayer[k] = this->Attributes.GetNumberOfLayers() - 1;
  }
  return true;
}

void vtkStackedHeightFieldMapper::ComputeBounds()
{
  vtkInternals& in = *this->Internals;
  double zr[2] = { in.ZRange[0], in.ZRange[1] };
  if (zr[0] > zr[1])
  {
    zr[0] = zr[1] = 0.0;
  }
  vtkMath::UninitializeBounds(in.Bounds);
  for (int corner = 0; corner < 8; ++corner)
  {
    const double p[4] = { (corner & 1) ? in.NX - 1.0 : 0.0,
      (corner & 2) ? in.NY - 1.0 : 0.0,
      (corner & 4) ? zr[1] : zr[0],
      1.0 };
    double w[4];
    in.GridToWorld->MultiplyPoint(p, w);
    for (int a = 0; a < 3; ++a)
    {
      if (corner == 0 || w[a] < in.Bounds[2 * a])
        in.Bounds[2 * a] = w[a];
      if (corner == 0 || w[a] > in.Bounds[2 * a + 1])
        in.Bounds[2 * a + 1] = w[a];
    }
  }
}

void vtkStackedHeightFieldMapper::SetPooledInputsToCoarsest()
{
  // A tile pool's reader serves its coarsest level only: the tiles are paged, not read
  // through the pipeline.
  for (int i = 0; i < this->GetNumberOfInputConnections(0); ++i)
  {
    this->GetInputAlgorithm(0, i)->UpdateInformation();
    vtkPagePoolProtocol::RequestCoarsestLevel(this->GetInputInformation(0, i));
  }
}

vtkTypeBool vtkStackedHeightFieldMapper::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const vtkTypeBool result = this->Superclass::ProcessRequest(request, inputVector, outputVector);
  // Whatever updates the inputs (GetBounds, the render), a pool's reader serves its coarsest
  // level only.
  vtkPagePoolProtocol::RequestCoarsestLevels(request, inputVector, 1);
  return result;
}

bool vtkStackedHeightFieldMapper::UpdatePagedStack(const std::vector<vtkImageData*>& images)
{
  vtkInternals& in = *this->Internals;
  std::vector<strata::HeightFieldPager::Source> sources(images.size());
  in.RootValues.resize(images.size());
  for (size_t i = 0; i < images.size(); ++i)
  {
    const vtkPagePoolProtocol::Identity pool = vtkPagePoolProtocol::GetInputPool(
      this->GetInputInformation(0, static_cast<int>(i)), images[i]);
    sources[i].FileName = pool.FileName;
    sources[i].Layer = pool.Layer;
    // The reader's coarsest level is the root tile: the pager starts from it without a read.
    vtkDataArray* array = images[i]->GetPointData()->GetScalars();
    int d[3];
    images[i]->GetDimensions(d);
    if (array && array->GetNumberOfComponents() == 1 && d[2] == 1 &&
        array->GetNumberOfTuples() == static_cast<vtkIdType>(d[0]) * d[1])
    {
      in.RootValues[i].resize(static_cast<size_t>(d[0]) * d[1]);
      for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
      {
        in.RootValues[i][t] = static_cast<float>(array->GetTuple1(t));
      }
      sources[i].RootValues = in.RootValues[i].data();
      sources[i].RootDims[0] = d[0];
      sources[i].RootDims[1] = d[1];
    }
  }
  if (!in.Pager.Open(sources))
  {
    vtkErrorMacro("Cannot page the horizons: " << in.Pager.GetErrorMessage() << ".");
    return false;
  }
  in.Pager.SetTileSize(this->TileSize);
  in.NX = in.Pager.GetNX();
  in.NY = in.Pager.GetNY();
  in.Layers = in.Pager.GetNumberOfHorizons();
  in.Pager.GetValueRange(in.ZRange);
  // Holes may appear under paging (empty or missing tiles) whatever the data.
  in.Holes = true;
  double origin[3], spacing[3], dir[9];
  in.Pager.GetOrigin(origin);
  in.Pager.GetSpacing(spacing);
  in.Pager.GetDirection(dir);
  const double scale[3] = { spacing[0], spacing[1], this->HeightScale };
  in.GridToWorld->Identity();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      in.GridToWorld->SetElement(r, c, dir[3 * r + c] * scale[c]);
    }
    in.GridToWorld->SetElement(r, 3, origin[r]);
  }
  this->ComputeBounds();
  in.Valid = true;
  return true;
}

void vtkStackedHeightFieldMapper::AddInputData(vtkImageData* horizon)
{
  this->AddInputDataInternal(0, horizon);
}

vtkStackedHeightFieldMapper::PagingStatistics vtkStackedHeightFieldMapper::GetPagingStatistics()
  const
{
  return this->Internals->Paging;
}

void vtkStackedHeightFieldMapper::GetPagingStatistics(vtkFieldData* statistics) const
{
  strata::RenderUtilities::ToFieldData(this->Internals->Paging, statistics);
}

void vtkStackedHeightFieldMapper::RetryFailedPages()
{
  this->Internals->Pager.RetryFailedPages();
}

bool vtkStackedHeightFieldMapper::WaitForPages(double seconds)
{
  return this->Internals->Pager.WaitForIdle(seconds);
}

bool vtkStackedHeightFieldMapper::GetPaged() const
{
  return this->Internals->Paged;
}

const strata::HeightFieldPager* vtkStackedHeightFieldMapper::GetPager() const
{
  return &this->Internals->Pager;
}

double* vtkStackedHeightFieldMapper::GetBounds()
{
  if (!this->UpdateStack())
  {
    vtkMath::UninitializeBounds(this->Bounds);
    return this->Bounds;
  }
  std::copy(this->Internals->Bounds, this->Internals->Bounds + 6, this->Bounds);
  return this->Bounds;
}

// --- Paged: the atlas for the budget, the pager's frame (feedback read first if it was
// deferred), the tiles and borders it uploads, the page table when the cut changed.
bool vtkStackedHeightFieldMapper::vtkInternals::UpdatePages(Self* self,
  vtkRenderer* ren,
  vtkActor* actor)
{
  std::string error;
  const int allocated = this->Atlas.Allocate(self->AtlasBudget, this->Pager.GetPageSize(), error);
  if (allocated < 0)
  {
    vtkErrorWithObjectMacro(self, << error);
    return false;
  }
  if (allocated > 0)
  {
    this->Pager.SetAtlasSlots(this->Atlas.GetSlots());
    this->Pager.InvalidateAtlas();
  }
  this->Pager.SetCacheBudgetMiB(self->PageCacheBudget);
  this->Pager.SetPagesPerFrame(self->PagesPerFrame);
  this->Pager.SetPrefetch(self->Prefetch);
  this->Pager.SetMorphFrames(self->MorphFrames);
  // The last frame's feedback when its read-back was deferred (DeferFeedbackReadBack).
  if (this->Feedback.IsPending())
  {
    this->ReadFeedback(self);
  }
  // The cut refines by the size of a tile's points on screen, under this camera.
  vtkNew<vtkMatrix4x4> modelGrid;
  vtkMatrix4x4::Multiply4x4(actor->GetMatrix(), this->GridToWorld, modelGrid);
  std::vector<strata::HeightFieldPager::Upload> uploads;
  const bool changed =
    this->Pager.Update(strata::RenderUtilities::GetCutCamera(ren), modelGrid->GetData(), uploads);
  this->Paging.BytesUploaded = this->Atlas.Upload(this->Pager, uploads);
  if (changed || !this->Atlas.HasPageTable())
  {
    this->Atlas.UploadPageTable(this->Pager);
    this->TreeDirty = true;
  }
  for (const std::string& failure : this->Pager.TakeNewFailures())
  {
    vtkErrorWithObjectMacro(self, "Could not load " << failure << "; showing the coarser level.");
  }
  const std::string clamped = this->Pager.TakeBudgetWarning();
  if (!clamped.empty())
  {
    vtkWarningWithObjectMacro(self, << clamped);
  }
  static_cast<strata::HeightFieldPager::Statistics&>(this->Paging) = this->Pager.GetStatistics();
  this->Paging.Paged = true;
  this->Paging.AtlasSlots = this->Atlas.GetSlots();
  this->Paging.FeedbackUsed = this->FeedbackActive;
  return true;
}

// --- The stack on the GPU: paged, the pager's frame, the box and the tree when they changed;
// in core, the heights, the tree and the box when the inputs changed.
bool vtkStackedHeightFieldMapper::vtkInternals::Upload(Self* self,
  vtkRenderer* ren,
  vtkActor* actor,
  vtkOpenGLRenderWindow* renWin,
  bool pageFrame)
{
  if (this->Paged)
  {
    if (pageFrame && !this->UpdatePages(self, ren, actor))
      return false;
    if (this->UploadTime < this->BuildTime)
    {
      this->Buffers.UploadBox(this->NX, this->NY, this->ZRange);
      this->UploadTime = this->BuildTime;
    }
    if (this->TreeDirty)
    {
      this->Buffers.UploadTree(renWin, this->Pager.GetTree());
      this->TreeDirty = false;
    }
    return true;
  }
  if (this->UploadTime >= this->BuildTime && this->Buffers.HasHeights())
    return true;
  std::string error;
  if (!this->Buffers.UploadHeights(renWin, this->Stack, error) ||
      !this->Buffers.UploadAttributes(renWin, this->Attributes, error))
  {
    vtkErrorWithObjectMacro(self, << error);
    return false;
  }
  this->Buffers.UploadTree(renWin, this->Tree);
  this->Buffers.UploadBox(this->NX, this->NY, this->ZRange);
  this->UploadTime = this->BuildTime;
  return true;
}

// --- Colours: one per horizon (SetHorizonColor or the palette) or 1024 entries of the lookup
// table (or the default depth map) over its range or the stack's; or, when some horizon has its
// own table or colour array, per horizon a descriptor, its solid colour and its table.
namespace
{
const int TableEntries = 1024;

// A table of TableEntries colours over range, then the colour of no data.
void AppendTable(vtkScalarsToColors* lut, const double range[2], std::vector<float>& colors)
{
  for (int e = 0; e <= TableEntries; ++e)
  {
    double rgb[3] = { 0.5, 0.5, 0.5 };
    const double s = (e + 0.5) / TableEntries;
    if (e == TableEntries)
    {
      if (lut)
        lut->GetColor(std::nan(""), rgb);
    }
    else if (lut)
      lut->GetColor(range[0] + s * (range[1] - range[0]), rgb);
    else
      DefaultDepthColor(s, rgb);
    colors.insert(colors.end(), { float(rgb[0]), float(rgb[1]), float(rgb[2]), 1.0f });
  }
}

// The table's range: the table's own when it has one, else `fallback`; never empty.
/// Table entries per unit of a table's range, as the shaders scale by it: the reciprocal in
/// double (hi - lo of a narrow range far from 0, depths of 1e6, is 0 in float).
float EntriesPerUnit(const double range[2])
{
  return static_cast<float>(1024.0 / (range[1] - range[0]));
}

void TableRange(vtkScalarsToColors* lut, double lo, double hi, double range[2])
{
  range[0] = lo;
  range[1] = hi;
  if (lut)
  {
    const double* r = lut->GetRange();
    if (r[0] < r[1])
    {
      range[0] = r[0];
      range[1] = r[1];
    }
  }
  if (!(range[1] > range[0]))
    range[1] = range[0] + 1.0;
}
}

bool vtkStackedHeightFieldMapper::vtkInternals::ColorsCurrent() const
{
  if (this->ColorTime < this->ColorsModified.GetMTime() || this->ColorTime < this->BuildTime)
    return false;
  if (this->Lut && this->ColorTime < this->Lut->GetMTime())
    return false;
  for (const auto& entry : this->HorizonLuts)
  {
    if (this->ColorTime < entry.second->GetMTime())
      return false;
  }
  return true;
}

std::vector<float> vtkStackedHeightFieldMapper::vtkInternals::PerHorizonColors(Self* self) const
{
  std::vector<float> colors(8 * static_cast<size_t>(this->Layers), 0.0f);
  for (int k = 0; k < this->Layers; ++k)
  {
    auto lutIt = this->HorizonLuts.find(k);
    vtkScalarsToColors* lut = lutIt != this->HorizonLuts.end() ? lutIt->second.Get() : nullptr;
    const int attribute =
      k < static_cast<int>(this->AttributeLayer.size()) ? this->AttributeLayer[k] : -1;
    float* d = &colors[8 * static_cast<size_t>(k)];
    auto colorIt = this->HorizonColors.find(k);
    const double* rgb =
      colorIt != this->HorizonColors.end() ? colorIt->second.data() : DefaultPalette[k % 8];
    std::copy_n(rgb, 3, d + 4);
    d[7] = static_cast<float>(this->Opacity(k));
    const bool byDepth = self->ColorMode == ColorModes::LookupTable;
    if (!lut && attribute < 0 && !byDepth)
    {
      d[0] = -1.0f; // its solid colour
      continue;
    }
    double range[2];
    if (attribute >= 0)
      TableRange(lut,
        this->Attributes.GetLayerMin(attribute),
        this->Attributes.GetLayerMax(attribute),
        range);
    else
      TableRange(lut ? lut : this->Lut.Get(), this->ZRange[0], this->ZRange[1], range);
    d[0] = static_cast<float>(colors.size() / 4);
    d[1] = static_cast<float>(attribute);
    d[2] = static_cast<float>(range[0]);
    d[3] = EntriesPerUnit(range);
    AppendTable(lut || attribute >= 0 ? lut : this->Lut.Get(), range, colors);
  }
  return colors;
}

void vtkStackedHeightFieldMapper::vtkInternals::UpdateColors(Self* self,
  vtkOpenGLRenderWindow* renWin,
  Frame& frame)
{
  frame.Shaded = self->OutputMode == OutputModes::Shaded;
  // Translucency with a table over depth: per horizon, the table of each (its opacity there).
  frame.PerHorizon =
    frame.Shaded &&
    (!this->HorizonLuts.empty() ||
      (self->ColorMode == ColorModes::LookupTable && this->AnyTranslucent()) ||
      std::any_of(
        this->AttributeLayer.begin(), this->AttributeLayer.end(), [](int l) { return l >= 0; }));
  frame.LookupTable =
    frame.Shaded && !frame.PerHorizon && self->ColorMode == ColorModes::LookupTable;
  TableRange(this->Lut, this->ZRange[0], this->ZRange[1], frame.LutRange);
  if (!frame.Shaded || this->ColorsCurrent())
    return;
  std::vector<float> colors;
  if (frame.PerHorizon)
  {
    colors = this->PerHorizonColors(self);
  }
  else if (frame.LookupTable)
  {
    AppendTable(this->Lut, frame.LutRange, colors);
    colors.resize(4 * TableEntries); // the flat table has no entry for no data
  }
  else
  {
    for (int k = 0; k < this->Layers; ++k)
    {
      auto it = this->HorizonColors.find(k);
      const double* rgb =
        it != this->HorizonColors.end() ? it->second.data() : DefaultPalette[k % 8];
      colors.insert(
        colors.end(), { float(rgb[0]), float(rgb[1]), float(rgb[2]), float(this->Opacity(k)) });
    }
  }
  this->Buffers.UploadColors(renWin, colors);
  this->ColorTime = std::max(this->ColorsModified.GetMTime(), this->BuildTime);
  if (this->Lut)
    this->ColorTime = std::max(this->ColorTime, this->Lut->GetMTime());
  for (const auto& entry : this->HorizonLuts)
    this->ColorTime = std::max(this->ColorTime, entry.second->GetMTime());
}

// Feedback needs paging, image load/store (GL 4.2 or the ARB extension) and at most 63
// horizons (page ids); without it the pager goes back to screen-space priorities.
bool vtkStackedHeightFieldMapper::vtkInternals::UseFeedback(Self* self)
{
  bool feedback = this->Paged && self->LevelOfDetailFeedback &&
                  this->Layers <= strata::FeedbackReduction::MaxDataSets;
  if (feedback)
  {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 42)
    {
      if (!this->FeedbackUnsupportedWarned)
      {
        vtkWarningWithObjectMacro(self,
          "OpenGL " << major << "." << minor
                    << " has no image load/store: paging without feedback.");
        this->FeedbackUnsupportedWarned = true;
      }
      feedback = false;
    }
  }
  this->FeedbackActive = feedback;
  if (!feedback)
  {
    this->Pager.ClearFeedback();
    this->Feedback.Drop();
  }
  return feedback;
}

// --- The program for exactly this scene's features (the composer's, by key).
vtkShaderProgram* vtkStackedHeightFieldMapper::vtkInternals::ReadyProgram(Self* self,
  vtkOpenGLRenderWindow* renWin,
  vtkOpenGLRenderer* oglRen,
  const Frame& frame)
{
  strata::HeightFieldShaderComposer::Key key;
  key.Paged = this->Paged;
  // A peel redraws the frame's cut: no feedback of its own.
  key.Feedback = frame.Peel ? false : this->UseFeedback(self);
  key.Holes = this->Holes;
  key.Shaded = frame.Shaded;
  key.LookupTable = frame.LookupTable;
  key.PerHorizon = frame.PerHorizon;
  key.Attributes = frame.PerHorizon && !this->Paged && this->Attributes.GetNumberOfLayers() > 0;
  key.Lit = frame.Lit;
  key.LightingComplexity = frame.Lit ? oglRen->GetLightingComplexity() : 0;
  key.LightCount = frame.Lit ? oglRen->GetLightingCount() : 0;
  key.Translucent = frame.Translucent;
  std::string log;
  auto lighting = [oglRen] { return oglRen->GetLightingUniforms(); };
  vtkShaderProgram* program = frame.Compute
                                ? this->Composer.ReadyComputeProgram(renWin, key, lighting, log)
                                : this->Composer.ReadyProgram(renWin, key, lighting);
  if (!program)
  {
    vtkErrorWithObjectMacro(self,
      "The height-field ray casting " << (frame.Compute ? "compute" : "fragment")
                                      << " shader did not compile or link. " << log);
    return nullptr;
  }
  this->LastKey = key;
  this->HasLastKey = true;
  return program;
}

namespace
{
// The region's faces in grid space (inside: dot(n, g) + w <= 0): world plane (n, w) through
// grid -> world g -> A g + b is (A^T n, n . b + w), composed in double.
void SetRegionUniforms(vtkStackedHeightFieldMapper* self,
  vtkMatrix4x4* gridToWorld,
  vtkShaderProgram* program)
{
  double region[6];
  if (!self->GetRegion(region))
  {
    program->SetUniformi("uNumRegionPlanes", 0);
    return;
  }
  float planes[24];
  for (int a = 0; a < 6; ++a)
  {
    const double sign = (a % 2) ? 1.0 : -1.0; // x >= lo or x <= hi
    double n[3] = { 0.0, 0.0, 0.0 };
    n[a / 2] = sign;
    double w = -sign * region[a];
    for (int c = 0; c < 3; ++c)
    {
      double g = 0.0;
      for (int r = 0; r < 3; ++r)
        g += gridToWorld->GetElement(r, c) * n[r];
      planes[4 * a + c] = static_cast<float>(g);
      w += n[c] * gridToWorld->GetElement(c, 3);
    }
    planes[4 * a + 3] = static_cast<float>(w);
  }
  program->SetUniformi("uNumRegionPlanes", 6);
  program->SetUniform4fv("uRegionPlanes", 6, reinterpret_cast<const float(*)[4]>(planes));
}
}

// --- Matrices, composed in double so UTM-scale coordinates lose nothing: the GPU only sees
// grid space (cells and heights) and clip space; then the grid, the search and the tree.
bool vtkStackedHeightFieldMapper::vtkInternals::SetUniforms(Self* self,
  vtkRenderer* ren,
  vtkActor* actor,
  vtkShaderProgram* program,
  Frame& frame)
{
  vtkCamera* camera = ren->GetActiveCamera();
  vtkNew<vtkMatrix4x4> worldToClip, modelGrid;
  worldToClip->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1));
  vtkMatrix4x4::Multiply4x4(actor->GetMatrix(), this->GridToWorld, modelGrid);
  vtkMatrix4x4::Multiply4x4(worldToClip, modelGrid, frame.GridToClip);
  vtkMatrix4x4::Invert(frame.GridToClip, frame.ClipToGrid);
  vtkMatrix4x4::Multiply4x4(camera->GetViewTransformMatrix(), modelGrid, frame.GridToView);
  float m[16];
  strata::RenderUtilities::ToColumnMajor(frame.GridToClip->GetData(), m);
  program->SetUniformMatrix4x4("uGridToClip", m);
  strata::RenderUtilities::ToColumnMajor(frame.ClipToGrid->GetData(), m);
  program->SetUniformMatrix4x4("uClipToGrid", m);
  int* vp = frame.Viewport;
  ren->GetTiledSizeAndOrigin(&vp[2], &vp[3], &vp[0], &vp[1]);
  const float viewport[4] = { float(vp[0]), float(vp[1]), float(vp[2]), float(vp[3]) };
  program->SetUniform4f("uViewport", viewport);
  const float gridMax[2] = { float(this->NX - 1), float(this->NY - 1) };
  program->SetUniform2f("uGridMax", gridMax);
  SetRegionUniforms(self, modelGrid, program);
  const bool range = this->ZRange[0] <= this->ZRange[1];
  const double zr[2] = { range ? this->ZRange[0] : 0.0, range ? this->ZRange[1] : 0.0 };
  const float zRange[2] = { float(zr[0]), float(zr[1]) };
  program->SetUniform2f("uZRange", zRange);
  // Bilinear interpolation in float is within a few ulps of the corner range; 1e-5 relative
  // of the largest magnitude is far above that and far below anything visible.
  program->SetUniformf("uZEps", float(1e-5 * std::max({ 1.0, std::abs(zr[0]), std::abs(zr[1]) })));
  program->SetUniformf("uStep", float(self->LinearSearchStep));
  // Ties: hits closer than 1e-6 of the near-to-far segment (t spans [0, 1]) are one hit.
  program->SetUniformf("uTieEps", 1e-6f);
  const strata::MinMaxQuadtree& tree = this->Paged ? this->Pager.GetTree() : this->Tree;
  program->SetUniformi("uTileSize", tree.GetTileSize());
  const int levels = tree.GetNumberOfLevels();
  if (levels > 16)
  {
    vtkErrorWithObjectMacro(self, "Quadtree of " << levels << " levels: raise TileSize.");
    return false;
  }
  program->SetUniformi("uNumLevels", levels);
  int offsets[16] = { 0 };
  int levelDims[32] = { 0 };
  for (int l = 0; l < levels; ++l)
  {
    offsets[l] = tree.GetLevelOffset(l);
    levelDims[2 * l] = tree.GetLevelNX(l);
    levelDims[2 * l + 1] = tree.GetLevelNY(l);
  }
  program->SetUniform1iv("uLevelOffset", 16, offsets);
  glUniform2iv(program->FindUniform("uLevelDims"), 16, levelDims);
  return true;
}

// The actor's material and the renderer's lights, in view coordinates.
void vtkStackedHeightFieldMapper::vtkInternals::SetLightingUniforms(vtkOpenGLRenderer* ren,
  vtkActor* actor,
  vtkShaderProgram* program,
  const Frame& frame)
{
  vtkNew<vtkMatrix3x3> normal;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      normal->SetElement(r, c, frame.GridToView->GetElement(r, c));
  normal->Invert();
  normal->Transpose();
  float n9[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      n9[c * 3 + r] = static_cast<float>(normal->GetElement(r, c));
  program->SetUniformMatrix3x3("uNormalMatrix", n9);
  float m[16];
  strata::RenderUtilities::ToColumnMajor(frame.GridToView->GetData(), m);
  program->SetUniformMatrix4x4("uGridToView", m);
  program->SetUniformi("uParallel", ren->GetActiveCamera()->GetParallelProjection() ? 1 : 0);
  vtkProperty* prop = actor->GetProperty();
  program->SetUniformf("uAmbient", float(prop->GetAmbient()));
  program->SetUniformf("uDiffuse", float(prop->GetDiffuse()));
  program->SetUniformf("uSpecular", float(prop->GetSpecular()));
  program->SetUniformf("uSpecularPower", float(prop->GetSpecularPower()));
  const double* sc = prop->GetSpecularColor();
  const float specColor[3] = { float(sc[0]), float(sc[1]), float(sc[2]) };
  program->SetUniform3f("uSpecularColor", specColor);
  ren->UpdateLightingUniforms(program);
}

// --- Feedback: the buffer cleared, on image unit 0, and what the rays need to name a tile;
// the lattice phase cycles so that every pixel asks once per FeedbackScale^2 frames.
void vtkStackedHeightFieldMapper::vtkInternals::PrepareFeedback(Self* self,
  vtkOpenGLRenderWindow* renWin,
  vtkShaderProgram* program,
  const Frame& frame)
{
  const int s = self->FeedbackScale;
  this->Feedback.Allocate(renWin, frame.Viewport[2], frame.Viewport[3], s);
  this->Feedback.Clear(renWin);
  this->Feedback.BindImages(false);
  program->SetUniformi("uFeedback", 0);
  program->SetUniformi("uFeedbackScale", s);
  const int phase = static_cast<int>(this->FeedbackFrame % (s * s));
  glUniform2i(program->FindUniform("uFeedbackOffset"), phase % s, phase / s);
  program->SetUniformf("uLodScale", float(self->LevelOfDetailThreshold));
  const int levelsPaged =
    std::min(this->Pager.GetNumberOfLevels(), strata::FeedbackReduction::MaxLevels);
  program->SetUniformi("uPageLevels", levelsPaged);
  int tilesX[32] = { 0 };
  for (int l = 0; l < levelsPaged; ++l)
    tilesX[l] = this->Pager.GetLevelTiles(l)[0];
  program->SetUniform1iv("uLevelTilesX", 32, tilesX);
}

// --- The box's back faces, depth-clamped so far-plane clipping cannot cut rays short.
void vtkStackedHeightFieldMapper::vtkInternals::Draw(vtkOpenGLRenderWindow* renWin,
  vtkShaderProgram* program,
  bool writeDepth)
{
  vtkOpenGLState* state = renWin->GetState();
  this->Buffers.BindBox(program);
  vtkOpenGLState::ScopedglEnableDisable cullSaver(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  state->vtkglEnable(GL_CULL_FACE);
  state->vtkglCullFace(GL_FRONT);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthMask(writeDepth ? GL_TRUE : GL_FALSE);
  {
    const strata::RenderUtilities::ScopedEnable depthClamp(GL_DEPTH_CLAMP);
    this->Buffers.DrawBox();
  }
  state->vtkglCullFace(GL_BACK); // VTK's default; its actors set their own
}

// The queued feedback, mapped and reduced, handed to the pager (a (tile, pixels) list).
void vtkStackedHeightFieldMapper::vtkInternals::ReadFeedback(Self* self)
{
  const bool viewChanged = this->PendingViewChanged;
  // Timed from here: mapping, reduction and handing over (the copy was queued after the draw).
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<strata::FeedbackReduction::Entry> list;
  this->Feedback.SetUseOpenCL(self->FeedbackOpenCL);
  this->Feedback.Read(list);
  std::vector<uint32_t> pages(list.size()), coverage(list.size());
  for (size_t e = 0; e < list.size(); ++e)
  {
    pages[e] = list[e].Page;
    coverage[e] = list[e].Coverage;
  }
  this->Pager.SetFeedback(pages, coverage, self->FeedbackScale * self->FeedbackScale, viewChanged);
  ++this->FeedbackFrame;
  this->Paging.FeedbackMilliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  this->Paging.FeedbackOpenCL = this->Feedback.GetLastReadUsedOpenCL();
}

// --- Which horizons this call draws: all (every one opaque); the opaque ones (the renderer's
// opaque pass, rays passing through the translucent); inside a peel of the volume ray caster's
// surface layers, one layer of the translucent ones; or, in the renderer's translucent pass of
// an actor no ray caster peels, the translucent ones blended front to back.
bool vtkStackedHeightFieldMapper::vtkInternals::ChooseTranslucency(Self* self,
  vtkActor* actor,
  Frame& frame)
{
  using Translucency = strata::HeightFieldShaderComposer::Translucency;
  const bool translucent = self->OutputMode == OutputModes::Shaded && this->AnyTranslucent();
  vtkVolumeSurfacePeelPass* peel = vtkVolumeSurfacePeelPass::Find(actor);
  if (peel && peel->Active)
  {
    frame.Peel = peel;
    frame.Translucent = Translucency::Layer;
    return translucent;
  }
  if (actor->IsRenderingTranslucentPolygonalGeometry())
  {
    // Attached to a ray caster's peel: it composites them among its volumes. Else VTK's
    // order-independent pass (vtkOpenGLRenderer's without depth peeling) takes the stack's
    // translucent hits composited as one fragment; its depth peeling passes are not supported.
    if (!translucent || peel)
      return false;
    if (!strata::RenderUtilities::FindRenderPass<vtkOrderIndependentTranslucentPass>(actor))
    {
      if (!this->UnsupportedTranslucentWarned)
        vtkWarningWithObjectMacro(self,
          "Translucent horizons are drawn by the renderer's order-independent translucent pass "
          "(UseDepthPeeling off) or by a vtkMultiVolumeRayCastMapper (AddTranslucentActor): "
          "not drawn.");
      this->UnsupportedTranslucentWarned = true;
      return false;
    }
    frame.Translucent = Translucency::Blend;
    return true;
  }
  frame.Translucent = translucent ? Translucency::Skip : Translucency::None;
  return !translucent || this->AnyOpaque();
}

// --- A peel: its framebuffer is the viewport's size from (0, 0); the scene's and the last
// layer's depths (activated by the peel), the horizons the merge looks through.
void vtkStackedHeightFieldMapper::vtkInternals::SetPeelUniforms(vtkShaderProgram* program,
  const Frame& frame) const
{
  if (frame.Translucent == strata::HeightFieldShaderComposer::Translucency::Blend)
    program->SetUniformi("uNumHorizons", this->Layers);
  if (!frame.Peel)
    return;
  const float viewport[4] = { 0.0f, 0.0f, float(frame.Viewport[2]), float(frame.Viewport[3]) };
  program->SetUniform4f("uViewport", viewport);
  program->SetUniformi("uPeelScene", frame.Peel->Scene->GetTextureUnit());
  program->SetUniformi("uPeelPrevious", frame.Peel->Previous->GetTextureUnit());
  program->SetUniformi("uPeelLayer", frame.Peel->Layer);
  program->SetUniformi("uNumHorizons", this->Layers);
}

// The heights (the tile atlas when paged, else the height array), normals and attributes on
// their units for this frame's program, and the colour table's range.
void vtkStackedHeightFieldMapper::vtkInternals::BindData(vtkOpenGLRenderWindow* renWin,
  vtkShaderProgram* program,
  const Frame& frame)
{
  vtkTextureUnitManager* units = renWin->GetTextureUnitManager();
  if (this->Paged)
  {
    this->Atlas.Bind(renWin, program, this->Pager);
  }
  else
  {
    this->HeightUnit = units->Allocate();
    renWin->GetState()->vtkglActiveTexture(GL_TEXTURE0 + this->HeightUnit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, this->Buffers.GetHeightTexture());
    program->SetUniformi("uHeights", this->HeightUnit);
  }
  this->Buffers.Activate(program, frame.Shaded);
  if (this->LastKey.Attributes)
  {
    this->AttributeUnit = units->Allocate();
    renWin->GetState()->vtkglActiveTexture(GL_TEXTURE0 + this->AttributeUnit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, this->Buffers.GetAttributeTexture());
    program->SetUniformi("uAttributes", this->AttributeUnit);
  }
  if (frame.LookupTable)
  {
    const float lr[2] = { float(frame.LutRange[0]), EntriesPerUnit(frame.LutRange) };
    program->SetUniform2f("uLutRange", lr);
  }
}

void vtkStackedHeightFieldMapper::vtkInternals::UnbindData(vtkOpenGLRenderWindow* renWin,
  const Frame& frame)
{
  vtkTextureUnitManager* units = renWin->GetTextureUnitManager();
  this->Buffers.Deactivate(frame.Shaded);
  for (int* unit : { &this->AttributeUnit, &this->HeightUnit })
  {
    if (*unit < 0)
      continue;
    renWin->GetState()->vtkglActiveTexture(GL_TEXTURE0 + *unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    units->Free(*unit);
    *unit = -1;
  }
  if (this->Paged)
  {
    this->Atlas.Unbind(renWin);
  }
}

// The frame's feedback image copied into the pixel buffer now; mapped at once, or at the next
// frame when the read-back is deferred (ReadFeedback).
void vtkStackedHeightFieldMapper::vtkInternals::QueueFeedback(Self* self,
  vtkOpenGLRenderWindow* renWin,
  const Frame& frame)
{
  this->Feedback.UnbindImages();
  std::array<double, 16> view;
  std::copy_n(frame.GridToClip->GetData(), 16, view.begin());
  this->Feedback.Queue(renWin);
  this->PendingViewChanged = view != this->LastView;
  this->LastView = view;
  if (!self->DeferFeedbackReadBack)
  {
    this->ReadFeedback(self);
  }
}

void vtkStackedHeightFieldMapper::ReleaseGraphicsResources(vtkWindow* win)
{
  vtkInternals& in = *this->Internals;
  in.Buffers.ReleaseGraphicsResources(win);
  in.Atlas.ReleaseGraphicsResources();
  in.Feedback.ReleaseGraphicsResources();
  in.Composer.ReleaseGraphicsResources();
  in.Staging.ReleaseGraphicsResources(win);
  in.UploadTime = 0;
  in.ColorTime = 0;
  this->Superclass::ReleaseGraphicsResources(win);
}

// One frame: the stack and colours on the GPU, the program for the scene's features, its
// uniforms and textures, the box drawn, and the feedback read or queued.
void vtkStackedHeightFieldMapper::Render(vtkRenderer* ren, vtkActor* actor)
{
  vtkInternals& in = *this->Internals;
  if (!this->UpdateStack() || in.Layers == 0)
  {
    return;
  }
  auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  auto* oglRen = vtkOpenGLRenderer::SafeDownCast(ren);
  if (!renWin || !oglRen)
  {
    vtkErrorMacro("vtkStackedHeightFieldMapper needs an OpenGL render window.");
    return;
  }
  vtkInternals::Frame frame;
  if (!in.ChooseTranslucency(this, actor, frame))
  {
    return;
  }
  in.GraphicsResources.Register(renWin);
  vtkOpenGLClearErrorMacro();
  if (!in.Upload(this, ren, actor, renWin, frame.Peel == nullptr))
  {
    return;
  }
  in.UpdateColors(this, renWin, frame);
  frame.Lit =
    frame.Shaded && actor->GetProperty()->GetLighting() && oglRen->GetLightingComplexity() > 0;
  in.ChooseStage(this, renWin, frame);
  vtkShaderProgram* program = in.ReadyProgram(this, renWin, oglRen, frame);
  if (!program || !in.SetUniforms(this, ren, actor, program, frame))
  {
    return;
  }
  if (frame.Lit)
  {
    in.SetLightingUniforms(oglRen, actor, program, frame);
  }
  in.SetPeelUniforms(program, frame);
  in.BindData(renWin, program, frame);
  if (in.LastKey.Feedback)
  {
    in.PrepareFeedback(this, renWin, program, frame);
  }
  const bool writeDepth =
    frame.Translucent != strata::HeightFieldShaderComposer::Translucency::Blend;
  if (frame.Compute)
    in.DrawCompute(renWin, program, frame, writeDepth);
  else
    in.Draw(renWin, program, writeDepth);
  in.UnbindData(renWin, frame);
  if (in.LastKey.Feedback)
  {
    in.QueueFeedback(this, renWin, frame);
  }
  vtkOpenGLCheckErrorMacro("failed after rendering the height-field stack");
}

void vtkStackedHeightFieldMapper::SetRegion(const double bounds[6])
{
  if (this->Region.Set(bounds))
    this->Modified();
}

void vtkStackedHeightFieldMapper::RemoveRegion()
{
  if (this->Region.Remove())
    this->Modified();
}

bool vtkStackedHeightFieldMapper::GetRegion(double bounds[6]) const
{
  return this->Region.Get(bounds);
}

void vtkStackedHeightFieldMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Region: ";
  this->Region.Print(os);
  os << "\n";
  os << indent << "TileSize: " << this->TileSize << "\n";
  os << indent << "LinearSearchStep: " << this->LinearSearchStep << "\n";
  os << indent << "Stage: " << strata::ComputeStage::StageName(static_cast<int>(this->Stage))
     << " (last frame: " << this->GetStageInUseAsString() << ")\n";
  os << indent << "HeightScale: " << this->HeightScale << "\n";
  os << indent << "NullValue: " << this->NullValue << "\n";
  os << indent << "UseNullValue: " << this->UseNullValue << "\n";
  os << indent << "HeightArrayName: " << this->HeightArrayName << "\n";
  os << indent << "ColorMode: " << static_cast<int>(this->ColorMode) << "\n";
  os << indent << "OutputMode: " << static_cast<int>(this->OutputMode) << "\n";
  os << indent << "LevelOfDetailFeedback: " << this->LevelOfDetailFeedback << ", scale "
     << this->FeedbackScale << ", deferred read-back " << this->DeferFeedbackReadBack << "\n";
  os << indent << "LevelOfDetailThreshold: " << this->LevelOfDetailThreshold << "\n";
  os << indent << "PageCacheBudget: " << this->PageCacheBudget
     << ", AtlasBudget: " << this->AtlasBudget << ", PagesPerFrame: " << this->PagesPerFrame
     << ", Prefetch: " << this->Prefetch << ", MorphFrames: " << this->MorphFrames << "\n";
  os << indent << "Horizons: " << this->Internals->Stack.GetNumberOfLayers() << "\n";
}
