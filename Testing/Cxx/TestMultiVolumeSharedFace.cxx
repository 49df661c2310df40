// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "SharedFace" of the multi-volume ray caster, compared pixel by pixel with the
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

int TestMultiVolumeSharedFace(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // Two volumes sharing a face: no seam, no double counting on it.
  VolumeScene s(paths.Output);
  s.Add(Blob(30, 30, 30, 1.0, 1.0, 1.0, 0, 0, 0, 8), MakeVolumeProperty(0));
  s.Add(Blob(20, 30, 30, 1.5, 1.0, 1.0, 29, 0, 0, 9), MakeVolumeProperty(1));
  s.UseMultiVolume();
  const double pos[3] = { -30, -70, 60 }, foc[3] = { 29, 15, 15 };
  s.Camera(pos, foc);
  ok = CheckVolumeComparison(s.Compare("SharedFace"), "SharedFace", 0.4, 2, 3000);
  std::cout << "SharedFace: " << s.Mapper->GetNumberOfFragments() << " fragments\n";
  return CaseResult(ok, output);
}
