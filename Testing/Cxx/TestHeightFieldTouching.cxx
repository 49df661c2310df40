// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Hard case "Touching" of the stacked height-field ray caster, compared pixel by pixel with the
// double-precision reference (StrataHeightFieldCase.h).
#include "StrataHeightFieldCase.h"
#include "StrataHeightFieldScenes.h"
#include "StrataTestPaths.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

int TestHeightFieldTouching(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  bool ok = true;
  // Two horizons equal over the left third, touching at one point on the right, apart elsewhere.
  const int n = 97;
  std::vector<float> a(n * n), b(n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      const double base = 30.0 * FractalNoise(i * 0.05, j * 0.05, 9, 4);
      const double dx = i - 72.0, dy = j - 48.0;
      const double gap = i < 32 ? 0.0 : std::min(40.0, 0.02 * (dx * dx + dy * dy));
      a[j * n + i] = static_cast<float>(base);
      b[j * n + i] = static_cast<float>(base - gap);
    }
  HeightFieldScene s(
    paths.Output, { MakeHorizon(n, n, 0, 0, 10, 10, 0, a), MakeHorizon(n, n, 0, 0, 10, 10, 0, b) });
  const double pos[3] = { 480, -700, 900 }, foc[3] = { 480, 480, -10 }, up[3] = { 0, 0, 1 };
  s.Camera(pos, foc, up);
  ok = s.Check("Touching-above", 15000);
  const double below[3] = { 480, -700, -900 };
  s.Camera(below, foc, up);
  ok = s.Check("Touching-below", 15000) && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
