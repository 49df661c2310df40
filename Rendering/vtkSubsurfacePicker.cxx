// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkSubsurfacePicker.h"

#include "StrataHeightFieldReferenceCaster.h"
#include "StrataHeightFieldStack.h"
#include "StrataTransferFunctionTable.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkStackedHeightFieldMapper.h"

#include "StrataImageSampling.h"
#include "StrataPagePoolFile.h"
#include "StrataPagePoolSet.h"
#include "vtkAlgorithmOutput.h"
#include "vtkAssemblyPath.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiVolume.h"
#include "vtkObjectFactory.h"
#include "vtkPagePoolProtocol.h"
#include "vtkPointData.h"
#include "vtkProp3D.h"
#include "vtkProp3DCollection.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSubsurfacePicker);

namespace
{
/// index -> world of an image geometry (origin + D diag(s) index), as VTK composes it.
void IndexMatrix(const double o[3], const double s[3], const double* d, vtkMatrix4x4* m)
{
  vtkImageData::ComputeIndexToPhysicalMatrix(o, s, d, m->GetData());
  m->Modified();
}

void Apply(vtkMatrix4x4* m, const double p[3], double out[3])
{
  const double in[4] = { p[0], p[1], p[2], 1.0 };
  double r[4];
  m->MultiplyPoint(in, r);
  out[0] = r[0];
  out[1] = r[1];
  out[2] = r[2];
}

/// Clips the parametric segment [t0, t1] of a + t (b - a) to the box [lo, hi] (index space).
bool ClipToBox(const double a[3],
  const double b[3],
  const double lo[3],
  const double hi[3],
  double& t0,
  double& t1)
{
  for (int c = 0; c < 3; ++c)
  {
    const double d = b[c] - a[c];
    if (std::abs(d) < 1e-300)
    {
      if (a[c] < lo[c] || a[c] > hi[c])
        return false;
      continue;
    }
    double u0 = (lo[c] - a[c]) / d, u1 = (hi[c] - a[c]) / d;
    if (u0 > u1)
      std::swap(u0, u1);
    t0 = std::max(t0, u0);
    t1 = std::min(t1, u1);
  }
  return t0 <= t1;
}

/// The full-resolution data of `pool` under the segment p1-p2: only the pages its index-space
/// bounding box (+1 point) touches. `worldToIndexHint` gets the full resolution's world ->
/// index matrix. A height field (`heightScale` not 0) has the values for its third axis: the
/// segment is clipped to the value `range` of the stack there, so a ray reads only the tiles
/// under the part of it that can meet a surface.
vtkSmartPointer<vtkImageData> ReadPooled(const std::string& pool,
  int layer,
  vtkMatrix4x4* worldToIndexHint,
  const double p1[3],
  const double p2[3],
  double heightScale = 0.0,
  const double range[2] = nullptr)
{
  strata::PagePoolSet set;
  std::string error;
  if (!set.Open(pool, error))
  {
    vtkGenericWarningMacro("Cannot pick in the page pool: " << error);
    return nullptr;
  }
  const strata::PagePoolFormat::Header& h = set.GetFile().GetHeader();
  const int whole[6] = {
    0, h.Dimensions[0] - 1, 0, h.Dimensions[1] - 1, 0, set.IsTilePool() ? 0 : h.Dimensions[2] - 1
  };
  double o[3], s[3], d[9];
  std::copy(h.Origin, h.Origin + 3, o);
  std::copy(h.Spacing, h.Spacing + 3, s);
  std::copy(h.Direction, h.Direction + 9, d);
  if (heightScale != 0.0)
    s[2] = heightScale;
  IndexMatrix(o, s, d, worldToIndexHint);
  worldToIndexHint->Invert();
  double a[3], b[3];
  Apply(worldToIndexHint, p1, a);
  Apply(worldToIndexHint, p2, b);
  double lo[3], hi[3];
  for (int c = 0; c < 3; ++c)
  {
    lo[c] = whole[2 * c];
    hi[c] = whole[2 * c + 1];
  }
  if (heightScale != 0.0)
  {
    if (!(range[0] <= range[1]))
      return nullptr; // no values at all
    // A relative margin: the surfaces the GPU sees are the float values.
    const double margin = 1e-6 * std::max(1.0, std::max(std::abs(range[0]), std::abs(range[1])));
    lo[2] = range[0] - margin;
    hi[2] = range[1] + margin;
  }
  double t0 = 0.0, t1 = 1.0;
  int extent[6];
  if (!ClipToBox(a, b, lo, hi, t0, t1))
  {
    return nullptr;
  }
  for (int c = 0; c < 3; ++c)
  {
    const double u = a[c] + t0 * (b[c] - a[c]), v = a[c] + t1 * (b[c] - a[c]);
    extent[2 * c] = std::max(whole[2 * c], static_cast<int>(std::floor(std::min(u, v))) - 1);
    extent[2 * c + 1] = std::min(whole[2 * c + 1], static_cast<int>(std::ceil(std::max(u, v))) + 1);
  }
  if (heightScale != 0.0)
  {
    extent[4] = whole[4];
    extent[5] = whole[5];
  }
  strata::PagePoolSet::Read read;
  read.Layer = layer;
  read.ArrayName = "values";
  vtkSmartPointer<vtkImageData> out = set.ReadImage(0, extent, read, error);
  if (!out)
    vtkGenericWarningMacro("Cannot pick in the page pool: " << error);
  return out;
}

/// The pool behind input `port`, `connection` of `mapper` (vtkPagePoolProtocol), or empty for
/// an in-core input. A paged input is brought up to date at its coarsest level only (one
/// page): updating it as it stands could read its every page.
std::string InputPool(vtkAlgorithm* mapper, int port, int connection, int& layer)
{
  vtkAlgorithm* input = mapper->GetInputAlgorithm(port, connection);
  input->UpdateInformation();
  vtkInformation* info = mapper->GetInputInformation(port, connection);
  layer = 0;
  if (!vtkPagePoolProtocol::RequestCoarsestLevel(info))
    return std::string();
  input->Update(mapper->GetInputConnection(port, connection)->GetIndex());
  const vtkPagePoolProtocol::Identity pool =
    vtkPagePoolProtocol::GetInputPool(info, mapper->GetInputDataObject(port, connection));
  layer = pool.Layer;
  return pool.FileName;
}

/// The data of an in-core input, brought up to date.
vtkImageData* InputImage(vtkAlgorithm* mapper, int port, int connection)
{
  mapper->GetInputAlgorithm(port, connection)->Update();
  return vtkImageData::SafeDownCast(mapper->GetInputDataObject(port, connection));
}

/// One volume input as the ray samples it.
struct RayVolume
{
  vtkSmartPointer<vtkImageData> Data;
  vtkDataArray* Values = nullptr;
  vtkNew<vtkMatrix4x4> IndexToMapper, MapperToIndex;
  bool Nearest = false;
  double Range[2] = { 0, 1 };
  std::vector<float> RgbTau, Opacity;
  double Tau(double v) const
  {
    if (std::isnan(v))
      return 0.0;
    const int n = static_cast<int>(this->Opacity.size());
    const double x =
      std::min(std::max((v - this->Range[0]) / (this->Range[1] - this->Range[0]), 0.0), 1.0) *
      (n - 1);
    const int i = std::min(static_cast<int>(x), n - 2);
    const double f = x - i;
    return (1.0 - f) * this->RgbTau[4 * i + 3] + f * this->RgbTau[4 * (i + 1) + 3];
  }
};
}

//------------------------------------------------------------------------------
vtkSubsurfacePicker::vtkSubsurfacePicker()
{
  // UTM coordinates need double: a float is 0.5 m coarse at 6.7e6 m.
  this->RayPoints->SetDataTypeToDouble();
}

//------------------------------------------------------------------------------
vtkSubsurfacePicker::~vtkSubsurfacePicker() = default;

//------------------------------------------------------------------------------
void vtkSubsurfacePicker::Initialize()
{
  this->Superclass::Initialize();
  this->HorizonId = -1;
  this->HorizonValue = 0.0;
  this->HorizonT = VTK_DOUBLE_MAX;
  this->VolumeHit = false;
  this->VolumeT = VTK_DOUBLE_MAX;
  this->RayPoints->Reset();
  this->RayValues->Reset();
  this->RayValues->SetNumberOfComponents(1);
  this->RayOpacity->Reset();
  this->RayT.clear();
}

//------------------------------------------------------------------------------
int vtkSubsurfacePicker::Pick3DInternal(vtkRenderer* ren, double p1World[4], double p2World[4])
{
  int picked = this->Superclass::Pick3DInternal(ren, p1World, p2World);
  // vtkPicker tests a prop's mapper bounds first, which for a vtkMultiVolume are those of its
  // first input only: its members are cast here, along the whole ray.
  vtkPropCollection* props = this->PickFromList ? this->GetPickList() : ren->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* candidate = props->GetNextProp(it))
  {
    auto* multi = vtkMultiVolume::SafeDownCast(candidate);
    auto* mapper = multi ? vtkMultiVolumeRayCastMapper::SafeDownCast(multi->GetMapper()) : nullptr;
    if (!mapper || !multi->GetPickable() || !multi->GetVisibility())
      continue;
    multi->InitPathTraversal();
    vtkAssemblyPath* path = multi->GetNextPath();
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(multi->GetMatrix(), inverse);
    double p1[3], p2[3];
    Apply(inverse, p1World, p1);
    Apply(inverse, p2World, p2);
    this->Transform->SetMatrix(multi->GetMatrix()); // MarkPicked maps the point back with it
    if (path && this->PickVolumes(p1, p2, path, multi, mapper) < VTK_DOUBLE_MAX)
    {
      this->Prop3Ds->AddItem(multi);
      this->PickedPositions->InsertNextPoint(this->VolumePosition);
      picked = 1;
    }
  }
  // A horizon nearer than the volume samples stops the ray there, as in the renderer.
  size_t keep = this->RayT.size();
  while (keep > 0 && this->RayT[keep - 1] > this->HorizonT)
    --keep;
  if (keep < this->RayT.size())
  {
    this->RayT.resize(keep);
    this->RayPoints->Resize(static_cast<vtkIdType>(keep));
    this->RayPoints->SetNumberOfPoints(static_cast<vtkIdType>(keep));
    this->RayValues->SetNumberOfTuples(static_cast<vtkIdType>(keep));
    this->RayOpacity->SetNumberOfTuples(static_cast<vtkIdType>(keep));
  }
  if (this->VolumeT > this->HorizonT)
    this->VolumeHit = false;
  return picked;
}

//------------------------------------------------------------------------------
double vtkSubsurfacePicker::IntersectWithLine(const double p1[3],
  const double p2[3],
  double tol,
  vtkAssemblyPath* path,
  vtkProp3D* prop,
  vtkAbstractMapper3D* mapper)
{
  if (vtkStackedHeightFieldMapper::SafeDownCast(mapper))
    return this->PickHorizons(p1, p2, path, prop, mapper);
  if (vtkMultiVolume::SafeDownCast(prop))
    return VTK_DOUBLE_MAX; // cast in Pick3DInternal, whatever the first input's bounds
  if (vtkMultiVolumeRayCastMapper::SafeDownCast(mapper))
    return this->PickVolumes(p1, p2, path, prop, mapper);
  return this->Superclass::IntersectWithLine(p1, p2, tol, path, prop, mapper);
}

//------------------------------------------------------------------------------
// The mapper's grid space (x, y in cells of the stack's grid, z = value) and its first hit,
// exactly as vtkStackedHeightFieldMapper places it.
double vtkSubsurfacePicker::PickHorizons(const double p1[3],
  const double p2[3],
  vtkAssemblyPath* path,
  vtkProp3D* prop,
  vtkAbstractMapper3D* m)
{
  auto* mapper = vtkStackedHeightFieldMapper::SafeDownCast(m);
  const int n = mapper->GetNumberOfInputConnections(0);
  // The value range of every paged horizon (their pools' headers): one footprint for all, so
  // that the layers share a grid.
  double range[2] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (int k = 0; k < n; ++k)
  {
    int layer = 0;
    const std::string pool = InputPool(mapper, 0, k, layer);
    strata::PagePoolSet set;
    std::string error;
    if (!pool.empty() && set.Open(pool, error) &&
        set.GetFile().GetHeader().ValueRange[0] <= set.GetFile().GetHeader().ValueRange[1])
    {
      range[0] = std::min(range[0], set.GetFile().GetHeader().ValueRange[0]);
      range[1] = std::max(range[1], set.GetFile().GetHeader().ValueRange[1]);
    }
  }
  std::vector<vtkSmartPointer<vtkImageData>> images;
  for (int k = 0; k < n; ++k)
  {
    int layer = 0;
    const std::string pool = InputPool(mapper, 0, k, layer);
    if (!pool.empty())
    {
      vtkNew<vtkMatrix4x4> scratch;
      const double scale = mapper->GetHeightScale();
      auto sub = scale != 0.0 ? ReadPooled(pool, layer, scratch, p1, p2, scale, range) : nullptr;
      if (!sub)
        return VTK_DOUBLE_MAX; // the ray passes beside the grid
      images.emplace_back(sub);
      continue;
    }
    vtkImageData* image = InputImage(mapper, 0, k);
    if (!image)
      return VTK_DOUBLE_MAX;
    images.emplace_back(image);
  }
  if (images.empty())
    return VTK_DOUBLE_MAX;
  int dims[3];
  images[0]->GetDimensions(dims);
  strata::HeightFieldStack stack;
  if (!stack.Initialize(dims[0], dims[1]))
    return VTK_DOUBLE_MAX;
  const std::string arrayName = mapper->GetHeightArrayName() ? mapper->GetHeightArrayName() : "";
  std::vector<std::vector<double>> copies(images.size());
  for (size_t k = 0; k < images.size(); ++k)
  {
    vtkDataArray* a = arrayName.empty() ? images[k]->GetPointData()->GetScalars()
                                        : images[k]->GetPointData()->GetArray(arrayName.c_str());
    if (!a || a->GetNumberOfTuples() != vtkIdType(dims[0]) * dims[1])
      return VTK_DOUBLE_MAX;
    copies[k].resize(a->GetNumberOfTuples());
    for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
      copies[k][t] = static_cast<float>(a->GetComponent(t, 0)); // what the GPU sees
    if (!stack.AddLayer(copies[k].data(), mapper->GetUseNullValue(), mapper->GetNullValue()))
      return VTK_DOUBLE_MAX;
  }
  // Grid -> mapper coordinates: image index i = x + offset, then origin + D diag(sx, sy,
  // HeightScale) (i, j, z) (vtkStackedHeightFieldMapper).
  const double* o = images[0]->GetOrigin();
  const double* s = images[0]->GetSpacing();
  const double* d = images[0]->GetDirectionMatrix()->GetData();
  const double scale[3] = { s[0], s[1], mapper->GetHeightScale() };
  int e[6];
  images[0]->GetExtent(e);
  const double offset[2] = { stack.GetIndexOffset(0) + e[0], stack.GetIndexOffset(1) + e[2] };
  vtkNew<vtkMatrix4x4> gridToMapper, mapperToGrid;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
      gridToMapper->SetElement(r, c, d[3 * r + c] * scale[c]);
    gridToMapper->SetElement(
      r, 3, o[r] + d[3 * r] * s[0] * offset[0] + d[3 * r + 1] * s[1] * offset[1]);
  }
  vtkMatrix4x4::Invert(gridToMapper, mapperToGrid);
  double a[3], b[3], dir[3];
  Apply(mapperToGrid, p1, a);
  Apply(mapperToGrid, p2, b);
  for (int c = 0; c < 3; ++c)
    dir[c] = b[c] - a[c];
  const strata::HeightFieldReferenceCaster caster(stack);
  const strata::HeightFieldReferenceCaster::Hit hit = caster.Cast(a, dir, 0.0, 1.0);
  if (hit.Layer < 0 || !(hit.T < this->HorizonT))
    return hit.Layer < 0 ? VTK_DOUBLE_MAX : hit.T;
  double mapperPos[3];
  Apply(gridToMapper, hit.Point, mapperPos);
  this->HorizonId = hit.Layer;
  this->HorizonValue = hit.Point[2];
  this->HorizonT = hit.T;
  {
    const double in[4] = { mapperPos[0], mapperPos[1], mapperPos[2], 1.0 };
    double w[4];
    prop->GetMatrix()->MultiplyPoint(in, w);
    std::copy(w, w + 3, this->HorizonPosition);
  }
  if (hit.T < this->GlobalTMin)
    this->MarkPicked(path, prop, m, hit.T, mapperPos);
  return hit.T;
}

//------------------------------------------------------------------------------
// March the ray through every input of the mapper: extinction of all volumes at each
// segment midpoint, front to back, to OpacityThreshold.
double vtkSubsurfacePicker::PickVolumes(const double p1[3],
  const double p2[3],
  vtkAssemblyPath* path,
  vtkProp3D* prop,
  vtkAbstractMapper3D* m)
{
  auto* mapper = vtkMultiVolumeRayCastMapper::SafeDownCast(m);
  auto* multi = vtkMultiVolume::SafeDownCast(prop);
  vtkNew<vtkMatrix4x4> propInverse;
  vtkMatrix4x4::Invert(prop->GetMatrix(), propInverse);
  std::vector<std::unique_ptr<RayVolume>> volumes;
  double tA = 1.0, tB = 0.0, smallest = VTK_DOUBLE_MAX;
  for (int port = 0; port < mapper->GetNumberOfInputPorts(); ++port)
  {
    if (mapper->GetNumberOfInputConnections(port) == 0)
      continue;
    vtkVolume* member = multi ? multi->GetVolume(port) : vtkVolume::SafeDownCast(prop);
    int layer = 0;
    const std::string pool = InputPool(mapper, port, 0, layer);
    vtkImageData* image = pool.empty() ? InputImage(mapper, port, 0) : nullptr;
    if (!member || (pool.empty() && !image) || !member->GetProperty())
      continue;
    auto v = std::unique_ptr<RayVolume>(new RayVolume);
    // Mapper coordinates (the ray's) -> the member's world -> index.
    vtkNew<vtkMatrix4x4> memberToMapper;
    member->ComputeMatrix();
    vtkMatrix4x4::Multiply4x4(propInverse, member->GetMatrix(), memberToMapper);
    if (!multi)
      memberToMapper->Identity();
    vtkNew<vtkMatrix4x4> indexToMember;
    if (!pool.empty())
    {
      vtkNew<vtkMatrix4x4> mapperToMember;
      vtkMatrix4x4::Invert(memberToMapper, mapperToMember);
      double q1[3], q2[3];
      Apply(mapperToMember, p1, q1);
      Apply(mapperToMember, p2, q2);
      vtkNew<vtkMatrix4x4> memberToIndex;
      v->Data = ReadPooled(pool, layer, memberToIndex, q1, q2);
      if (!v->Data)
        continue;
      vtkMatrix4x4::Invert(memberToIndex, indexToMember);
    }
    else
    {
      v->Data = image;
      IndexMatrix(image->GetOrigin(),
        image->GetSpacing(),
        image->GetDirectionMatrix()->GetData(),
        indexToMember);
    }
    v->Values = v->Data->GetPointData()->GetScalars();
    if (!v->Values && v->Data->GetPointData()->GetNumberOfArrays() > 0)
      v->Values = v->Data->GetPointData()->GetArray(0);
    if (!v->Values)
      continue;
    vtkMatrix4x4::Multiply4x4(memberToMapper, indexToMember, v->IndexToMapper);
    vtkMatrix4x4::Invert(v->IndexToMapper, v->MapperToIndex);
    vtkVolumeProperty* p = member->GetProperty();
    v->Nearest = p->GetInterpolationType() == VTK_NEAREST_INTERPOLATION;
    strata::TransferFunctionTable::TabulateExtinction(
      p, strata::TransferFunctionTable::TableSize, v->Range, v->RgbTau, v->Opacity);
    double a[3], b[3], lo[3], hi[3];
    Apply(v->MapperToIndex, p1, a);
    Apply(v->MapperToIndex, p2, b);
    const int* e = v->Data->GetExtent();
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = e[2 * c];
      hi[c] = e[2 * c + 1];
      const double edge = std::sqrt(std::pow(v->IndexToMapper->GetElement(0, c), 2) +
                                    std::pow(v->IndexToMapper->GetElement(1, c), 2) +
                                    std::pow(v->IndexToMapper->GetElement(2, c), 2));
      if (edge > 0)
        smallest = std::min(smallest, edge);
    }
    double t0 = 0.0, t1 = 1.0;
    if (ClipToBox(a, b, lo, hi, t0, t1))
    {
      tA = std::min(tA, t0);
      tB = std::max(tB, t1);
    }
    volumes.push_back(std::move(v));
  }
  if (volumes.empty() || !(tA < tB))
    return VTK_DOUBLE_MAX;
  const double length =
    std::sqrt(vtkMath::Distance2BetweenPoints(p1, p2)); // world length of t in [0, 1]
  const double dt = this->StepFraction * smallest / length;
  this->RayValues->SetNumberOfComponents(static_cast<int>(volumes.size()));
  std::vector<double> values(volumes.size());
  double alpha = 0.0;
  for (double t = tA; t < tB; t += dt)
  {
    const double step = std::min(dt, tB - t);
    const double mid = t + 0.5 * step;
    double p[3], tau = 0.0;
    for (int c = 0; c < 3; ++c)
      p[c] = p1[c] + mid * (p2[c] - p1[c]);
    for (size_t k = 0; k < volumes.size(); ++k)
    {
      double x[3];
      Apply(volumes[k]->MapperToIndex, p, x);
      values[k] = strata::SampleImage(volumes[k]->Data, volumes[k]->Values, x, volumes[k]->Nearest);
      tau += volumes[k]->Tau(values[k]);
    }
    const double w = step * length;
    const double next = alpha + (1.0 - alpha) * (1.0 - std::exp(-tau * w));
    double world[3];
    {
      const double in[4] = { p[0], p[1], p[2], 1.0 };
      double out[4];
      prop->GetMatrix()->MultiplyPoint(in, out);
      std::copy(out, out + 3, world);
    }
    this->RayPoints->InsertNextPoint(world);
    this->RayValues->InsertNextTuple(values.data());
    this->RayT.push_back(mid);
    if (next >= this->OpacityThreshold && tau > 0.0)
    {
      // Where in this step: (1 - alpha) exp(-tau u) = 1 - threshold.
      const double u = -std::log((1.0 - this->OpacityThreshold) / (1.0 - alpha)) / tau;
      const double tHit = t + std::min(std::max(u / length, 0.0), step);
      this->RayOpacity->InsertNextValue(this->OpacityThreshold);
      double mapperPos[3];
      for (int c = 0; c < 3; ++c)
        mapperPos[c] = p1[c] + tHit * (p2[c] - p1[c]);
      this->VolumeHit = true;
      this->VolumeT = tHit;
      const double in[4] = { mapperPos[0], mapperPos[1], mapperPos[2], 1.0 };
      double out[4];
      prop->GetMatrix()->MultiplyPoint(in, out);
      std::copy(out, out + 3, this->VolumePosition);
      if (tHit < this->GlobalTMin)
        this->MarkPicked(path, prop, m, tHit, mapperPos);
      return tHit;
    }
    this->RayOpacity->InsertNextValue(next);
    alpha = next;
  }
  return VTK_DOUBLE_MAX;
}

//------------------------------------------------------------------------------
void vtkSubsurfacePicker::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OpacityThreshold: " << this->OpacityThreshold << "\n";
  os << indent << "StepFraction: " << this->StepFraction << "\n";
  os << indent << "HorizonId: " << this->HorizonId << "\n";
  os << indent << "HorizonValue: " << this->HorizonValue << "\n";
  os << indent << "HorizonPosition: " << this->HorizonPosition[0] << " " << this->HorizonPosition[1]
     << " " << this->HorizonPosition[2] << "\n";
  os << indent << "HorizonT: " << this->HorizonT << "\n";
  os << indent << "VolumeHit: " << this->VolumeHit << "\n";
  os << indent << "VolumePosition: " << this->VolumePosition[0] << " " << this->VolumePosition[1]
     << " " << this->VolumePosition[2] << "\n";
  os << indent << "VolumeT: " << this->VolumeT << "\n";
  os << indent << "RayPoints: " << this->RayPoints->GetNumberOfPoints() << "\n";
}
