// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Two" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include <cstdlib>

int TestMultiVolumeTwo(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  // Two overlapping volumes of different resolution and spacing, the second turned 30 degrees
  // about z (RenderTwoVolumes).
  const bool ok =
    CheckVolumeComparison(RenderTwoVolumes(0, 0, "Two", paths.Output), "Two", 0.4, 2, 3000);
  return CaseResult(ok, output);
}
