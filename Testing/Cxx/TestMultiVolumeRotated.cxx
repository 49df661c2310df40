// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Rotated" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <cstdlib>
#include <string>

int TestMultiVolumeRotated(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // Rotation through the image's direction matrix and the prop's transform together.
  VolumeScene s(paths.Output);
  auto image = Blob(40, 30, 26, 1.0, 1.2, 0.8, 5, -3, 2, 1);
  const double c = std::cos(0.6), sn = std::sin(0.6);
  const double dir[9] = { c, 0, sn, 0, 1, 0, -sn, 0, c };
  image->SetDirectionMatrix(dir);
  vtkNew<vtkTransform> t;
  t->RotateWXYZ(50, 0.3, 0.2, 1.0);
  s.Add(image, MakeVolumeProperty(2, 0.5), t);
  s.UseMultiVolume();
  const double pos[3] = { -60, -60, 60 }, foc[3] = { 10, 10, 10 };
  s.Camera(pos, foc);
  ok = CheckVolumeComparison(s.Compare("Rotated"), "Rotated", 0.4, 2, 1000);
  return CaseResult(ok, output);
}
