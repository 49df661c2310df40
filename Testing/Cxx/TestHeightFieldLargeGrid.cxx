// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Hard case "LargeGrid" of the stacked height-field ray caster, compared pixel by pixel with the
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

int TestHeightFieldLargeGrid(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  bool ok = true;
  // A 2048 x 1536 grid (thousands of cells along each ray) seen from far away: the traversal
  // must advance by whole nodes and cells however coarse the float rounding of t is there.
  // A walk that re-derived its node from positions stalled here and left streaks of misses.
  HeightFieldScene s(paths.Output, MakeDemoHorizons(2048, 1536, 0, 0, 2000.0 / 2048, 0));
  s.Mapper->SetTileSize(64);
  const double a = 0.6 + 2.2, cx = 1000, cy = 750;
  const double pos[3] = { cx - 2200 * std::cos(a), cy - 2200 * std::sin(a), 1200 };
  const double foc[3] = { cx, cy, -420 }, up[3] = { 0, 0, 1 };
  s.Camera(pos, foc, up);
  ok = s.Check("LargeGrid", 15000);
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
