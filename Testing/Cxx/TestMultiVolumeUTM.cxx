// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "UTM" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>

int TestMultiVolumeUTM(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  // The scene of TestMultiVolumeTwo (RenderTwoVolumes) near the origin and at x = 6e5,
  // y = 6.7e6: both against the reference, and the two images against each other.
  auto a = RenderTwoVolumes(0, 0, "UTM-origin", paths.Output);
  bool ok = CheckVolumeComparison(a, "UTM-origin", 0.4, 2, 3000);
  auto b = RenderTwoVolumes(600000, 6700000, "UTM-utm", paths.Output);
  ok = CheckVolumeComparison(b, "UTM-utm", 0.4, 2, 3000) && ok;
  long differ = 0;
  int mx = 0;
  for (size_t i = 0; i < a.Gpu.size(); ++i)
  {
    const int d = std::abs(int(a.Gpu[i]) - int(b.Gpu[i]));
    differ += d > 1;
    mx = std::max(mx, d);
  }
  std::cout << "UTM vs origin: " << differ << " channel values differ by more than 1, max " << mx
            << "\n";
  if (differ > 0)
  {
    std::cerr << "FAILED: the UTM-scale image differs from the one at the origin\n";
    ok = false;
  }
  return CaseResult(ok, output);
}
