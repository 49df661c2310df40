// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataImageSampling.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace strata
{
double SampleImage(vtkImageData* image, vtkDataArray* values, const double x[3], bool nearest)
{
  const int* e = image->GetExtent();
  int base[3];
  double f[3];
  for (int c = 0; c < 3; ++c)
  {
    if (!(x[c] >= e[2 * c] - 1e-9 && x[c] <= e[2 * c + 1] + 1e-9))
      return std::numeric_limits<double>::quiet_NaN();
    if (nearest)
    {
      base[c] =
        std::min(std::max(static_cast<int>(std::floor(x[c] + 0.5)), e[2 * c]), e[2 * c + 1]);
      f[c] = 0.0;
      continue;
    }
    base[c] = std::min(
      std::max(static_cast<int>(std::floor(x[c])), e[2 * c]), std::max(e[2 * c + 1] - 1, e[2 * c]));
    f[c] = e[2 * c + 1] > e[2 * c] ? std::min(std::max(x[c] - base[c], 0.0), 1.0) : 0.0;
  }
  const vtkIdType nx = e[1] - e[0] + 1, ny = e[3] - e[2] + 1;
  double sum = 0.0;
  for (int k = 0; k < 8; ++k)
  {
    const int o[3] = { k & 1, (k >> 1) & 1, (k >> 2) & 1 };
    double w = 1.0;
    int p[3];
    for (int c = 0; c < 3; ++c)
    {
      w *= o[c] ? f[c] : 1.0 - f[c];
      p[c] = std::min(base[c] + o[c], e[2 * c + 1]);
    }
    if (w == 0.0)
      continue;
    const vtkIdType id = (vtkIdType(p[2] - e[4]) * ny + (p[1] - e[2])) * nx + (p[0] - e[0]);
    sum += w * values->GetComponent(id, 0);
  }
  return sum;
}
}
