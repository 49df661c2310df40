// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStackedHeightFieldMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFeedbackReadBack.h"
#include "vtkFeedbackReduction.h"
#include "vtkFloatArray.h"
#include "vtkHeightFieldPager.h"
#include "vtkHeightFieldStack.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkInformationStringKey.h"
#include "vtkInformationVector.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkMinMaxQuadtree.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkStrataRenderUtilities.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtkVolumeCut.h"
#include "vtk_glew.h"

#include "vtkStackedHeightFieldFS.h"
#include "vtkStackedHeightFieldPagedLookup.h"
#include "vtkStackedHeightFieldVS.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
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

// The feedback write (paged horizons): one pixel per FeedbackScale^2 lattice cell asks for the
// tile its hit lies in, at the level whose cells cover about uLodScale pixels' worth of the
// pixel's footprint (one pixel unprojected at the hit's depth, in level-0 cells).
const char* FeedbackDeclarations = R"(layout(r32ui) uniform uimage2D uFeedback;
uniform int uFeedbackScale;
uniform ivec2 uFeedbackOffset;
uniform float uLodScale;
uniform int uPageLevels;
uniform int uLevelTilesX[32];
)";
const char* FeedbackWrite =
  R"(if (all(equal(ivec2(gl_FragCoord.xy) % uFeedbackScale, uFeedbackOffset)))
  {
    vec3 n0 = clip.xyz / clip.w;
    vec4 gx = uClipToGrid * vec4(n0 + vec3(2.0 / uViewport.z, 0.0, 0.0), 1.0);
    vec4 gy = uClipToGrid * vec4(n0 + vec3(0.0, 2.0 / uViewport.w, 0.0), 1.0);
    float footprint = max(length(gx.xy / gx.w - pGrid.xy), length(gy.xy / gy.w - pGrid.xy)) * uLodScale;
    int want = footprint >= 2.0 ? min(int(floor(log2(footprint))), uPageLevels - 1) : 0;
    ivec2 tile = min(max(ivec2(floor(pGrid.xy)), ivec2(0)) / uPageStride, uPageTiles - 1) >> want;
    uint id = strataPackPage(uint(hitLayer), uint(want), uint(tile.y * uLevelTilesX[want] + tile.x));
    imageStore(uFeedback, ivec2(gl_FragCoord.xy) / uFeedbackScale, uvec4(id, 0u, 0u, 0u));
  })";

void Replace(std::string& source, const std::string& tag, const std::string& code)
{
  vtkShaderProgram::Substitute(source, tag, code, true);
}

void ToFloat(vtkMatrix4x4* m, float out[16], bool transpose)
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[transpose ? c * 4 + r : r * 4 + c] = static_cast<float>(m->GetElement(r, c));
    }
  }
}
}

class vtkStackedHeightFieldMapper::vtkInternals
{
public:
  // CPU side
  vtkHeightFieldStack Stack;
  vtkMinMaxQuadtree Tree;
  std::vector<vtkSmartPointer<vtkDataArray>> Arrays; // keep borrowed layers alive
  vtkNew<vtkMatrix4x4> GridToWorld;
  vtkMTimeType BuildTime = 0;
  bool Valid = false;
  double Bounds[6] = { 0, -1, 0, -1, 0, -1 };
  std::map<int, std::array<double, 3>> HorizonColors;
  vtkSmartPointer<vtkScalarsToColors> Lut;
  // What the renderer draws, in core or paged: grid size, horizons, value range, holes.
  int NX = 0, NY = 0, Layers = 0;
  double ZRange[2] = { 0.0, -1.0 };
  bool Holes = false;

  // Paging (tile pools behind the inputs): the pager, the readers' coarsest levels as roots,
  // the tile atlas and page table on the GPU.
  bool Paged = false;
  vtkHeightFieldPager Pager;
  vtkFeedbackReduction Reduction; ///< this mapper's (OpenCL set up on first use)
  std::vector<std::vector<float>> RootValues;
  unsigned int AtlasTexture = 0;
  unsigned int PageTableTexture = 0;
  int AtlasSlots = 0;
  // Level-of-detail feedback: the buffer, the lattice phase and the view it was written from.
  unsigned int FeedbackTexture = 0;
  unsigned int FeedbackBuffer = 0; ///< pixel buffer the texture is copied into after a frame
  bool FeedbackPending = false;    ///< the buffer holds a frame not read yet
  bool PendingViewChanged = false; ///< that frame's view differed from the one before
  int FeedbackSize[2] = { 0, 0 };
  int64_t FeedbackFrame = 0;
  bool FeedbackActive = false; ///< this frame's shader writes the buffer
  bool FeedbackUnsupportedWarned = false;
  std::array<double, 16> LastView{};
  vtkStackedHeightFieldMapper::PagingStatistics Paging;
  bool TreeDirty = true;

  // GPU side
  unsigned int HeightTexture = 0;
  vtkNew<vtkOpenGLBufferObject> NodeBuffer, IntervalBuffer, LayerListBuffer, ColorBuffer;
  vtkNew<vtkTextureObject> NodeTexture, IntervalTexture, LayerListTexture, ColorTexture;
  vtkNew<vtkOpenGLBufferObject> BoxVertices, BoxIndices;
  unsigned int VAO = 0;
  vtkShaderProgram* LastProgram = nullptr;
  vtkMTimeType UploadTime = 0;
  vtkMTimeType ColorTime = 0;
  std::string FragmentSource;
  std::string VertexSource;
  vtkTimeStamp ColorsModified;
};

vtkStackedHeightFieldMapper::vtkStackedHeightFieldMapper()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(1);
  this->Static = 0;
  this->Internals->ColorsModified.Modified();
  for (auto* bo : { this->Internals->NodeBuffer.Get(),
         this->Internals->IntervalBuffer.Get(),
         this->Internals->LayerListBuffer.Get(),
         this->Internals->ColorBuffer.Get() })
  {
    bo->SetType(vtkOpenGLBufferObject::TextureBuffer);
  }
  this->Internals->BoxIndices->SetType(vtkOpenGLBufferObject::ElementArrayBuffer);
}

vtkStackedHeightFieldMapper::~vtkStackedHeightFieldMapper() = default;

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

void vtkStackedHeightFieldMapper::SetHeightLookupTable(vtkScalarsToColors* lut)
{
  this->Internals->Lut = lut;
  this->Internals->ColorsModified.Modified();
  this->Modified();
}

std::string vtkStackedHeightFieldMapper::GetFragmentShaderSource() const
{
  return this->Internals->FragmentSource;
}

void vtkStackedHeightFieldMapper::GetGridToWorld(double m[16])
{
  this->UpdateStack();
  vtkMatrix4x4::DeepCopy(m, this->Internals->GridToWorld);
}

const vtkHeightFieldStack* vtkStackedHeightFieldMapper::GetStack()
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
    vtkInformation* info = this->GetInputInformation(0, i);
    pooled += info && info->Has(vtkPagePoolReader::POOL_FILE_NAME()) ? 1 : 0;
  }
  if (pooled > 0 && pooled < n)
  {
    vtkErrorMacro(<< pooled << " of " << n
                  << " horizons come from page pools: page all horizons of a stack or none.");
    return false;
  }
  in.Paged = pooled > 0;
  if (in.Paged)
  {
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
    vtkPagePoolReader::RequestCoarsestLevel(this->GetInputInformation(0, i));
  }
}

vtkTypeBool vtkStackedHeightFieldMapper::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const vtkTypeBool result = this->Superclass::ProcessRequest(request, inputVector, outputVector);
  // Whatever updates the inputs (GetBounds, the render), a pool's reader serves its coarsest
  // level only.
  vtkPagePoolReader::RequestCoarsestLevels(request, inputVector, 1);
  return result;
}

bool vtkStackedHeightFieldMapper::UpdatePagedStack(const std::vector<vtkImageData*>& images)
{
  vtkInternals& in = *this->Internals;
  std::vector<vtkHeightFieldPager::Source> sources(images.size());
  in.RootValues.resize(images.size());
  for (size_t i = 0; i < images.size(); ++i)
  {
    vtkInformation* info = this->GetInputInformation(0, static_cast<int>(i));
    sources[i].FileName = info->Get(vtkPagePoolReader::POOL_FILE_NAME());
    sources[i].Layer =
      info->Has(vtkPagePoolReader::POOL_LAYER()) ? info->Get(vtkPagePoolReader::POOL_LAYER()) : 0;
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

bool vtkStackedHeightFieldMapper::UpdatePages(vtkRenderer* ren, vtkActor* actor)
{
  vtkInternals& in = *this->Internals;
  const int B = in.Pager.GetPageSize();
  // The atlas: as many B x B float tiles as the budget holds, within the GPU's layer limit.
  GLint maxLayers = 0, maxSize = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  const double tileBytes = double(B) * B * sizeof(float);
  const int slots = static_cast<int>(
    std::min<double>(maxLayers, std::floor(this->AtlasBudget * 1048576.0 / tileBytes)));
  if (slots < 1 || B > maxSize)
  {
    vtkErrorMacro("An atlas of " << this->AtlasBudget << " MiB holds no tile of " << B << " x " << B
                                 << " heights: raise AtlasBudget.");
    return false;
  }
  if (slots != in.AtlasSlots || !in.AtlasTexture)
  {
    if (!in.AtlasTexture)
    {
      glGenTextures(1, &in.AtlasTexture);
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, in.AtlasTexture);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R32F, B, B, slots, 0, GL_RED, GL_FLOAT, nullptr);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    if (glGetError() != GL_NO_ERROR)
    {
      vtkErrorMacro("Could not allocate a tile atlas of "
                    << slots << " tiles of " << B << " x " << B
                    << " (out of GPU memory?): lower AtlasBudget.");
      return false;
    }
    in.AtlasSlots = slots;
    in.Pager.SetAtlasSlots(slots);
    in.Pager.InvalidateAtlas();
  }
  in.Pager.SetCacheBudgetMiB(this->PageCacheBudget);
  in.Pager.SetPagesPerFrame(this->PagesPerFrame);
  in.Pager.SetPrefetch(this->Prefetch);
  in.Pager.SetMorphFrames(this->MorphFrames);

  // The last frame's feedback when its read-back was deferred (DeferFeedbackReadBack).
  if (in.FeedbackPending)
  {
    this->ReadFeedback();
  }
  // The cut refines by the size of a tile's points on screen, under this camera.
  const vtkVolumeCut::Camera cutCamera = vtkStrataRenderUtilities::GetCutCamera(ren);
  vtkNew<vtkMatrix4x4> modelGrid;
  vtkMatrix4x4::Multiply4x4(actor->GetMatrix(), in.GridToWorld, modelGrid);
  std::vector<vtkHeightFieldPager::Upload> uploads;
  const bool changed = in.Pager.Update(cutCamera, modelGrid->GetData(), uploads);

  in.Paging.BytesUploaded = 0;
  if (!uploads.empty())
  {
    std::vector<float> values;
    glBindTexture(GL_TEXTURE_2D_ARRAY, in.AtlasTexture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (const auto& u : uploads)
    {
      in.Pager.GetUploadValues(u, values);
      glTexSubImage3D(
        GL_TEXTURE_2D_ARRAY, 0, 0, 0, u.Slot, B, B, 1, GL_RED, GL_FLOAT, values.data());
      in.Paging.BytesUploaded += static_cast<long long>(values.size() * sizeof(float));
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  }
  // Borders stitched anew to coarser neighbours: two columns and two rows per page.
  if (!in.Pager.GetBorderUploads().empty())
  {
    std::vector<float> border;
    glBindTexture(GL_TEXTURE_2D_ARRAY, in.AtlasTexture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (const auto& u : in.Pager.GetBorderUploads())
    {
      if (u.Slot < 0)
        continue;
      in.Pager.GetBorderValues(u, border);
      glTexSubImage3D(
        GL_TEXTURE_2D_ARRAY, 0, 0, 0, u.Slot, 1, B, 1, GL_RED, GL_FLOAT, border.data());
      glTexSubImage3D(
        GL_TEXTURE_2D_ARRAY, 0, B - 1, 0, u.Slot, 1, B, 1, GL_RED, GL_FLOAT, border.data() + B);
      glTexSubImage3D(
        GL_TEXTURE_2D_ARRAY, 0, 0, 0, u.Slot, B, 1, 1, GL_RED, GL_FLOAT, border.data() + 2 * B);
      glTexSubImage3D(
        GL_TEXTURE_2D_ARRAY, 0, 0, B - 1, u.Slot, B, 1, 1, GL_RED, GL_FLOAT, border.data() + 3 * B);
      in.Paging.BytesUploaded += static_cast<long long>(border.size() * sizeof(float));
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  }
  if (changed || !in.PageTableTexture)
  {
    const std::vector<uint16_t>& table = in.Pager.GetPageTable();
    const int* tiles = in.Pager.GetTiles();
    if (!in.PageTableTexture)
    {
      glGenTextures(1, &in.PageTableTexture);
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, in.PageTableTexture);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glTexImage3D(GL_TEXTURE_2D_ARRAY,
      0,
      GL_RGBA16UI,
      tiles[0],
      tiles[1],
      in.Layers,
      0,
      GL_RGBA_INTEGER,
      GL_UNSIGNED_SHORT,
      table.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    in.TreeDirty = true;
  }
  for (const std::string& failure : in.Pager.TakeNewFailures())
  {
    vtkErrorMacro("Could not load " << failure << "; showing the coarser level.");
  }
  static_cast<vtkHeightFieldPager::Statistics&>(in.Paging) = in.Pager.GetStatistics();
  in.Paging.Paged = true;
  in.Paging.AtlasSlots = in.AtlasSlots;
  in.Paging.FeedbackUsed = in.FeedbackActive;
  return true;
}

vtkStackedHeightFieldMapper::PagingStatistics vtkStackedHeightFieldMapper::GetPagingStatistics()
  const
{
  return this->Internals->Paging;
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

const vtkHeightFieldPager* vtkStackedHeightFieldMapper::GetPager() const
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

void vtkStackedHeightFieldMapper::ReleaseGraphicsResources(vtkWindow* win)
{
  vtkInternals& in = *this->Internals;
  for (unsigned int* texture :
    { &in.HeightTexture, &in.AtlasTexture, &in.PageTableTexture, &in.FeedbackTexture })
  {
    if (*texture)
    {
      glDeleteTextures(1, texture);
      *texture = 0;
    }
  }
  if (in.FeedbackBuffer)
  {
    glDeleteBuffers(1, &in.FeedbackBuffer);
    in.FeedbackBuffer = 0;
  }
  in.FeedbackPending = false;
  in.AtlasSlots = 0;
  in.FeedbackSize[0] = in.FeedbackSize[1] = 0;
  for (auto* t : { in.NodeTexture.Get(),
         in.IntervalTexture.Get(),
         in.LayerListTexture.Get(),
         in.ColorTexture.Get() })
  {
    t->ReleaseGraphicsResources(win);
  }
  for (auto* b : { in.NodeBuffer.Get(),
         in.IntervalBuffer.Get(),
         in.LayerListBuffer.Get(),
         in.ColorBuffer.Get(),
         in.BoxVertices.Get(),
         in.BoxIndices.Get() })
  {
    b->ReleaseGraphicsResources();
  }
  if (in.VAO)
  {
    glDeleteVertexArrays(1, &in.VAO);
    in.VAO = 0;
  }
  in.LastProgram = nullptr;
  in.UploadTime = 0;
  in.ColorTime = 0;
  this->Modified();
}

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
  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLClearErrorMacro();
  const int nx = in.NX;
  const int ny = in.NY;
  const int layers = in.Layers;

  auto uploadBuffer =
    [&](vtkOpenGLBufferObject* bo, vtkTextureObject* tex, const std::vector<float>& data, int comps)
  {
    tex->SetContext(renWin);
    bo->Upload(data, vtkOpenGLBufferObject::TextureBuffer);
    tex->CreateTextureBuffer(static_cast<unsigned int>(data.size() / comps), comps, VTK_FLOAT, bo);
  };
  auto uploadTree = [&](const vtkMinMaxQuadtree& tree)
  {
    // Ints stored as floats are exact below 2^24, far above any tree built here.
    std::vector<float> nodes, intervals, lists;
    for (const auto& node : tree.GetNodes())
    {
      nodes.insert(
        nodes.end(), { node.Min, node.Max, float(node.IntervalOffset), float(node.IntervalCount) });
    }
    for (const auto& iv : tree.GetIntervals())
    {
      intervals.insert(
        intervals.end(), { iv.ZMin, iv.ZMax, float(iv.LayerOffset), float(iv.LayerCount) });
    }
    for (int id : tree.GetLayerLists())
    {
      lists.push_back(float(id));
    }
    if (intervals.empty())
    {
      intervals.assign(4, 0.0f);
    }
    if (lists.empty())
    {
      lists.assign(1, 0.0f);
    }
    uploadBuffer(in.NodeBuffer, in.NodeTexture, nodes, 4);
    uploadBuffer(in.IntervalBuffer, in.IntervalTexture, intervals, 4);
    uploadBuffer(in.LayerListBuffer, in.LayerListTexture, lists, 1);
  };
  auto uploadBox = [&]()
  {
    // Proxy box, slightly taller than the data so that flat stacks still have back faces.
    double zr[2] = { in.ZRange[0], in.ZRange[1] };
    if (zr[0] > zr[1])
    {
      zr[0] = zr[1] = 0.0;
    }
    const double pad = std::max(1e-3, 1e-3 * (zr[1] - zr[0]));
    const float x1 = float(nx - 1), y1 = float(ny - 1);
    const float z0 = float(zr[0] - pad), z1 = float(zr[1] + pad);
    const std::vector<float> verts = {
      0, 0, z0, x1, 0, z0, 0, y1, z0, x1, y1, z0, 0, 0, z1, x1, 0, z1, 0, y1, z1, x1, y1, z1
    };
    const std::vector<unsigned int> faces = { 0,
      2,
      1,
      1,
      2,
      3,
      4,
      5,
      6,
      5,
      7,
      6,
      0,
      1,
      4,
      1,
      5,
      4,
      2,
      6,
      3,
      3,
      6,
      7,
      0,
      4,
      2,
      2,
      4,
      6,
      1,
      3,
      5,
      3,
      7,
      5 };
    in.BoxVertices->Upload(verts, vtkOpenGLBufferObject::ArrayBuffer);
    in.BoxIndices->Upload(faces, vtkOpenGLBufferObject::ElementArrayBuffer);
    in.LastProgram = nullptr; // attribute bindings must be redone
  };

  if (in.Paged)
  {
    if (!this->UpdatePages(ren, actor))
    {
      return;
    }
    if (in.UploadTime < in.BuildTime)
    {
      uploadBox();
      in.UploadTime = in.BuildTime;
    }
    if (in.TreeDirty)
    {
      uploadTree(in.Pager.GetTree());
      in.TreeDirty = false;
    }
  }
  // --- Upload the stack and the tree when they changed.
  else if (in.UploadTime < in.BuildTime || !in.HeightTexture)
  {
    GLint maxSize = 0, maxLayers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    if (nx > maxSize || ny > maxSize || layers > maxLayers)
    {
      vtkErrorMacro("A grid of " << nx << " x " << ny << " x " << layers
                                 << " horizons exceeds this GPU's texture limits (" << maxSize
                                 << " per side, " << maxLayers
                                 << " layers); page it from a tile pool instead.");
      return;
    }
    if (!in.HeightTexture)
    {
      glGenTextures(1, &in.HeightTexture);
    }
    state->vtkglActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, in.HeightTexture);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R32F, nx, ny, layers, 0, GL_RED, GL_FLOAT, nullptr);
    for (int k = 0; k < layers; ++k)
    {
      glTexSubImage3D(
        GL_TEXTURE_2D_ARRAY, 0, 0, 0, k, nx, ny, 1, GL_RED, GL_FLOAT, in.Stack.GetLayer(k));
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    if (glGetError() != GL_NO_ERROR)
    {
      vtkErrorMacro("Could not upload " << layers << " horizons of " << nx << " x " << ny
                                        << " heights (out of GPU memory?).");
      return;
    }

    uploadTree(in.Tree);
    uploadBox();
    in.UploadTime = in.BuildTime;
  }
  const vtkMinMaxQuadtree& tree = in.Paged ? in.Pager.GetTree() : in.Tree;

  // --- Colours: per-horizon table or lookup table over height.
  const bool shaded = this->OutputMode == OutputModes::Shaded;
  const bool useLut = shaded && this->ColorMode == ColorModes::LookupTable;
  double lutRange[2] = { in.ZRange[0], in.ZRange[1] };
  if (in.Lut && useLut)
  {
    const double* r = in.Lut->GetRange();
    if (r[0] < r[1])
    {
      lutRange[0] = r[0];
      lutRange[1] = r[1];
    }
  }
  if (lutRange[1] <= lutRange[0])
  {
    lutRange[1] = lutRange[0] + 1.0;
  }
  if (shaded && (in.ColorTime < in.ColorsModified.GetMTime() || in.ColorTime < in.BuildTime ||
                  (in.Lut && in.ColorTime < in.Lut->GetMTime())))
  {
    std::vector<float> colors;
    if (useLut)
    {
      const int entries = 1024;
      for (int e = 0; e < entries; ++e)
      {
        const double s = (e + 0.5) / entries;
        double rgb[3];
        if (in.Lut)
        {
          in.Lut->GetColor(lutRange[0] + s * (lutRange[1] - lutRange[0]), rgb);
        }
        else
        {
          DefaultDepthColor(s, rgb);
        }
        colors.insert(colors.end(), { float(rgb[0]), float(rgb[1]), float(rgb[2]), 1.0f });
      }
    }
    else
    {
      for (int k = 0; k < layers; ++k)
      {
        auto it = in.HorizonColors.find(k);
        const double* rgb =
          it != in.HorizonColors.end() ? it->second.data() : DefaultPalette[k % 8];
        colors.insert(colors.end(), { float(rgb[0]), float(rgb[1]), float(rgb[2]), 1.0f });
      }
    }
    in.ColorTexture->SetContext(renWin);
    in.ColorBuffer->Upload(colors, vtkOpenGLBufferObject::TextureBuffer);
    in.ColorTexture->CreateTextureBuffer(
      static_cast<unsigned int>(colors.size() / 4), 4, VTK_FLOAT, in.ColorBuffer);
    in.ColorTime = std::max(in.ColorsModified.GetMTime(), in.BuildTime);
    if (in.Lut)
    {
      in.ColorTime = std::max(in.ColorTime, in.Lut->GetMTime());
    }
  }

  // --- Shader for exactly this scene's features.
  vtkProperty* prop = actor->GetProperty();
  const int complexity = oglRen->GetLightingComplexity();
  const bool lit = shaded && prop->GetLighting() && complexity > 0;
  const bool holes = in.Holes;
  std::string vs = vtkStackedHeightFieldVS;
  std::string fs = vtkStackedHeightFieldFS;
  // Data lookup: one function, so that paging can swap in a virtual-texture lookup.
  Replace(fs,
    "//STRATA::HeightLookup::Dec",
    in.Paged ? vtkStackedHeightFieldPagedLookup
             : "uniform sampler2DArray uHeights;\n"
               "float strataHeight(int layer, ivec2 p) { return texelFetch(uHeights, ivec3(p, "
               "layer), 0).r; }");
  // Feedback: image load/store (GL 4.2 or the ARB extension), at most 63 horizons (page ids).
  bool feedback =
    in.Paged && this->LevelOfDetailFeedback && layers <= vtkFeedbackReduction::MaxDataSets;
  if (feedback)
  {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 42)
    {
      if (!in.FeedbackUnsupportedWarned)
      {
        vtkWarningMacro("OpenGL " << major << "." << minor
                                  << " has no image load/store: paging without feedback.");
        in.FeedbackUnsupportedWarned = true;
      }
      feedback = false;
    }
  }
  in.FeedbackActive = feedback;
  if (!feedback)
  {
    in.Pager.ClearFeedback();
    in.FeedbackPending = false;
  }
  Replace(fs,
    "//STRATA::Extensions::Dec",
    feedback ? "#extension GL_ARB_shader_image_load_store : require" : "");
  Replace(fs,
    "//STRATA::Feedback::Dec",
    feedback ? std::string(FeedbackDeclarations) + vtkFeedbackReduction::GetGLSLPackFunction()
             : "");
  Replace(fs, "//STRATA::Feedback::Impl", feedback ? FeedbackWrite : "");
  if (in.Paged)
  {
    Replace(fs,
      "//STRATA::CellCorners::Dec",
      "vec4 strataCellCorners(int layer, ivec2 c)\n"
      "{\n"
      "  ivec2 q = c - gPageBase;\n"
      "  return vec4(strataTexel(gPageSlot, q), strataTexel(gPageSlot, q + ivec2(1, 0)),\n"
      "    strataTexel(gPageSlot, q + ivec2(0, 1)), strataTexel(gPageSlot, q + ivec2(1, 1)));\n"
      "}");
    Replace(fs,
      "//STRATA::SearchLevel::Impl",
      "lv = strataLeafPage(layer, cLo0);\n"
      "  if (lv < 0)\n"
      "  {\n"
      "    return BIG; // an empty tile, or one without a slot: a hole\n"
      "  }");
  }
  else
  {
    Replace(fs,
      "//STRATA::CellCorners::Dec",
      "vec4 strataCellCorners(int layer, ivec2 c) { return strataCorners(layer, c); }");
    Replace(fs, "//STRATA::SearchLevel::Impl", "");
  }
  // Paged: a missing tile reads as BIG (GLSL 1.50 has no portable NaN constant).
  Replace(fs,
    "//STRATA::Hole::Impl",
    !holes     ? ""
    : in.Paged ? "valid = !any(isnan(h)) && all(lessThan(abs(h), vec4(1.0e30)));"
               : "valid = !any(isnan(h));");
  if (!shaded)
  {
    Replace(fs, "//STRATA::Color::Dec", "");
    Replace(fs, "//STRATA::Color::Impl", "");
    Replace(fs, "//STRATA::Shading::Dec", "");
    Replace(fs, "//STRATA::Shading::Impl", "");
    Replace(fs,
      "//STRATA::Output::Impl",
      "int id = hitLayer + 1;\n"
      "  fragOutput0 = vec4(float(id & 255), float((id >> 8) & 255), float((id >> 16) & 255), "
      "255.0) / 255.0;");
  }
  else
  {
    if (useLut)
    {
      Replace(fs,
        "//STRATA::Color::Dec",
        "uniform samplerBuffer uColors; // 1024 entries over uLutRange\nuniform vec2 uLutRange;");
      Replace(fs,
        "//STRATA::Color::Impl",
        "float lutS = (pGrid.z - uLutRange.x) / (uLutRange.y - uLutRange.x);\n"
        "  vec3 baseColor = texelFetch(uColors, clamp(int(lutS * 1024.0), 0, 1023)).rgb;");
    }
    else
    {
      Replace(fs, "//STRATA::Color::Dec", "uniform samplerBuffer uColors; // one per horizon");
      Replace(fs, "//STRATA::Color::Impl", "vec3 baseColor = texelFetch(uColors, hitLayer).rgb;");
    }
    if (lit)
    {
      std::ostringstream dec, impl;
      dec << "uniform mat3 uNormalMatrix; // grid -> view, inverse transpose\n"
             "uniform mat4 uGridToView;\n"
             "uniform int uParallel;\n"
             "uniform float uAmbient, uDiffuse, uSpecular, uSpecularPower;\n"
             "uniform vec3 uSpecularColor;\n"
          << oglRen->GetLightingUniforms();
      impl << "vec4 hc = strataCorners(hitLayer, hitCell);\n"
              "  vec2 huv = clamp(pGrid.xy - vec2(hitCell), 0.0, 1.0);\n"
              "  vec3 nGrid = vec3(-mix(hc.y - hc.x, hc.w - hc.z, huv.y), -mix(hc.z - hc.x, hc.w - "
              "hc.y, huv.x), 1.0);\n"
              "  vec3 normalVC = normalize(uNormalMatrix * nGrid);\n"
              "  vec3 posVC = (uGridToView * vec4(pGrid, 1.0)).xyz;\n"
              "  vec3 viewDirectionVC = uParallel != 0 ? vec3(0.0, 0.0, 1.0) : normalize(-posVC);\n"
              "  if (dot(normalVC, viewDirectionVC) < 0.0) normalVC = -normalVC; // two-sided\n"
              "  vec3 diffuse = vec3(0.0), specular = vec3(0.0);\n";
      if (complexity == 1)
      {
        impl << "  float df = max(0.0, normalVC.z);\n"
                "  diffuse = df * lightColor0;\n"
                "  specular = pow(df, uSpecularPower) * lightColor0;\n";
      }
      else
      {
        for (int l = 0; l < oglRen->GetLightingCount(); ++l)
        {
          impl << "  {\n    vec3 L = lightDirectionVC" << l << ";\n    float att = 1.0;\n";
          if (complexity == 3)
          {
            impl << "    if (lightPositional" << l << " != 0)\n    {\n"
                 << "      vec3 toP = posVC - lightPositionVC" << l << ";\n"
                 << "      float dist = length(toP);\n"
                 << "      float coneDot = dot(normalize(toP), lightDirectionVC" << l << ");\n"
                 << "      L = normalize(toP);\n"
                 << "      att = 1.0 / (lightAttenuation" << l << ".x + lightAttenuation" << l
                 << ".y * dist + lightAttenuation" << l << ".z * dist * dist);\n"
                 << "      if (lightConeAngle" << l << " < 90.0)\n"
                 << "        att *= coneDot >= cos(radians(lightConeAngle" << l
                 << ")) ? pow(coneDot, lightExponent" << l << ") : 0.0;\n"
                 << "    }\n";
          }
          impl << "    float df = max(0.0, dot(normalVC, -L));\n"
               << "    diffuse += att * df * lightColor" << l << ";\n"
               << "    if (df > 0.0)\n"
               << "      specular += att * pow(max(0.0, dot(reflect(L, normalVC), "
                  "viewDirectionVC)), uSpecularPower) * lightColor"
               << l << ";\n  }\n";
        }
      }
      impl << "  vec3 shadedColor = uAmbient * baseColor + uDiffuse * diffuse * baseColor + "
              "uSpecular * specular * uSpecularColor;";
      Replace(fs, "//STRATA::Shading::Dec", dec.str());
      Replace(fs, "//STRATA::Shading::Impl", impl.str());
      Replace(
        fs, "//STRATA::Output::Impl", "fragOutput0 = vec4(clamp(shadedColor, 0.0, 1.0), 1.0);");
    }
    else
    {
      Replace(fs, "//STRATA::Shading::Dec", "");
      Replace(fs, "//STRATA::Shading::Impl", "");
      Replace(fs, "//STRATA::Output::Impl", "fragOutput0 = vec4(baseColor, 1.0);");
    }
  }
  vtkShaderProgram* program =
    renWin->GetShaderCache()->ReadyShaderProgram(vs.c_str(), fs.c_str(), "");
  if (!program)
  {
    vtkErrorMacro("The height-field ray casting shader did not compile or link.");
    return;
  }
  in.VertexSource = vs;
  in.FragmentSource = fs;
  if (program != in.LastProgram || !in.VAO)
  {
    // A plain VAO: the box has one attribute, and its element buffer is part of its state.
    if (!in.VAO)
    {
      glGenVertexArrays(1, &in.VAO);
    }
    glBindVertexArray(in.VAO);
    in.BoxVertices->Bind();
    const GLint location = glGetAttribLocation(program->GetHandle(), "vertexGrid");
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    in.BoxIndices->Bind();
    glBindVertexArray(0);
    in.LastProgram = program;
  }

  // --- Matrices, composed in double so UTM-scale coordinates lose nothing: the GPU only sees
  // grid space (cells and heights) and clip space.
  vtkCamera* camera = ren->GetActiveCamera();
  const double aspect = ren->GetTiledAspectRatio();
  vtkNew<vtkMatrix4x4> worldToClip, gridToClip, clipToGrid, gridToView, modelGrid;
  worldToClip->DeepCopy(camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1));
  vtkMatrix4x4::Multiply4x4(actor->GetMatrix(), in.GridToWorld, modelGrid);
  vtkMatrix4x4::Multiply4x4(worldToClip, modelGrid, gridToClip);
  vtkMatrix4x4::Invert(gridToClip, clipToGrid);
  vtkMatrix4x4::Multiply4x4(camera->GetViewTransformMatrix(), modelGrid, gridToView);
  float m[16];
  ToFloat(gridToClip, m, true);
  program->SetUniformMatrix4x4("uGridToClip", m);
  ToFloat(clipToGrid, m, true);
  program->SetUniformMatrix4x4("uClipToGrid", m);

  int vp[4];
  ren->GetTiledSizeAndOrigin(&vp[2], &vp[3], &vp[0], &vp[1]);
  const float viewport[4] = { float(vp[0]), float(vp[1]), float(vp[2]), float(vp[3]) };
  program->SetUniform4f("uViewport", viewport);
  const float gridMax[2] = { float(nx - 1), float(ny - 1) };
  program->SetUniform2f("uGridMax", gridMax);
  const double zr[2] = { in.ZRange[0] <= in.ZRange[1] ? in.ZRange[0] : 0.0,
    in.ZRange[0] <= in.ZRange[1] ? in.ZRange[1] : 0.0 };
  const float zRange[2] = { float(zr[0]), float(zr[1]) };
  program->SetUniform2f("uZRange", zRange);
  // Bilinear interpolation in float is within a few ulps of the corner range; 1e-5 relative
  // of the largest magnitude is far above that and far below anything visible.
  program->SetUniformf("uZEps", float(1e-5 * std::max({ 1.0, std::abs(zr[0]), std::abs(zr[1]) })));
  program->SetUniformf("uStep", float(this->LinearSearchStep));
  // Ties: hits closer than 1e-6 of the near-to-far segment (t spans [0, 1]) are one hit.
  program->SetUniformf("uTieEps", 1e-6f);
  program->SetUniformi("uTileSize", tree.GetTileSize());
  const int levels = tree.GetNumberOfLevels();
  if (levels > 16)
  {
    vtkErrorMacro("Quadtree of " << levels << " levels: raise TileSize.");
    return;
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

  if (lit)
  {
    vtkNew<vtkMatrix3x3> normal;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        normal->SetElement(r, c, gridToView->GetElement(r, c));
    normal->Invert();
    normal->Transpose();
    float n9[9];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        n9[c * 3 + r] = static_cast<float>(normal->GetElement(r, c));
    program->SetUniformMatrix3x3("uNormalMatrix", n9);
    ToFloat(gridToView, m, true);
    program->SetUniformMatrix4x4("uGridToView", m);
    program->SetUniformi("uParallel", camera->GetParallelProjection() ? 1 : 0);
    program->SetUniformf("uAmbient", float(prop->GetAmbient()));
    program->SetUniformf("uDiffuse", float(prop->GetDiffuse()));
    program->SetUniformf("uSpecular", float(prop->GetSpecular()));
    program->SetUniformf("uSpecularPower", float(prop->GetSpecularPower()));
    const double* sc = prop->GetSpecularColor();
    const float specColor[3] = { float(sc[0]), float(sc[1]), float(sc[2]) };
    program->SetUniform3f("uSpecularColor", specColor);
    oglRen->UpdateLightingUniforms(program);
  }

  // --- Textures.
  vtkTextureUnitManager* units = renWin->GetTextureUnitManager();
  const int heightUnit = units->Allocate();
  const int tableUnit = in.Paged ? units->Allocate() : -1;
  state->vtkglActiveTexture(GL_TEXTURE0 + heightUnit);
  if (in.Paged)
  {
    glBindTexture(GL_TEXTURE_2D_ARRAY, in.AtlasTexture);
    program->SetUniformi("uAtlas", heightUnit);
    state->vtkglActiveTexture(GL_TEXTURE0 + tableUnit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, in.PageTableTexture);
    program->SetUniformi("uPageTable", tableUnit);
    program->SetUniformi("uPageStride", in.Pager.GetPageSize() - 1);
    const int* tiles = in.Pager.GetTiles();
    glUniform2i(program->FindUniform("uPageTiles"), tiles[0], tiles[1]);
  }
  else
  {
    glBindTexture(GL_TEXTURE_2D_ARRAY, in.HeightTexture);
    program->SetUniformi("uHeights", heightUnit);
  }
  in.NodeTexture->Activate();
  program->SetUniformi("uNodes", in.NodeTexture->GetTextureUnit());
  in.IntervalTexture->Activate();
  program->SetUniformi("uIntervals", in.IntervalTexture->GetTextureUnit());
  in.LayerListTexture->Activate();
  program->SetUniformi("uLayerLists", in.LayerListTexture->GetTextureUnit());
  if (shaded)
  {
    in.ColorTexture->Activate();
    program->SetUniformi("uColors", in.ColorTexture->GetTextureUnit());
    if (useLut)
    {
      const float lr[2] = { float(lutRange[0]), float(lutRange[1]) };
      program->SetUniform2f("uLutRange", lr);
    }
  }

  if (feedback)
  {
    const int s = this->FeedbackScale;
    const int fw = (vp[2] + s - 1) / s, fh = (vp[3] + s - 1) / s;
    if (!in.FeedbackTexture || fw != in.FeedbackSize[0] || fh != in.FeedbackSize[1])
    {
      if (!in.FeedbackTexture)
      {
        glGenTextures(1, &in.FeedbackTexture);
      }
      glBindTexture(GL_TEXTURE_2D, in.FeedbackTexture);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_R32UI, fw, fh, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
      vtkFeedbackReadBack::Allocate(in.FeedbackBuffer, size_t(fw) * fh);
      in.FeedbackSize[0] = fw;
      in.FeedbackSize[1] = fh;
      in.FeedbackPending = false;
    }
    const std::vector<uint32_t> zeros(size_t(fw) * fh, 0u);
    glBindTexture(GL_TEXTURE_2D, in.FeedbackTexture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, fw, fh, GL_RED_INTEGER, GL_UNSIGNED_INT, zeros.data());
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindImageTexture(0, in.FeedbackTexture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
    program->SetUniformi("uFeedback", 0);
    program->SetUniformi("uFeedbackScale", s);
    // The lattice phase cycles so that every pixel asks once per s^2 frames.
    const int phase = static_cast<int>(in.FeedbackFrame % (s * s));
    glUniform2i(program->FindUniform("uFeedbackOffset"), phase % s, phase / s);
    program->SetUniformf("uLodScale", float(this->LevelOfDetailThreshold));
    const int levelsPaged = std::min(in.Pager.GetNumberOfLevels(), vtkFeedbackReduction::MaxLevels);
    program->SetUniformi("uPageLevels", levelsPaged);
    int tilesX[32] = { 0 };
    for (int l = 0; l < levelsPaged; ++l)
    {
      tilesX[l] = in.Pager.GetLevelTiles(l)[0];
    }
    program->SetUniform1iv("uLevelTilesX", 32, tilesX);
  }

  // --- Draw the box's back faces, depth-clamped so far-plane clipping cannot cut rays short.
  vtkOpenGLState::ScopedglEnableDisable cullSaver(state, GL_CULL_FACE);
  state->vtkglEnable(GL_CULL_FACE);
  state->vtkglCullFace(GL_FRONT);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_CLAMP);
  glBindVertexArray(in.VAO);
  glDrawElements(GL_TRIANGLES, 36, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  glDisable(GL_DEPTH_CLAMP);
  state->vtkglCullFace(GL_BACK);

  in.NodeTexture->Deactivate();
  in.IntervalTexture->Deactivate();
  in.LayerListTexture->Deactivate();
  if (shaded)
  {
    in.ColorTexture->Deactivate();
  }
  state->vtkglActiveTexture(GL_TEXTURE0 + heightUnit);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  units->Free(heightUnit);
  if (tableUnit >= 0)
  {
    state->vtkglActiveTexture(GL_TEXTURE0 + tableUnit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    units->Free(tableUnit);
  }
  if (feedback)
  {
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
    std::array<double, 16> view;
    std::copy_n(gridToClip->GetData(), 16, view.begin());
    // Copied into the pixel buffer now; mapped at once or at the next frame (ReadFeedback).
    vtkFeedbackReadBack::Queue(renWin, in.FeedbackTexture, in.FeedbackBuffer);
    in.FeedbackPending = true;
    in.PendingViewChanged = view != in.LastView;
    in.LastView = view;
    if (!this->DeferFeedbackReadBack)
    {
      this->ReadFeedback();
    }
  }
  vtkOpenGLCheckErrorMacro("failed after rendering the height-field stack");
}

void vtkStackedHeightFieldMapper::ReadFeedback()
{
  vtkInternals& in = *this->Internals;
  in.FeedbackPending = false;
  const bool viewChanged = in.PendingViewChanged;
  const size_t count = size_t(in.FeedbackSize[0]) * in.FeedbackSize[1];
  // Timed from here: mapping, reduction and handing over (the copy was queued after the draw).
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<vtkFeedbackReduction::Entry> list;
  bool openCL = false;
  vtkFeedbackReadBack::Map(in.FeedbackBuffer,
    count,
    [&](const uint32_t* ids)
    {
      openCL = this->FeedbackOpenCL && in.Reduction.ReduceOpenCL(ids, count, list);
      if (!openCL)
        in.Reduction.ReduceCPU(ids, count, list);
    });
  std::vector<uint32_t> pages(list.size()), coverage(list.size());
  for (size_t e = 0; e < list.size(); ++e)
  {
    pages[e] = list[e].Page;
    coverage[e] = list[e].Coverage;
  }
  in.Pager.SetFeedback(pages, coverage, this->FeedbackScale * this->FeedbackScale, viewChanged);
  ++in.FeedbackFrame;
  in.Paging.FeedbackMilliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  in.Paging.FeedbackOpenCL = openCL;
}

void vtkStackedHeightFieldMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TileSize: " << this->TileSize << "\n";
  os << indent << "LinearSearchStep: " << this->LinearSearchStep << "\n";
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
