// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Hard case "Holes" of the stacked height-field ray caster, compared pixel by pixel with the
// double-precision reference (StrataHeightFieldCase.h).
#include "StrataHeightFieldCase.h"
#include "StrataHeightFieldScenes.h"
#include "StrataTestPaths.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

int TestHeightFieldHoles(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  bool ok = true;
  // NaN holes and null-value (-999.25) holes in two horizons above a third.
  const int n = 101;
  std::vector<float> a = Field(n, n, 3, 80, 20), b = Field(n, n, 4, 0, 20),
                     c = Field(n, n, 6, -80, 20);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      if ((i - 30) * (i - 30) + (j - 50) * (j - 50) < 300)
        a[j * n + i] = nan;
      if (std::abs(i - j) < 6 || (i > 70 && j < 30))
        b[j * n + i] = -999.25f;
    }
  HeightFieldScene s(paths.Output,
    { MakeHorizon(n, n, 0, 0, 10, 10, 0, a),
      MakeHorizon(n, n, 0, 0, 10, 10, 0, b),
      MakeHorizon(n, n, 0, 0, 10, 10, 0, c) });
  s.Mapper->UseNullValueOn();
  s.Mapper->SetNullValue(-999.25);
  const double pos[3] = { 500, -300, 1400 }, foc[3] = { 500, 500, 0 }, up[3] = { 0, 0, 1 };
  s.Camera(pos, foc, up);
  auto r = CompareWithReference(s.Win, s.Ren, s.Actor, s.Mapper, s.Images, "Holes", paths.Output);
  ok = CheckReference(r, "Holes", 20000);
  // Rays through the holes must reach the lower horizons: ids 1 and 2 both visible.
  long seen[3] = { 0, 0, 0 };
  for (int id : r.GpuIds)
    if (id >= 0 && id < 3)
      ++seen[id];
  std::cout << "Holes: pixels per horizon " << seen[0] << " " << seen[1] << " " << seen[2] << "\n";
  if (seen[1] < 1000 || seen[2] < 100)
  {
    std::cerr << "FAILED: too few rays pass through the holes\n";
    ok = false;
  }
  if (s.Mapper->GetShaderSource().find("valid = !any(strataHoles(h))") == std::string::npos)
  {
    std::cerr << "FAILED: a stack with holes must be drawn with the hole test\n";
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
