// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Hard case "Rotated" of the stacked height-field ray caster, compared pixel by pixel with the
// double-precision reference (StrataHeightFieldCase.h).
#include "StrataHeightFieldCase.h"
#include "StrataHeightFieldScenes.h"
#include "StrataTestPaths.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkRenderer.h"

#include <cstdlib>
#include <string>

int TestHeightFieldRotated(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  bool ok = true;
  // The demo stack on a grid rotated by 140 degrees, viewed obliquely.
  HeightFieldScene s(paths.Output, MakeDemoHorizons(121, 91, 5000, 2000, 12.5, 140.0));
  double b[6];
  s.Mapper->GetBounds(b);
  const double c[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), -420 };
  const double pos[3] = { c[0] + 900, c[1] - 1500, 1200 }, up[3] = { 0, 0, 1 };
  s.Camera(pos, c, up);
  ok = s.Check("Rotated", 15000);
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
