// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Hard case "AxisParallel" of the stacked height-field ray caster, compared pixel by pixel with the
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

int TestHeightFieldAxisParallel(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  bool ok = true;
  // Parallel projection along +x and then +y, tilted down 30 degrees: every ray has an exactly
  // zero lateral component across the other axis.
  HeightFieldScene s(paths.Output, MakeDemoHorizons(81, 61));
  s.Ren->GetActiveCamera()->ParallelProjectionOn();
  double c[3];
  Center(s.Images[0], c);
  const double foc[3] = { c[0], c[1], -420 }, up[3] = { 0, 0, 1 };
  const double posX[3] = { c[0] - 2000, c[1], -420 + 2000 * std::tan(0.5236) };
  s.Camera(posX, foc, up);
  s.Ren->GetActiveCamera()->SetParallelScale(300);
  s.Ren->ResetCameraClippingRange();
  ok = s.Check("AxisParallel-x", 10000);
  const double posY[3] = { c[0], c[1] - 2000, -420 + 2000 * std::tan(0.5236) };
  s.Camera(posY, foc, up);
  s.Ren->ResetCameraClippingRange();
  ok = s.Check("AxisParallel-y", 10000) && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
