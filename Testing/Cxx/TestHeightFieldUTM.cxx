// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Hard case "UTM" of the stacked height-field ray caster, compared pixel by pixel with the
// double-precision reference (StrataHeightFieldCase.h).
#include "StrataHeightFieldCase.h"
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataTestPaths.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestHeightFieldUTM(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  bool ok = true;
  // The same stack at the origin and at UTM scale (x = 600000, y = 6700000, 12.5 m spacing),
  // camera moved with it: the two id images must agree as well as each match the reference.
  HeightFieldScene a(paths.Output, MakeDemoHorizons(161, 121, 0, 0, 12.5, 0));
  HeightFieldScene b(paths.Output, MakeDemoHorizons(161, 121, 600000, 6700000, 12.5, 0));
  const double pos[3] = { -300, -900, 1200 }, foc[3] = { 1000, 750, -400 }, up[3] = { 0, 0, 1 };
  a.Camera(pos, foc, up);
  const double posU[3] = { 600000 - 300, 6700000 - 900, 1200 }, focU[3] = { 601000, 6700750, -400 };
  b.Camera(posU, focU, up);
  b.Ren->GetActiveCamera()->SetClippingRange(a.Ren->GetActiveCamera()->GetClippingRange());
  auto ra =
    CompareWithReference(a.Win, a.Ren, a.Actor, a.Mapper, a.Images, "UTM-origin", paths.Output);
  auto rb =
    CompareWithReference(b.Win, b.Ren, b.Actor, b.Mapper, b.Images, "UTM-utm", paths.Output);
  ok = CheckReference(ra, "UTM-origin", 20000);
  ok = CheckReference(rb, "UTM-utm", 20000) && ok;
  const auto same = CompareIds(ra.GpuIds, rb.GpuIds, 200, 160);
  std::cout << "UTM vs origin: " << same.Mismatched << " of " << same.Covered << " pixels differ\n";
  if (same.MismatchFraction() > 0.001 || same.WideRegion)
  {
    std::cerr << "FAILED: the UTM-scale image differs from the one at the origin\n";
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
