// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Hard case "Grazing" of the stacked height-field ray caster, compared pixel by pixel with the
// double-precision reference (StrataHeightFieldCase.h).
#include "StrataHeightFieldCase.h"
#include "StrataHeightFieldScenes.h"
#include "StrataTestPaths.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

int TestHeightFieldGrazing(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  bool ok = true;
  // Camera 1 degree above the mean plane of a gently rolling horizon, looking across it.
  const int n = 129;
  std::vector<float> h = Field(n, n, 5, 0.0, 6.0);
  HeightFieldScene s(paths.Output, { MakeHorizon(n, n, 0, 0, 10, 10, 0, h) });
  const double pos[3] = { -200, 640, 20 + 1200 * std::tan(std::acos(-1.0) / 180.0) };
  const double foc[3] = { 1000, 640, 20 }, up[3] = { 0, 0, 1 };
  s.Camera(pos, foc, up);
  ok = s.Check("Grazing", 3000);
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
