// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Coincident" of the multi-volume ray caster, compared pixel by pixel with the
// double-precision reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
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

int TestMultiVolumeCoincident(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // Two identical coincident volumes: one fragment covered by both; the media add up.
  VolumeScene s(paths.Output);
  auto image = Blob(36, 32, 28, 1.0, 1.0, 1.0, 0, 0, 0, 7);
  s.Add(image, MakeVolumeProperty(0));
  s.Add(image, MakeVolumeProperty(1));
  s.UseMultiVolume();
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 18, 16, 14 };
  s.Camera(pos, foc);
  ok = CheckVolumeComparison(s.Compare("Coincident"), "Coincident", 0.4, 2, 3000);
  std::cout << "Coincident: " << s.Mapper->GetNumberOfFragments() << " fragments\n";
  if (s.Mapper->GetNumberOfFragments() != 1)
  {
    std::cerr << "FAILED: two coincident volumes must make one fragment\n";
    ok = false;
  }
  return CaseResult(ok, output);
}
