// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Hard case "Inside" of the stacked height-field ray caster, compared pixel by pixel with the
// double-precision reference (StrataHeightFieldCase.h).
#include "StrataHeightFieldCase.h"
#include "StrataHeightFieldScenes.h"
#include "StrataTestPaths.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkRenderer.h"

#include <cstdlib>
#include <string>
#include <vector>

int TestHeightFieldInside(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  bool ok = true;
  // Camera inside the box, between two horizons, looking obliquely: both are visible.
  const int n = 101;
  std::vector<float> top = Field(n, n, 1, 100.0, 25.0), bottom = Field(n, n, 2, -100.0, 25.0);
  HeightFieldScene s(paths.Output,
    { MakeHorizon(n, n, 0, 0, 10, 10, 0, top), MakeHorizon(n, n, 0, 0, 10, 10, 0, bottom) });
  const double pos[3] = { 300, 500, 0 }, foc[3] = { 800, 500, 20 }, up[3] = { 0, 0, 1 };
  s.Camera(pos, foc, up);
  s.Ren->GetActiveCamera()->SetViewAngle(90);
  s.Ren->GetActiveCamera()->SetClippingRange(1.0, 3000.0);
  ok = s.Check("Inside", 25000);
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
