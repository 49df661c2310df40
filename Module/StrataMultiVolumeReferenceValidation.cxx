// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// MultiVolumeReferenceIntegrator: what a volume description must be (AddVolume's checks).
#include "StrataMultiVolumeReferenceIntegrator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace strata
{

namespace
{
// A transfer function the integrator can tabulate: null when it is, else why not.
const char* ValidateFunction(const MultiVolumeReferenceIntegrator::TransferFunction& tf)
{
  const int n = static_cast<int>(tf.Opacity.size());
  if (n < 1 || (!tf.Color.empty() && tf.Color.size() != 3 * tf.Opacity.size()))
  {
    return "transfer function needs N >= 1 opacities and 3 N colours (or none)";
  }
  if (n > 1 && !(tf.Range[1] > tf.Range[0]))
  {
    return "transfer function range must be increasing";
  }
  if (!(tf.UnitDistance > 0.0) || !std::isfinite(tf.UnitDistance))
  {
    return "unit distance must be positive";
  }
  return nullptr;
}

// The components agree with their mode: the count, a function per independent component,
// weights in [0, 1], an RGBA colour range, composite blending and no gradient opacity.
const char* ValidateComponents(const MultiVolumeReferenceIntegrator::Volume& in)
{
  using Components = MultiVolumeReferenceIntegrator::Components;
  const int nc = in.NumberOfComponents;
  const Components mode = in.ComponentMode;
  if ((mode == Components::One && nc != 1) || (mode == Components::ColorOpacity && nc != 2) ||
      (mode == Components::RGBA && nc != 4) ||
      (mode == Components::Independent && (nc < 2 || nc > 4)))
  {
    return "number of components does not fit the component mode";
  }
  if (nc > 1 && (in.BlendMode != MultiVolumeReferenceIntegrator::Blend::Composite ||
                  !in.Classification.GradientOpacity.empty()))
  {
    return "components need composite blending without gradient opacity";
  }
  if (mode == Components::Independent)
  {
    if (in.ComponentClassifications.size() != static_cast<size_t>(nc - 1))
      return "independent components need a function for each component after the first";
    for (const auto& tf : in.ComponentClassifications)
      if (const char* error = ValidateFunction(tf))
        return error;
    for (int i = 0; i < nc; ++i)
      if (!(in.ComponentWeights[i] >= 0.0 && in.ComponentWeights[i] <= 1.0))
        return "component weights must lie in [0, 1]";
  }
  for (int k = 0; mode == Components::RGBA && k < 3; ++k)
    if (!(in.ColorRange[k][1] > in.ColorRange[k][0]))
      return "RGBA colour ranges must be increasing";
  return nullptr;
}

}

// What a volume must be for the integrator: dimensions, spacing, one scalar array of the
// right size, an affine model matrix, transfer functions and components that fit; null when it
// is, else why not.
const char* MultiVolumeReferenceIntegrator::Validate(const Volume& in)
{
  size_t count = 1;
  for (int k = 0; k < 3; ++k)
  {
    if (in.Dimensions[k] < 1)
    {
      return "dimensions must be >= 1";
    }
    if (!(in.Spacing[k] > 0.0) || !std::isfinite(in.Spacing[k]))
    {
      return "spacing must be positive";
    }
    count *= static_cast<size_t>(in.Dimensions[k]);
  }
  if (in.Scalars.empty() == in.FloatScalars.empty())
  {
    return "fill exactly one of Scalars and FloatScalars";
  }
  if (const char* error = ValidateComponents(in))
  {
    return error;
  }
  if ((in.Scalars.empty() ? in.FloatScalars.size() : in.Scalars.size()) !=
      count * static_cast<size_t>(in.NumberOfComponents))
  {
    return "number of scalars does not match the dimensions";
  }
  const double* m = in.ModelMatrix;
  if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0)
  {
    return "model matrix must be affine (last row 0 0 0 1)";
  }
  return ValidateFunction(in.Classification);
}
}
