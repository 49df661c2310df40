// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataMultiVolumeInput.h"

#include "StrataBrickAtlasFormat.h"
#include "StrataRenderUtilities.h"
#include "StrataVolumeBrickTree.h"

#include "vtkVolumeMapper.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPiecewiseFunction.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace strata
{

namespace
{
constexpr int TableSize = strata::TransferFunctionTable::TableSize;
}

bool MultiVolumeInput::GetComponentMode(vtkDataArray* scalars,
  vtkVolumeProperty* property,
  Components& mode,
  std::string& error)
{
  const int nc = scalars ? scalars->GetNumberOfComponents() : 1;
  const bool independent = property->GetIndependentComponents() != 0;
  mode = Components::One;
  if (nc > 4)
    error = std::to_string(nc) + " components (at most 4)";
  else if (nc == 3 && !independent)
    error = "3 dependent components (2: colour and opacity, 4: RGBA)";
  else if (nc > 1)
    mode = independent
             ? static_cast<Components>(static_cast<int>(Components::Independent2) + nc - 2)
             : (nc == 2 ? Components::ColorOpacity : Components::RGBA);
  return error.empty();
}

bool MultiVolumeInput::DrawsComponentsAsAsked(vtkVolumeProperty* property,
  int blendMode,
  Classifications classification)
{
  return blendMode == vtkVolumeMapper::COMPOSITE_BLEND && !property->GetShade(0) &&
         (!property->HasGradientOpacity(0) || property->GetDisableGradientOpacity(0)) &&
         classification == Classifications::PostClassification;
}

bool MultiVolumeInput::CollectComponents(vtkMultiVolumeRayCastMapper* mapper,
  int port,
  vtkImageData* image,
  vtkVolumeProperty* property,
  int& blendMode,
  Components& mode,
  bool& warned)
{
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(image,
    mapper->GetScalarMode(),
    mapper->GetArrayAccessMode(),
    mapper->GetArrayId(),
    mapper->GetArrayName(),
    cellFlag);
  std::string error;
  if (!GetComponentMode(scalars, property, mode, error))
  {
    vtkErrorWithObjectMacro(mapper, "The volume on port " << port << " has " << error << ".");
    return false;
  }
  if (mode == Components::One)
    return true;
  if (!warned && !DrawsComponentsAsAsked(property, blendMode, mapper->GetClassification()))
  {
    vtkWarningWithObjectMacro(mapper,
      "The volume on port " << port << " has several components: drawn composite, "
                            << "post-classified, without shading or gradient opacity.");
    warned = true;
  }
  blendMode = vtkVolumeMapper::COMPOSITE_BLEND;
  return true;
}

int MultiVolumeInput::GetOpacityComponent(Components mode)
{
  switch (mode)
  {
    case Components::One:
      return 0;
    case Components::ColorOpacity:
      return 1;
    case Components::RGBA:
      return 3;
    default:
      return -1;
  }
}

void MultiVolumeInput::GetColorRange(vtkDataArray* scalars, int c, double range[2])
{
  range[0] = 0.0;
  switch (scalars->GetDataType())
  {
    case VTK_UNSIGNED_CHAR:
      range[1] = VTK_UNSIGNED_CHAR_MAX;
      return;
    case VTK_SIGNED_CHAR:
      range[1] = VTK_SIGNED_CHAR_MAX;
      return;
    case VTK_UNSIGNED_SHORT:
      range[1] = VTK_UNSIGNED_SHORT_MAX;
      return;
    case VTK_SHORT:
      range[1] = VTK_SHORT_MAX;
      return;
    case VTK_FLOAT:
      range[1] = 1.0;
      return;
    default:
      scalars->GetFiniteRange(range, c);
      if (!(range[1] > range[0]))
        range[1] = range[0] + 1.0;
  }
}

MultiVolumeInput::MultiVolumeInput() = default;
MultiVolumeInput::~MultiVolumeInput() = default;

bool MultiVolumeInput::HasScalarsOf(vtkImageData* image) const
{
  return !this->Scalars.empty() && this->DataInput == image && this->DataTime >= image->GetMTime();
}

bool MultiVolumeInput::UpdateScalars(vtkImageData* image, vtkDataArray* scalars, vtkWindow* window)
{
  if (this->HasScalarsOf(image))
    return false;
  const vtkIdType n = image->GetNumberOfPoints();
  this->Scalars.resize(n);
  for (vtkIdType i = 0; i < n; ++i)
    this->Scalars[i] = static_cast<float>(scalars->GetComponent(i, 0));
  this->NumberOfComponents = std::min(std::max(scalars->GetNumberOfComponents(), 1), 4);
  const int nc = this->NumberOfComponents;
  this->ScalarType = strata::BrickAtlasFormat::FromVTKType(scalars->GetDataType());
  this->ComponentScalars.clear();
  this->ComponentScalars.resize(nc > 1 ? size_t(n) * nc : 0);
  for (int c = 0; nc > 1 && c < nc; ++c)
    for (vtkIdType i = 0; i < n; ++i)
      this->ComponentScalars[size_t(i) * nc + c] = static_cast<float>(scalars->GetComponent(i, c));
  this->UpdateColorRanges(scalars);
  this->DataTime = image->GetMTime();
  this->DataInput = image;
  this->Tree.reset();
  for (ComponentTree& t : this->ComponentTrees)
    t = ComponentTree();
  if (this->Data)
  {
    this->Data->ReleaseGraphicsResources(window);
    this->Data = nullptr;
  }
  return true;
}

void MultiVolumeInput::UpdateColorRanges(vtkDataArray* scalars)
{
  for (int c = 0; scalars && scalars->GetNumberOfComponents() == 4 && c < 3; ++c)
    GetColorRange(scalars, c, this->ColorRanges[c]);
}

namespace
{
template<typename T>
void StoreAs(const std::vector<float>& values, std::vector<unsigned char>& storage)
{
  storage.resize(values.size() * sizeof(T));
  T* out = reinterpret_cast<T*>(storage.data());
  for (size_t i = 0; i < values.size(); ++i)
    out[i] = static_cast<T>(values[i]); // integral values of the type's range: exact
}
}

namespace
{
// A tree of `values` in `type` (Float32: borrowing `values`; else stored in `native`, which
// it borrows).
bool BuildTree(const std::vector<float>& values,
  strata::VolumeBrickTree::ScalarType type,
  const int dims[3],
  int brickSize,
  std::vector<unsigned char>& native,
  std::unique_ptr<strata::VolumeBrickTree>& tree,
  std::string& error)
{
  using Type = strata::VolumeBrickTree::ScalarType;
  tree.reset(new strata::VolumeBrickTree);
  const void* scalars = values.data();
  if (type == Type::Float32)
    native.clear();
  else
  {
    if (type == Type::UInt8)
      StoreAs<uint8_t>(values, native);
    else if (type == Type::UInt16)
      StoreAs<uint16_t>(values, native);
    else
      StoreAs<int16_t>(values, native);
    scalars = native.data();
  }
  if (!tree->Build(scalars, type, dims, brickSize))
  {
    error = tree->GetErrorMessage();
    tree.reset();
    return false;
  }
  return true;
}
}

int MultiVolumeInput::UpdateTree(const int dims[3], int brickSize, bool native, std::string& error)
{
  using Type = strata::VolumeBrickTree::ScalarType;
  // Natively (8- and 16-bit): coarse levels rounded as page pools round them.
  const Type type = native ? this->ScalarType : Type::Float32;
  if (this->Tree && this->Tree->GetBrickSize() == brickSize && this->Tree->GetScalarType() == type)
    return 0;
  if (!BuildTree(this->Scalars, type, dims, brickSize, this->NativeScalars, this->Tree, error))
    return -1;
  const int nc = this->NumberOfComponents;
  for (int c = 1; c < nc; ++c)
  {
    ComponentTree& t = this->ComponentTrees[c - 1];
    t.Values.resize(this->Scalars.size());
    for (size_t i = 0; i < t.Values.size(); ++i)
      t.Values[i] = this->ComponentScalars[i * nc + c];
    if (!BuildTree(t.Values, type, dims, brickSize, t.Native, t.Tree, error))
    {
      this->Tree.reset();
      return -1;
    }
    if (type != Type::Float32)
      std::vector<float>().swap(t.Values); // the native tree borrows t.Native alone
  }
  return 1;
}

void MultiVolumeInput::UpdatePlainTexture(vtkOpenGLRenderWindow* window,
  const int dims[3],
  strata::BrickAtlasFormat::Storage storage)
{
  const int nc = this->NumberOfComponents;
  // One component stores like the atlas (R8, R16); several stay float.
  const auto type = strata::BrickAtlasFormat::Choose(
    { this->ScalarType }, nc == 1 ? storage : strata::BrickAtlasFormat::Storage::Float32);
  if (this->Data && this->DataType == type)
    return;
  if (this->Data)
    this->Data->ReleaseGraphicsResources(window);
  this->Data = vtkSmartPointer<vtkTextureObject>::New();
  this->Data->SetContext(window);
  this->DataType = type;
  if (strata::BrickAtlasFormat::IsNormalized(type))
  {
    std::vector<unsigned char> texels(
      this->Scalars.size() * strata::BrickAtlasFormat::GetTexelSize(type));
    strata::BrickAtlasFormat::Encode(
      this->Scalars.data(), this->Scalars.size(), type, this->ScalarType, texels.data());
    this->Data->Create3DFromRaw(dims[0],
      dims[1],
      dims[2],
      1,
      type == strata::VolumeBrickTree::ScalarType::UInt8 ? VTK_UNSIGNED_CHAR : VTK_UNSIGNED_SHORT,
      texels.data());
  }
  else
    this->Data->Create3DFromRaw(dims[0],
      dims[1],
      dims[2],
      nc,
      VTK_FLOAT,
      nc > 1 ? this->ComponentScalars.data() : this->Scalars.data());
  this->Data->SetWrapS(vtkTextureObject::ClampToEdge);
  this->Data->SetWrapT(vtkTextureObject::ClampToEdge);
  this->Data->SetWrapR(vtkTextureObject::ClampToEdge);
  // Nearest volumes snap to voxel centres in the shader: linear filtering serves both.
  this->Data->SetMinificationFilter(vtkTextureObject::Linear);
  this->Data->SetMagnificationFilter(vtkTextureObject::Linear);
}

namespace
{
// The largest opacity `table` reaches for scalars in [lo, hi]: the entries whose interpolation
// intervals meet it (clamped at the ends, as the texture is).
double TableMaxOpacity(const strata::TransferFunctionTable& table, double lo, double hi)
{
  const std::vector<float>& alpha = table.GetOpacity();
  const int n = static_cast<int>(alpha.size());
  if (n == 0)
    return 1.0;
  const double* range = table.GetScalarRange();
  const double scale = (n - 1) / (range[1] - range[0]);
  const double x0 = std::floor((lo - range[0]) * scale);
  const double x1 = std::ceil((hi - range[0]) * scale);
  const int i0 = static_cast<int>(std::min(std::max(x0, 0.0), n - 1.0));
  const int i1 = static_cast<int>(std::min(std::max(x1, 0.0), n - 1.0));
  return *std::max_element(alpha.begin() + i0, alpha.begin() + i1 + 1);
}

// What empty bricks read: the first scalar of zero opacity (the first scalar if none).
double TableEmptyScalar(const strata::TransferFunctionTable& table)
{
  const double* range = table.GetScalarRange();
  const std::vector<float>& alpha = table.GetOpacity();
  const int n = static_cast<int>(alpha.size());
  for (int i = 0; i < n; ++i)
    if (alpha[i] <= 0.0f)
      return range[0] + (range[1] - range[0]) * i / (n - 1.0);
  return range[0];
}
}

bool MultiVolumeInput::IsIndependent(Components mode)
{
  return mode == Components::Independent2 || mode == Components::Independent3 ||
         mode == Components::Independent4;
}

void MultiVolumeInput::UpdateTransfer(vtkOpenGLRenderWindow* window, vtkVolumeProperty* property)
{
  if (!this->Table.Update(window, property))
    return;
  const double* range = this->Table.GetScalarRange();
  const std::vector<float>& table = this->Table.GetRGBTau();
  std::vector<double> rgb(3 * TableSize), tau(TableSize);
  for (int i = 0; i < TableSize; ++i)
  {
    for (int c = 0; c < 3; ++c)
      rgb[3 * i + c] = table[4 * i + c];
    tau[i] = table[4 * i + 3];
  }
  this->PreIntegration.SetTransferFunction(range[0], range[1], TableSize, rgb.data(), tau.data());
  this->EmptyScalar = TableEmptyScalar(this->Table);
}

void MultiVolumeInput::UpdateComponentTables(vtkOpenGLRenderWindow* window,
  vtkVolumeProperty* property,
  Components mode)
{
  const bool independent = IsIndependent(mode);
  const int count =
    independent ? strata::MultiVolumeShaderComposer::GetNumberOfComponents(mode) : 1;
  for (int c = 1; c < count; ++c)
    this->ComponentTables[c - 1].Update(window, property, c);
  for (int c = 0; c < 4; ++c)
    this->ComponentWeights[c] = independent ? property->GetComponentWeight(c) : 1.0;
}

void MultiVolumeInput::UpdateGradientOpacity(vtkOpenGLRenderWindow* window,
  vtkVolumeProperty* property)
{
  const bool has = property->HasGradientOpacity(0) && !property->GetDisableGradientOpacity(0);
  const vtkMTimeType time =
    has ? std::max(property->GetMTime(), property->GetStoredGradientOpacity(0)->GetMTime()) : 0;
  if (!has || (this->GradientTexture && time > this->GradientTime))
  {
    if (this->GradientTexture)
      this->GradientTexture->ReleaseGraphicsResources(window);
    this->GradientTexture = nullptr;
  }
  if (!has || this->GradientTexture)
    return;
  std::vector<float> table;
  strata::TransferFunctionTable::TabulateGradientOpacity(property, 256, this->GradientRange, table);
  this->GradientTexture = vtkSmartPointer<vtkTextureObject>::New();
  this->GradientTexture->SetContext(window);
  this->GradientTexture->Create2DFromRaw(256, 1, 1, VTK_FLOAT, table.data());
  this->GradientTexture->SetWrapS(vtkTextureObject::ClampToEdge);
  this->GradientTexture->SetWrapT(vtkTextureObject::ClampToEdge);
  this->GradientTexture->SetMinificationFilter(vtkTextureObject::Linear);
  this->GradientTexture->SetMagnificationFilter(vtkTextureObject::Linear);
  this->GradientTime = time;
}

double MultiVolumeInput::MaxOpacity(double lo, double hi) const
{
  return TableMaxOpacity(this->Table, lo, hi);
}

double MultiVolumeInput::ComponentVisibility(Components mode, int c, double lo, double hi) const
{
  if (mode == Components::One)
    return this->BrickVisibility(lo, hi);
  if (IsIndependent(mode))
    return this->ShowsComponent(c)
             ? TableMaxOpacity(c == 0 ? this->Table : this->ComponentTables[c - 1], lo, hi)
             : 0.0;
  return c == GetOpacityComponent(mode) ? this->MaxOpacity(lo, hi) : 1.0;
}

double MultiVolumeInput::GetComponentEmptyScalar(Components mode, int c) const
{
  if (mode == Components::One)
    return this->GetEmptyScalar();
  if (IsIndependent(mode) && c > 0)
    return TableEmptyScalar(this->ComponentTables[c - 1]);
  return this->EmptyScalar;
}

void MultiVolumeInput::SetBlendMode(int mode, const std::vector<double>& isoValues)
{
  std::vector<double> iso = isoValues;
  std::sort(iso.begin(), iso.end());
  if (mode == this->BlendMode && iso == this->IsoValues)
    return;
  this->BlendMode = mode;
  this->IsoValues = iso;
  this->SkipTime = 0; // the skip grid is classified again
}

double MultiVolumeInput::BrickVisibility(double lo, double hi) const
{
  switch (this->BlendMode)
  {
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      return this->MaxOpacity(-VTK_DOUBLE_MAX, hi);
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      return this->MaxOpacity(lo, VTK_DOUBLE_MAX);
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      return 1.0;
    default:
      return this->MaxOpacity(lo, hi);
  }
}

double MultiVolumeInput::CellVisibility(double lo, double hi) const
{
  if (this->BlendMode != vtkVolumeMapper::ISOSURFACE_BLEND)
    return this->BrickVisibility(lo, hi);
  double visible = 0.0;
  for (double v : this->IsoValues)
    if (v >= lo && v <= hi)
      visible = std::max(visible, this->MaxOpacity(v, v));
  return visible;
}

double MultiVolumeInput::GetEmptyScalar() const
{
  const double* range = this->Table.GetScalarRange();
  switch (this->BlendMode)
  {
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      return range[0];
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      return range[1];
    default:
      return this->EmptyScalar;
  }
}

void MultiVolumeInput::UpdateSkipGrid(const strata::VolumeBrickTree* poolTree,
  const std::string& pool,
  const int dims[3],
  int cellSize,
  int opacityComponent)
{
  if (poolTree && this->SkipPool != pool)
  {
    this->SkipPool = pool;
    this->SkipDataTime = 0;
  }
  const int component = this->NumberOfComponents > 1 ? opacityComponent : 0;
  const bool build =
    poolTree ? this->SkipDataTime == 0
             : this->SkipDataTime != this->DataTime || this->Skip.GetCellSize() != cellSize ||
                 this->Skip.GetMinima().empty() || this->SkipComponent != component;
  if (build && poolTree)
  {
    // Paged: the level-0 bricks' ranges are the cells (stride B - 1), nothing is read.
    const int* nb = poolTree->GetLevelBricks(0);
    std::vector<float> lo(poolTree->GetLevelOffset(0) + size_t(nb[0]) * nb[1] * nb[2]),
      hi(lo.size());
    for (size_t id = 0; id < lo.size(); ++id)
    {
      lo[id] = poolTree->GetNode(static_cast<int>(id)).Min;
      hi[id] = poolTree->GetNode(static_cast<int>(id)).Max;
    }
    this->Skip.BuildFromRanges(nb, poolTree->GetBrickStride(), lo.data(), hi.data());
    this->SkipDataTime = 1;
  }
  else if (build && component > 0)
  {
    std::vector<float> values(this->Scalars.size());
    for (size_t i = 0; i < values.size(); ++i)
      values[i] = this->ComponentScalars[i * this->NumberOfComponents + component];
    this->Skip.Build(values.data(), dims, cellSize);
  }
  else if (build)
    this->Skip.Build(this->Scalars.data(), dims, cellSize);
  if (build && !poolTree)
  {
    this->SkipDataTime = this->DataTime;
    this->SkipComponent = component;
  }
  if (!build && this->SkipTime == this->Table.GetBuildCount() && this->SkipTexture)
    return;
  this->Skip.Classify([this](double lo, double hi) { return this->CellVisibility(lo, hi); });
  const int* cd = this->Skip.GetCellDimensions();
  glBindTexture(GL_TEXTURE_3D, this->SkipTexture.Get());
  const strata::RenderUtilities::ScopedPixelStore alignment(GL_UNPACK_ALIGNMENT, 1);
  glTexImage3D(GL_TEXTURE_3D,
    0,
    GL_R8UI,
    cd[0],
    cd[1],
    cd[2],
    0,
    GL_RED_INTEGER,
    GL_UNSIGNED_BYTE,
    this->Skip.GetDistances().data());
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_3D, 0);
  this->SkipTime = this->Table.GetBuildCount();
}

void MultiVolumeInput::UpdatePreIntegration(vtkOpenGLRenderWindow* window,
  Classifications classification,
  int tableSize,
  double sampleDistance)
{
  const bool full = classification == Classifications::PreIntegrated;
  this->PreIntegration.SetTableSize(tableSize);
  this->PreIntegration.SetStepLength(sampleDistance);
  if (full)
    this->PreIntegration.UpdateFullTable();
  else
    this->PreIntegration.UpdateIntegralTable();
  const unsigned long count = full ? this->PreIntegration.GetFullTableBuildCount()
                                   : this->PreIntegration.GetIntegralTableBuildCount();
  const int kind = static_cast<int>(classification);
  if (this->PreTable && this->PreTableCount == count && this->PreTableKind == kind)
    return;
  if (!this->PreTable)
    this->PreTable = vtkSmartPointer<vtkTextureObject>::New();
  const int m = this->PreIntegration.GetTableSize();
  this->PreTable->SetContext(window);
  this->PreTable->ReleaseGraphicsResources(window);
  this->PreTable->SetContext(window);
  const std::vector<float>& data =
    full ? this->PreIntegration.GetFullTable() : this->PreIntegration.GetIntegralTable();
  this->PreTable->Create2DFromRaw(m, full ? m : 1, 4, VTK_FLOAT, const_cast<float*>(data.data()));
  this->PreTable->SetWrapS(vtkTextureObject::ClampToEdge);
  this->PreTable->SetWrapT(vtkTextureObject::ClampToEdge);
  // The full table is read with bilinear filtering; the integral table with texelFetch and
  // mix in float (filter weights would be amplified by its division).
  const int filter = full ? vtkTextureObject::Linear : vtkTextureObject::Nearest;
  this->PreTable->SetMinificationFilter(filter);
  this->PreTable->SetMagnificationFilter(filter);
  this->PreTableCount = count;
  this->PreTableKind = kind;
}

void MultiVolumeInput::Bind(vtkOpenGLRenderWindow* window,
  vtkShaderProgram* program,
  int n,
  vtkVolumeProperty* property,
  const Binding& b,
  std::vector<int>& rawUnits)
{
  vtkTextureUnitManager* units = window->GetTextureUnitManager();
  auto bindRaw = [&](unsigned int texture, const std::string& name)
  {
    const int unit = units->Allocate();
    rawUnits.push_back(unit);
    window->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_3D, texture);
    program->SetUniformi(name.c_str(), unit);
  };
  const std::string N = std::to_string(n);
  program->SetUniformMatrix4x4(("uLocalToIndex" + N).c_str(), const_cast<float*>(b.LocalToIndex));
  program->SetUniformf(("uNearest" + N).c_str(),
    property->GetInterpolationType() == VTK_NEAREST_INTERPOLATION ? 1.0f : 0.0f);
  if (b.Normalized)
    program->SetUniform2f(("uDecode" + N).c_str(), b.Decode);
  // Several components in the atlas: component c > 0 is volume N "c" c of one scalar, read by
  // its own lookup (strata::MultiVolumeShaderComposer).
  const int lookups =
    b.Atlas ? strata::MultiVolumeShaderComposer::GetNumberOfComponents(b.ComponentMode) : 0;
  for (int c = 0; c < lookups; ++c)
  {
    const std::string L = c == 0 ? N : N + "c" + std::to_string(c);
    bindRaw(c == 0 ? b.IndexTexture : b.ComponentIndexTextures[c - 1], "uIndex" + L);
    const float tableDims[3] = {
      float(b.TableBricks[0]), float(b.TableBricks[1]), float(b.TableBricks[2])
    };
    program->SetUniform3f(("uTableDims" + L).c_str(), tableDims);
    const float S = static_cast<float>(b.BrickSize - 1);
    const float extent[3] = { tableDims[0] * S, tableDims[1] * S, tableDims[2] * S };
    const float scale[3] = { 1.0f / extent[0], 1.0f / extent[1], 1.0f / extent[2] };
    program->SetUniform3f(("uIndexExtent" + L).c_str(), extent);
    program->SetUniform3f(("uIndexScale" + L).c_str(), scale);
    program->SetUniformf(("uEmptyScalar" + L).c_str(),
      static_cast<float>(this->GetComponentEmptyScalar(b.ComponentMode, c)));
    if (b.Normalized && c > 0)
      program->SetUniform2f(("uDecode" + L).c_str(), b.Decode);
  }
  if (!b.Atlas)
  {
    this->Data->Activate();
    program->SetUniformi(("uVolume" + N).c_str(), this->Data->GetTextureUnit());
    const float dims[3] = { float(b.Dims[0]), float(b.Dims[1]), float(b.Dims[2]) };
    program->SetUniform3f(("uDims" + N).c_str(), dims);
  }
  if (b.Skipping)
  {
    bindRaw(this->SkipTexture.GetName(), "uSkip" + N);
    const int* cd = this->Skip.GetCellDimensions();
    const float grid[4] = {
      float(cd[0]), float(cd[1]), float(cd[2]), float(this->Skip.GetCellSize())
    };
    program->SetUniform4f(("uSkipGrid" + N).c_str(), grid);
  }
  if (b.Shaded)
  {
    const float material[4] = { float(property->GetAmbient(0)),
      float(property->GetDiffuse(0)),
      float(property->GetSpecular(0)),
      float(property->GetSpecularPower(0)) };
    program->SetUniform4f(("uMaterial" + N).c_str(), material);
  }
  if (b.BlendMode != vtkVolumeMapper::COMPOSITE_BLEND)
    this->BindBlendMode(program, N, property, b);
  if (b.ComponentMode != Components::One)
    this->BindComponents(program, N, property, b);
  if (b.GradientOpacity && this->GradientTexture)
  {
    this->GradientTexture->Activate();
    program->SetUniformi(("uGradientOpacity" + N).c_str(), this->GradientTexture->GetTextureUnit());
    const double* g = this->GradientRange;
    // Entry i at magnitude g0 + i (g1 - g0) / 255, its texel centre at (i + 0.5) / 256.
    const float range[3] = { float(g[0]), float(255.0 / (256.0 * (g[1] - g[0]))), 0.5f / 256.f };
    program->SetUniform3f(("uGradientRange" + N).c_str(), range);
    program->SetUniformf(("uUnit" + N).c_str(),
      static_cast<float>(strata::TransferFunctionTable::GetUnitDistance(property)));
  }
  if (b.CropLo)
  {
    program->SetUniform3f(("uCropLo" + N).c_str(), b.CropLo);
    program->SetUniform3f(("uCropHi" + N).c_str(), b.CropHi);
    program->SetUniformi(("uCropFlags" + N).c_str(), b.CropFlags);
  }
  if (b.Classification == Classifications::PostClassification ||
      b.BlendMode != vtkVolumeMapper::COMPOSITE_BLEND)
  {
    vtkTextureObject* transfer = this->Table.GetTexture();
    transfer->Activate();
    program->SetUniformi(("uTransfer" + N).c_str(), transfer->GetTextureUnit());
    const double* r = this->Table.GetTableRange();
    const float range[3] = { float(r[0]), float(r[1]), float(r[2]) };
    program->SetUniform3f(("uTableRange" + N).c_str(), range);
    return;
  }
  this->PreTable->Activate();
  program->SetUniformi(("uPreTable" + N).c_str(), this->PreTable->GetTextureUnit());
  const double* sr = this->Table.GetScalarRange();
  const float preRange[3] = {
    float(sr[0]), float(1.0 / (sr[1] - sr[0])), float(this->PreIntegration.GetTableSize())
  };
  program->SetUniform3f(("uPreRange" + N).c_str(), preRange);
  if (b.Classification == Classifications::PreIntegrated)
    program->SetUniformf(("uPreStep" + N).c_str(), static_cast<float>(b.SampleDistance));
  else
    program->SetUniformf(
      ("uPreMaxColor" + N).c_str(), static_cast<float>(this->PreIntegration.GetMaximumColor()));
}

void MultiVolumeInput::BindBlendMode(vtkShaderProgram* program,
  const std::string& N,
  vtkVolumeProperty* property,
  const Binding& b)
{
  program->SetUniformf(("uUnit" + N).c_str(),
    static_cast<float>(strata::TransferFunctionTable::GetUnitDistance(property)));
  if (b.BlendMode == vtkVolumeMapper::ISOSURFACE_BLEND)
  {
    float iso[8] = { 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f };
    const int count = std::min(static_cast<int>(this->IsoValues.size()), 8);
    for (int i = 0; i < count; ++i)
      iso[i] = static_cast<float>(this->IsoValues[i]);
    program->SetUniform1fv(("uIso" + N).c_str(), 8, iso);
    program->SetUniformi(("uNumIso" + N).c_str(), count);
    return;
  }
  const double* sr = this->Table.GetScalarRange();
  const float normalize[2] = { float(sr[0]), float(1.0 / (sr[1] - sr[0])) };
  program->SetUniform2f(("uNormalize" + N).c_str(), normalize);
  const float average[2] = { b.AverageRange ? float(b.AverageRange[0]) : -VTK_FLOAT_MAX,
    b.AverageRange ? float(b.AverageRange[1]) : VTK_FLOAT_MAX };
  program->SetUniform2f(("uAverageRange" + N).c_str(), average);
}

// Several components: the weights and the tables of components 1, 2, ... (independent), or the
// colour ranges (RGBA); component 0's table is bound as every volume's.
void MultiVolumeInput::BindComponents(vtkShaderProgram* program,
  const std::string& N,
  vtkVolumeProperty* property,
  const Binding& b)
{
  if (b.ComponentMode == Components::RGBA)
  {
    float lo[3], scale[3];
    for (int c = 0; c < 3; ++c)
    {
      const double* r = this->ColorRanges[c];
      lo[c] = static_cast<float>(r[0]);
      scale[c] = static_cast<float>(r[1] > r[0] ? 1.0 / (r[1] - r[0]) : 1.0e6);
    }
    program->SetUniform3f(("uColorLo" + N).c_str(), lo);
    program->SetUniform3f(("uColorScale" + N).c_str(), scale);
    return;
  }
  if (b.ComponentMode == Components::ColorOpacity)
    return;
  const int count = strata::MultiVolumeShaderComposer::GetNumberOfComponents(b.ComponentMode);
  float weights[4] = { 0.f, 0.f, 0.f, 0.f };
  for (int c = 0; c < count; ++c)
    weights[c] = static_cast<float>(property->GetComponentWeight(c));
  program->SetUniform4f(("uWeights" + N).c_str(), weights);
  for (int c = 1; c < count; ++c)
  {
    vtkTextureObject* transfer = this->ComponentTables[c - 1].GetTexture();
    transfer->Activate();
    const std::string C = N + "_" + std::to_string(c);
    program->SetUniformi(("uTransfer" + C).c_str(), transfer->GetTextureUnit());
    const double* r = this->ComponentTables[c - 1].GetTableRange();
    const float range[3] = { float(r[0]), float(r[1]), float(r[2]) };
    program->SetUniform3f(("uTableRange" + C).c_str(), range);
  }
}

void MultiVolumeInput::Unbind(const Binding& b)
{
  const int count = IsIndependent(b.ComponentMode)
                      ? strata::MultiVolumeShaderComposer::GetNumberOfComponents(b.ComponentMode)
                      : 1;
  for (int c = 1; c < count; ++c)
    this->ComponentTables[c - 1].GetTexture()->Deactivate();
  if (b.GradientOpacity && this->GradientTexture)
    this->GradientTexture->Deactivate();
  if (this->Data && !b.Atlas)
    this->Data->Deactivate();
  if (b.Classification == Classifications::PostClassification ||
      b.BlendMode != vtkVolumeMapper::COMPOSITE_BLEND)
    this->Table.GetTexture()->Deactivate();
  else
    this->PreTable->Deactivate();
}

void MultiVolumeInput::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Data)
    this->Data->ReleaseGraphicsResources(window);
  this->Data = nullptr;
  this->Table.ReleaseGraphicsResources(window);
  for (strata::TransferFunctionTable& table : this->ComponentTables)
    table.ReleaseGraphicsResources(window);
  if (this->PreTable)
    this->PreTable->ReleaseGraphicsResources(window);
  this->PreTable = nullptr;
  this->PreTableKind = -1;
  this->SkipTexture.Release();
  if (this->GradientTexture)
    this->GradientTexture->ReleaseGraphicsResources(window);
  this->GradientTexture = nullptr;
}
}
