// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @file    StrataImageSampling.h
 * @brief   A value of an image at a continuous index: trilinear or nearest, in double.
 *
 * The double-precision sampling that the horizon sampler (IO) and the picker (Rendering)
 * share, so that a value picked on screen and a value draped on a horizon agree.
 */
#ifndef StrataImageSampling_h
#define StrataImageSampling_h

#include "StrataCoreModule.h" // For export macro

class vtkDataArray;
class vtkImageData;

namespace strata
{
/**
 * Component 0 of `values` (point data of `image`) at the continuous structured index `x`
 * (the image's extent, not from 0), trilinear (`nearest` false) or of the nearest point.
 * Axes of one point sample that point. NaN outside the extent (1e-9 of an index beyond it
 * counts as inside).
 */
STRATACORE_EXPORT double SampleImage(vtkImageData* image,
  vtkDataArray* values,
  const double x[3],
  bool nearest);
}

#endif
