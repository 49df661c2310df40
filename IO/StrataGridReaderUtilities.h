// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Private helpers shared by Strata's horizon-grid readers (not installed): the one definition
// of how a grid rotation becomes a direction matrix, of the grid information every reader
// reports, and of what a failed read leaves behind.
#ifndef StrataGridReaderUtilities_h
#define StrataGridReaderUtilities_h

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>

namespace strata_io
{
/// A rotation about z by `degrees` (counterclockwise), row-major, as vtkImageData's direction
/// matrix: its columns are the world directions of the i and j axes. Multiples of 90 degrees are
/// made exact so an unrotated grid gets an exact identity.
inline void RotationToDirection(double degrees, double d[9])
{
  double c = 0.0;
  double s = 0.0;
  const double quarterTurns = degrees / 90.0;
  if (quarterTurns == std::floor(quarterTurns) && std::fabs(quarterTurns) < 1e9)
  {
    const long long k = ((static_cast<long long>(quarterTurns) % 4) + 4) % 4;
    const double cs[4][2] = { { 1, 0 }, { 0, 1 }, { -1, 0 }, { 0, -1 } };
    c = cs[k][0];
    s = cs[k][1];
  }
  else
  {
    const double a = vtkMath::RadiansFromDegrees(degrees);
    c = std::cos(a);
    s = std::sin(a);
  }
  const double m[9] = { c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0 };
  std::copy(m, m + 9, d);
}

/// Reports an nx x ny grid with the given lateral origin, spacing and rotation (degrees) and
/// scalar type to the pipeline, as every horizon reader's RequestInformation does.
inline void SetGridInformation(vtkInformation* outInfo,
  int nx,
  int ny,
  const double origin[2],
  const double spacing[2],
  double rotationDegrees,
  int scalarType)
{
  const int extent[6] = { 0, nx - 1, 0, ny - 1, 0, 0 };
  const double origin3[3] = { origin[0], origin[1], 0.0 };
  const double spacing3[3] = { spacing[0], spacing[1], 1.0 };
  double direction[9];
  RotationToDirection(rotationDegrees, direction);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin3, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing3, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), direction, 9);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, scalarType, 1);
}

/// Gives `output` the same grid geometry that SetGridInformation() reported.
inline void SetGridGeometry(vtkImageData* output,
  int nx,
  int ny,
  const double origin[2],
  const double spacing[2],
  double rotationDegrees)
{
  double direction[9];
  RotationToDirection(rotationDegrees, direction);
  output->SetExtent(0, nx - 1, 0, ny - 1, 0, 0);
  output->SetOrigin(origin[0], origin[1], 0.0);
  output->SetSpacing(spacing[0], spacing[1], 1.0);
  output->SetDirectionMatrix(direction);
}

/// Leaves the output with no points and the pipeline with an empty extent.
inline void ClearOutput(vtkInformation* outInfo)
{
  if (!outInfo)
  {
    return;
  }
  const int empty[6] = { 0, -1, 0, -1, 0, -1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
  if (vtkImageData* output = vtkImageData::GetData(outInfo))
  {
    output->Initialize();
  }
}
}

#endif
