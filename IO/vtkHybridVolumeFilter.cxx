// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkHybridVolumeFilter.h"

#include "StrataHybridVolumeBuilder.h"
#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <string>

vtkStandardNewMacro(vtkHybridVolumeFilter);

namespace
{
/// Copies component 0 of `count` tuples from tuple `first` on into `out`, as float (what the
/// builder computes in). Dispatched to the array's own type, so no per-value virtual call.
struct CopyFirstComponent
{
  template<typename ArrayT>
  void operator()(ArrayT* array, vtkIdType first, vtkIdType count, float* out) const
  {
    for (const auto tuple : vtk::DataArrayTupleRange(array, first, first + count))
    {
      *out++ = static_cast<float>(tuple[0]);
    }
  }
};

/// The input's points per axis and the world position of its first point, the direction
/// ignored (see the class documentation).
void InputGeometry(const int extent[6],
  const double spacing[3],
  const double origin[3],
  int dimensions[3],
  double first[3])
{
  for (int a = 0; a < 3; ++a)
  {
    dimensions[a] = extent[2 * a + 1] - extent[2 * a] + 1;
    first[a] = origin[a] + extent[2 * a] * spacing[a];
  }
}
}

//------------------------------------------------------------------------------
vtkHybridVolumeFilter::vtkHybridVolumeFilter()
{
  this->SetNumberOfInputPorts(1);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

//------------------------------------------------------------------------------
vtkHybridVolumeFilter::~vtkHybridVolumeFilter()
{
  this->SetFileName(nullptr);
  this->SetOpacityFunction(nullptr);
}

//------------------------------------------------------------------------------
vtkCxxSetObjectMacro(vtkHybridVolumeFilter, OpacityFunction, vtkPiecewiseFunction);

//------------------------------------------------------------------------------
vtkMTimeType vtkHybridVolumeFilter::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  return this->OpacityFunction ? std::max(t, this->OpacityFunction->GetMTime()) : t;
}

//------------------------------------------------------------------------------
void vtkHybridVolumeFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Factor: " << this->Factor[0] << ", " << this->Factor[1] << ", "
     << this->Factor[2] << "\n";
  os << indent << "Filter: " << this->GetFilterAsString() << "\n";
  os << indent << "OverestimationBound: " << this->OverestimationBound << "\n";
  os << indent << "ErrorGridStep: " << this->ErrorGridStep[0] << ", " << this->ErrorGridStep[1]
     << ", " << this->ErrorGridStep[2] << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "PointBudget: " << this->PointBudget << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MB\n";
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

//------------------------------------------------------------------------------
void vtkHybridVolumeFilter::SetFilter(FilterType filter)
{
  if (this->Filter != filter)
  {
    this->Filter = filter;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
const char* vtkHybridVolumeFilter::GetFilterName(FilterType filter)
{
  switch (filter)
  {
    case FilterType::Box:
      return "box";
    case FilterType::Linear:
      return "linear";
    case FilterType::Cubic:
      return "cubic";
    case FilterType::Optimized:
      return "optimized";
  }
  return "unknown";
}

//------------------------------------------------------------------------------
void vtkHybridVolumeFilter::ConfigureBuilder(strata::HybridVolumeBuilder& builder) const
{
  builder.SetFactor(this->Factor[0], this->Factor[1], this->Factor[2]);
  builder.SetFilter(this->Filter);
  builder.SetOverestimationBound(this->OverestimationBound);
  builder.SetErrorGridStep(this->ErrorGridStep[0], this->ErrorGridStep[1], this->ErrorGridStep[2]);
  builder.SetThreshold(this->Threshold);
  if (vtkPiecewiseFunction* f = this->OpacityFunction)
  {
    builder.SetImportance([f](double original, double reconstruction)
      { return std::max(0.0, f->GetValue(original) - f->GetValue(reconstruction)); });
  }
  builder.SetPointBudget(static_cast<uint64_t>(this->PointBudget));
  builder.SetMemoryLimit(this->MemoryLimit);
}

//------------------------------------------------------------------------------
int vtkHybridVolumeFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkHybridVolumeFilter::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int whole[6] = { 0, -1, 0, -1, 0, -1 };
  double spacing[3] = { 1, 1, 1 };
  double origin[3] = { 0, 0, 0 };
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  }
  if (inInfo->Has(vtkDataObject::SPACING()))
  {
    inInfo->Get(vtkDataObject::SPACING(), spacing);
  }
  if (inInfo->Has(vtkDataObject::ORIGIN()))
  {
    inInfo->Get(vtkDataObject::ORIGIN(), origin);
  }
  int dimensions[3];
  double first[3];
  InputGeometry(whole, spacing, origin, dimensions, first);
  if (dimensions[0] <= 0 || dimensions[1] <= 0 || dimensions[2] <= 0)
  {
    // An empty input: RequestData reports it.
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    return 1;
  }
  SetLowResolutionInformation(outInfo, dimensions, this->Factor, spacing, first);
  return 1;
}

//------------------------------------------------------------------------------
int vtkHybridVolumeFilter::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // The builder reads every slice (twice): ask for all of them, whatever was asked downstream.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    int whole[6];
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), whole, 6);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkHybridVolumeFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  ClearOutputs(outputVector);
  auto fail = [&](const std::string& error)
  {
    ClearOutputs(outputVector);
    vtkErrorMacro("Cannot build the hybrid representation: " << error);
    return 0;
  };
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  if (!input)
  {
    return fail("no vtkImageData input");
  }
  int association = -1;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  if (!scalars || association != vtkDataObject::FIELD_ASSOCIATION_POINTS)
  {
    return fail("the input has no point scalars");
  }
  int dimensions[3];
  double first[3];
  InputGeometry(input->GetExtent(), input->GetSpacing(), input->GetOrigin(), dimensions, first);
  const vtkIdType sliceValues = static_cast<vtkIdType>(dimensions[0]) * dimensions[1];
  if (dimensions[0] <= 0 || dimensions[1] <= 0 || dimensions[2] <= 0 ||
      scalars->GetNumberOfTuples() != sliceValues * dimensions[2])
  {
    return fail("the input is empty or its scalars do not cover its extent");
  }
  if (scalars->GetNumberOfComponents() > 1)
  {
    vtkWarningMacro("Input array \"" << (scalars->GetName() ? scalars->GetName() : "") << "\" has "
                                     << scalars->GetNumberOfComponents()
                                     << " components; only the first is used.");
  }
  if (!input->GetDirectionMatrix()->IsIdentity())
  {
    vtkWarningMacro("The input's direction matrix is ignored: the outputs are axis-aligned.");
  }

  strata::HybridVolumeBuilder builder;
  this->ConfigureBuilder(builder);
  bool aborted = false;
  builder.SetInput(dimensions,
    input->GetSpacing(),
    first,
    [&](int firstSlice, int count, float* out)
    {
      aborted = aborted || this->GetAbortExecute();
      if (aborted)
      {
        return false;
      }
      const CopyFirstComponent copy;
      const vtkIdType start = firstSlice * sliceValues;
      const vtkIdType values = count * sliceValues;
      if (!vtkArrayDispatch::Dispatch::Execute(scalars, copy, start, values, out))
      {
        copy(scalars, start, values, out);
      }
      return true;
    });
  double last = 0.0;
  builder.SetProgressCallback(
    [&](double fraction)
    {
      // Short of 1 until the outputs are filled and the file is in place.
      fraction = std::min(fraction, 0.999);
      if (fraction > last)
      {
        last = fraction;
        this->UpdateProgress(fraction);
      }
    });
  strata::HybridVolumeFile file;
  if (!builder.Build(file))
  {
    return fail(aborted ? std::string("aborted") : builder.GetErrorMessage());
  }
  if (this->FileName && *this->FileName && !file.Write(this->FileName))
  {
    return fail(file.GetErrorMessage());
  }
  FillOutputs(file, vtkImageData::GetData(outputVector, 0), vtkPolyData::GetData(outputVector, 1));
  this->UpdateProgress(1.0);
  return 1;
}
