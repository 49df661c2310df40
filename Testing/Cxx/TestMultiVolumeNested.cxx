// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Nested" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkImageData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestMultiVolumeNested(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // A fine volume inside a coarse one.
  VolumeScene s(paths.Output);
  s.Add(Blob(24, 24, 20, 2.5, 2.5, 2.5, 0, 0, 0, 5), MakeVolumeProperty(0, 2.0));
  s.Add(Blob(30, 30, 24, 0.6, 0.6, 0.6, 20, 18, 14, 6), MakeVolumeProperty(1));
  s.UseMultiVolume();
  const double pos[3] = { -50, -60, 90 }, foc[3] = { 30, 30, 24 };
  s.Camera(pos, foc);
  ok = CheckVolumeComparison(s.Compare("Nested"), "Nested", 0.4, 2, 3000);
  std::cout << "Nested: " << s.Mapper->GetNumberOfFragments() << " fragments\n";
  return CaseResult(ok, output);
}
