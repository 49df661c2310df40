// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Private helpers shared by Strata's horizon-grid readers (not installed): the one definition
// of how a grid rotation becomes a direction matrix, and of what a failed read leaves behind.
#ifndef vtkStrataGridReaderUtilities_h
#define vtkStrataGridReaderUtilities_h

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
