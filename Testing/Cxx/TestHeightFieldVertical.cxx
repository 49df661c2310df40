// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Hard case "Vertical" of the stacked height-field ray caster, compared pixel by pixel with the
// double-precision reference (StrataHeightFieldCase.h).
#include "StrataHeightFieldCase.h"
#include "StrataHeightFieldScenes.h"
#include "StrataTestPaths.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkRenderer.h"

#include <cstdlib>
#include <string>

int TestHeightFieldVertical(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  bool ok = true;
  // Rays straight down: zero lateral direction for the centre ray, parallel projection makes
  // it zero for all of them.
  HeightFieldScene s(paths.Output, MakeDemoHorizons(81, 61));
  double c[3];
  Center(s.Images[0], c);
  const double pos[3] = { c[0], c[1], 3000 }, foc[3] = { c[0], c[1], 0 }, up[3] = { 0, 1, 0 };
  s.Camera(pos, foc, up);
  ok = s.Check("Vertical-perspective", 5000);
  s.Ren->GetActiveCamera()->ParallelProjectionOn();
  s.Ren->GetActiveCamera()->SetParallelScale(420);
  s.Ren->ResetCameraClippingRange();
  ok = s.Check("Vertical-parallel", 15000) && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
