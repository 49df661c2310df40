// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkHybridVolumeAlgorithm.h"

#include "StrataHybridVolumeFile.h"
#include "vtkCellArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedShortArray.h"

#include <algorithm>
#include <limits>

namespace
{
constexpr double Identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };

/// Output 0's extent and geometry from the original volume's; one definition for the
/// information pass and the data.
void LowResolutionGeometry(const int dimensions[3],
  const int factor[3],
  const double spacing[3],
  int extent[6],
  double lowSpacing[3])
{
  for (int a = 0; a < 3; ++a)
  {
    extent[2 * a] = 0;
    extent[2 * a + 1] =
      strata::HybridVolumeFile::GetLowResolutionDimension(dimensions[a], factor[a]) - 1;
    lowSpacing[a] = factor[a] * spacing[a];
  }
}

/// Connectivity 0, 1, ..., n - 1 in the narrowest array that holds it (vtkCellArray stores
/// either), so the vertex cells cost 4 bytes a point below 2^31 points.
template<typename ArrayT>
vtkSmartPointer<vtkDataArray> Iota(vtkIdType n)
{
  vtkNew<ArrayT> ids;
  ids->SetNumberOfValues(n);
  auto* p = ids->GetPointer(0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    p[i] = static_cast<typename ArrayT::ValueType>(i);
  }
  return vtkSmartPointer<vtkDataArray>(ids.GetPointer());
}

vtkSmartPointer<vtkFloatArray> NewFloatArray(const char* name, int components, vtkIdType tuples)
{
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(tuples);
  return a;
}
}

//------------------------------------------------------------------------------
vtkHybridVolumeAlgorithm::vtkHybridVolumeAlgorithm()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
}

//------------------------------------------------------------------------------
vtkHybridVolumeAlgorithm::~vtkHybridVolumeAlgorithm() = default;

//------------------------------------------------------------------------------
void vtkHybridVolumeAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}

//------------------------------------------------------------------------------
vtkTypeBool vtkHybridVolumeAlgorithm::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, inputVector, outputVector);
  }
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
  {
    return this->RequestUpdateExtent(request, inputVector, outputVector);
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    return this->RequestInformation(request, inputVector, outputVector);
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkHybridVolumeAlgorithm::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector*)
{
  return 1;
}

//------------------------------------------------------------------------------
int vtkHybridVolumeAlgorithm::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector*)
{
  return 1;
}

//------------------------------------------------------------------------------
int vtkHybridVolumeAlgorithm::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
vtkImageData* vtkHybridVolumeAlgorithm::GetLowResolutionOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(0));
}

//------------------------------------------------------------------------------
vtkPolyData* vtkHybridVolumeAlgorithm::GetPointsOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
void vtkHybridVolumeAlgorithm::SetLowResolutionInformation(vtkInformation* outInfo,
  const int dimensions[3],
  const int factor[3],
  const double spacing[3],
  const double origin[3])
{
  int extent[6];
  double lowSpacing[3];
  LowResolutionGeometry(dimensions, factor, spacing, extent, lowSpacing);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), lowSpacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), Identity, 9);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
}

//------------------------------------------------------------------------------
void vtkHybridVolumeAlgorithm::ClearOutputs(vtkInformationVector* outputVector)
{
  for (int port = 0; port < outputVector->GetNumberOfInformationObjects(); ++port)
  {
    if (vtkDataObject* output = vtkDataObject::GetData(outputVector, port))
    {
      output->Initialize();
    }
  }
}

//------------------------------------------------------------------------------
void vtkHybridVolumeAlgorithm::FillOutputs(const strata::HybridVolumeFile& file,
  vtkImageData* lowResolution,
  vtkPolyData* points)
{
  if (lowResolution)
  {
    int extent[6];
    double lowSpacing[3];
    LowResolutionGeometry(file.Dimensions, file.Factor, file.Spacing, extent, lowSpacing);
    lowResolution->Initialize();
    lowResolution->SetExtent(extent);
    lowResolution->SetSpacing(lowSpacing);
    lowResolution->SetOrigin(file.Origin);
    lowResolution->SetDirectionMatrix(Identity);
    vtkSmartPointer<vtkFloatArray> values =
      NewFloatArray("LowResolution", 1, static_cast<vtkIdType>(file.LowResolution.size()));
    std::copy(file.LowResolution.begin(), file.LowResolution.end(), values->GetPointer(0));
    lowResolution->GetPointData()->SetScalars(values);
  }
  if (!points)
  {
    return;
  }
  points->Initialize();
  const vtkIdType n = static_cast<vtkIdType>(file.Points.size());
  vtkNew<vtkPoints> positions;
  positions->SetDataTypeToDouble();
  positions->SetNumberOfPoints(n);
  vtkSmartPointer<vtkFloatArray> value = NewFloatArray("Value", 1, n);
  vtkSmartPointer<vtkFloatArray> error = NewFloatArray("Error", 1, n);
  vtkSmartPointer<vtkFloatArray> normals = NewFloatArray("Normals", 3, n);
  vtkNew<vtkUnsignedShortArray> codes;
  codes->SetName("NormalCode");
  codes->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const strata::HybridVolumeFile::Point& p = file.Points[static_cast<size_t>(i)];
    double x[3], normal[3];
    for (int a = 0; a < 3; ++a)
    {
      x[a] = file.Origin[a] + p.Position[a] * file.Spacing[a];
    }
    positions->SetPoint(i, x);
    strata::HybridVolumeFile::DecodeNormal(p.Normal, normal);
    normals->SetTuple(i, normal);
    value->SetValue(i, p.Value);
    error->SetValue(i, p.Error);
    codes->SetValue(i, p.Normal);
  }
  vtkNew<vtkCellArray> verts;
  verts->SetData(1,
    n <= std::numeric_limits<vtkTypeInt32>::max() ? Iota<vtkTypeInt32Array>(n)
                                                  : Iota<vtkTypeInt64Array>(n));
  points->SetPoints(positions);
  points->SetVerts(verts);
  vtkPointData* pd = points->GetPointData();
  pd->SetScalars(value);
  pd->AddArray(error);
  pd->SetNormals(normals);
  pd->AddArray(codes);
  // The world size of the error-grid cell a point stands for: what a renderer draws it as.
  vtkSmartPointer<vtkDoubleArray> cell = vtkSmartPointer<vtkDoubleArray>::New();
  cell->SetName("PointSpacing");
  cell->SetNumberOfComponents(3);
  const double g[3] = { file.ErrorGridStep[0] * file.Spacing[0],
    file.ErrorGridStep[1] * file.Spacing[1],
    file.ErrorGridStep[2] * file.Spacing[2] };
  cell->InsertNextTuple(g);
  points->GetFieldData()->AddArray(cell);
}
