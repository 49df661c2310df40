// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkHorizonVolumeSampler.h"

#include "StrataImageSampling.h"
#include "vtkPagePoolProtocol.h"
#include "vtkPagePoolReader.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkHorizonVolumeSampler);

namespace
{
const double NaN = std::numeric_limits<double>::quiet_NaN();

/// index -> world of an image geometry (origin + D diag(s) index), as VTK composes it.
void IndexToWorld(const double o[3], const double s[3], const double* d, vtkMatrix4x4* m)
{
  vtkImageData::ComputeIndexToPhysicalMatrix(o, s, d, m->GetData());
  m->Modified();
}

void Apply(vtkMatrix4x4* m, const double p[3], double out[3])
{
  const double in[4] = { p[0], p[1], p[2], 1.0 };
  double r[4];
  m->MultiplyPoint(in, r);
  std::copy_n(r, 3, out);
}

vtkDataArray* NamedOrScalars(vtkImageData* image, const std::string& name)
{
  return name.empty() ? image->GetPointData()->GetScalars()
                      : image->GetPointData()->GetArray(name.c_str());
}
}

vtkHorizonVolumeSampler::vtkHorizonVolumeSampler()
{
  this->SetNumberOfInputPorts(2);
}

vtkHorizonVolumeSampler::~vtkHorizonVolumeSampler() = default;

int vtkHorizonVolumeSampler::FillInputPortInformation(int port, vtkInformation* info)
{
  (void)port;
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkHorizonVolumeSampler::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector*)
{
  return 1; // the output's geometry is the horizon's, copied by the executive
}

int vtkHorizonVolumeSampler::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  for (int port = 0; port < 2; ++port)
  {
    vtkInformation* in = inputVector[port]->GetInformationObject(0);
    if (!in)
      continue;
    // A paged volume is read here block by block: its pipeline output stays the coarsest level.
    if (port == 1)
      vtkPagePoolProtocol::RequestCoarsestLevel(in);
    in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()),
      6);
  }
  return 1;
}

int vtkHorizonVolumeSampler::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  this->NumberOfSampledPoints = this->NumberOfEmptyPoints = this->NumberOfPagesRead = 0;
  vtkImageData* horizon = vtkImageData::GetData(inputVector[0]);
  vtkImageData* volume = vtkImageData::GetData(inputVector[1]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!horizon || !volume)
  {
    vtkErrorMacro("A horizon (input 0) and a volume (input 1) are needed.");
    return 0;
  }
  int dims[3];
  horizon->GetDimensions(dims);
  vtkDataArray* heights = NamedOrScalars(horizon, this->HeightArrayName);
  const vtkIdType points = static_cast<vtkIdType>(dims[0]) * dims[1];
  if (dims[2] != 1 || !heights || heights->GetNumberOfComponents() != 1 ||
      heights->GetNumberOfTuples() != points)
  {
    vtkErrorMacro("The horizon must be an nx x ny x 1 image with a single-component height "
                  "array ("
                  << (this->HeightArrayName.empty() ? "its scalars" : this->HeightArrayName)
                  << "); it has " << dims[0] << " x " << dims[1] << " x " << dims[2] << " points.");
    return 0;
  }

  // The volume: in core, or the pool behind a vtkPagePoolReader at full resolution.
  vtkInformation* volumeInfo = inputVector[1]->GetInformationObject(0);
  const std::string pool = vtkPagePoolProtocol::GetInputPool(volumeInfo, volume).FileName;
  vtkNew<vtkPagePoolReader> reader;
  vtkNew<vtkMatrix4x4> volumeToIndex;
  int whole[6];
  if (!pool.empty())
  {
    reader->SetFileName(pool.c_str());
    reader->SetResolution(1.0);
    reader->UpdateInformation();
    vtkInformation* info = reader->GetOutputInformation(0);
    if (!info->Has(vtkDataObject::ORIGIN()))
    {
      vtkErrorMacro("Cannot read the page pool " << pool << " behind the volume.");
      return 0;
    }
    double o[3], s[3], d[9];
    info->Get(vtkDataObject::ORIGIN(), o);
    info->Get(vtkDataObject::SPACING(), s);
    info->Get(vtkDataObject::DIRECTION(), d);
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    IndexToWorld(o, s, d, volumeToIndex);
  }
  else
  {
    if (!NamedOrScalars(volume, this->VolumeArrayName))
    {
      vtkErrorMacro("The volume has no point array "
                    << (this->VolumeArrayName.empty() ? "of scalars" : this->VolumeArrayName)
                    << ".");
      return 0;
    }
    volume->GetExtent(whole);
    IndexToWorld(volume->GetOrigin(),
      volume->GetSpacing(),
      volume->GetDirectionMatrix()->GetData(),
      volumeToIndex);
  }
  volumeToIndex->Invert();

  // Horizon point (i, j) with value h: origin + D (i sx, j sy, h HeightScale), as the mapper.
  vtkNew<vtkMatrix4x4> horizonToWorld;
  const double* hs = horizon->GetSpacing();
  const double scale[3] = { hs[0], hs[1], this->HeightScale };
  IndexToWorld(
    horizon->GetOrigin(), scale, horizon->GetDirectionMatrix()->GetData(), horizonToWorld);
  vtkNew<vtkMatrix4x4> horizonToIndex;
  vtkMatrix4x4::Multiply4x4(volumeToIndex, horizonToWorld, horizonToIndex);
  const int* he = horizon->GetExtent();

  vtkNew<vtkFloatArray> values;
  values->SetName(this->OutputArrayName.c_str());
  values->SetNumberOfTuples(points);
  const int block = this->BlockSize;
  const int blocksX = (dims[0] + block - 1) / block, blocksY = (dims[1] + block - 1) / block;
  std::vector<double> index;
  for (int by = 0; by < blocksY && !this->GetAbortExecute(); ++by)
  {
    for (int bx = 0; bx < blocksX; ++bx)
    {
      const int i0 = bx * block, i1 = std::min(dims[0], i0 + block);
      const int j0 = by * block, j1 = std::min(dims[1], j0 + block);
      // The block's points in the volume's index space, NaN for no data.
      index.assign(3 * static_cast<size_t>(i1 - i0) * (j1 - j0), NaN);
      double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
      double hi[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
      for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i)
        {
          const double h = heights->GetComponent(static_cast<vtkIdType>(j) * dims[0] + i, 0);
          if (std::isnan(h) || std::abs(h) >= 1e30 || (this->UseNullValue && h == this->NullValue))
            continue;
          const double p[3] = { double(i + he[0]), double(j + he[2]), h };
          double* x = &index[3 * (static_cast<size_t>(j - j0) * (i1 - i0) + (i - i0))];
          Apply(horizonToIndex, p, x);
          for (int c = 0; c < 3; ++c)
          {
            lo[c] = std::min(lo[c], x[c]);
            hi[c] = std::max(hi[c], x[c]);
          }
        }
      vtkImageData* source = volume;
      vtkSmartPointer<vtkImageData> pages;
      bool any = lo[0] <= hi[0];
      if (!pool.empty() && any)
      {
        // Only the pages under this block's points (one voxel of margin for the trilinear).
        int extent[6];
        for (int c = 0; c < 3 && any; ++c)
        {
          extent[2 * c] = std::max(whole[2 * c], static_cast<int>(std::floor(lo[c])) - 1);
          extent[2 * c + 1] = std::min(whole[2 * c + 1], static_cast<int>(std::ceil(hi[c])) + 1);
          any = extent[2 * c] <= extent[2 * c + 1];
        }
        if (any)
        {
          reader->UpdateExtent(extent);
          this->NumberOfPagesRead += reader->GetNumberOfPagesRead();
          pages = reader->GetOutput();
          source = pages;
        }
      }
      vtkDataArray* data =
        any ? NamedOrScalars(source, !pool.empty() ? std::string() : this->VolumeArrayName)
            : nullptr;
      if (any && !data)
      {
        vtkErrorMacro("Could not read the pages of the volume under horizon points ("
                      << i0 << ", " << j0 << ") - (" << i1 - 1 << ", " << j1 - 1 << ").");
        return 0;
      }
      for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i)
        {
          const double* x = &index[3 * (static_cast<size_t>(j - j0) * (i1 - i0) + (i - i0))];
          const double v = !any || std::isnan(x[0])
                             ? NaN
                             : strata::SampleImage(source, data, x, this->NearestNeighbor);
          values->SetValue(static_cast<vtkIdType>(j) * dims[0] + i, static_cast<float>(v));
          ++(std::isnan(v) ? this->NumberOfEmptyPoints : this->NumberOfSampledPoints);
        }
    }
    this->UpdateProgress(static_cast<double>(by + 1) / blocksY);
  }
  if (this->GetAbortExecute())
    return 0;
  output->ShallowCopy(horizon);
  output->GetPointData()->AddArray(values);
  return 1;
}

void vtkHorizonVolumeSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "HeightScale: " << this->HeightScale << "\n";
  os << indent << "HeightArrayName: " << this->HeightArrayName << "\n";
  os << indent << "NullValue: " << this->NullValue << "\n";
  os << indent << "UseNullValue: " << this->UseNullValue << "\n";
  os << indent << "VolumeArrayName: " << this->VolumeArrayName << "\n";
  os << indent << "OutputArrayName: " << this->OutputArrayName << "\n";
  os << indent << "NearestNeighbor: " << this->NearestNeighbor << "\n";
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "NumberOfSampledPoints: " << this->NumberOfSampledPoints << "\n";
  os << indent << "NumberOfEmptyPoints: " << this->NumberOfEmptyPoints << "\n";
  os << indent << "NumberOfPagesRead: " << this->NumberOfPagesRead << "\n";
}
