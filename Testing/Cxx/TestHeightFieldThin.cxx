// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Hard case "Thin" of the stacked height-field ray caster, compared pixel by pixel with the
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

int TestHeightFieldThin(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  bool ok = true;
  // 1 x N and N x 1 grids: drawn as ribbons one spacing wide.
  const int n = 60;
  std::vector<float> line(n);
  for (int i = 0; i < n; ++i)
    line[i] = static_cast<float>(20.0 * std::sin(i * 0.2));
  HeightFieldScene sx(paths.Output, { MakeHorizon(1, n, 0, 0, 25, 10, 0, line) });
  const double pos[3] = { 300, -250, 400 }, foc[3] = { 0, 300, 0 }, up[3] = { 0, 0, 1 };
  sx.Camera(pos, foc, up);
  ok = sx.Check("Thin-1xN", 300);
  HeightFieldScene sy(paths.Output, { MakeHorizon(n, 1, 0, 0, 10, 25, 0, line) });
  const double pos2[3] = { 300, -400, 300 }, foc2[3] = { 300, 0, 0 };
  sy.Camera(pos2, foc2, up);
  ok = sy.Check("Thin-Nx1", 300) && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
