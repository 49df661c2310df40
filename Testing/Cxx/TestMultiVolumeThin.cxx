// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Thin" of the multi-volume ray caster, compared pixel by pixel with the double-precision
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
#include <string>

int TestMultiVolumeThin(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // A one-voxel-thin volume (nz = 1): one spacing thick, seen obliquely.
  VolumeScene s(paths.Output);
  s.Add(Blob(48, 40, 1, 1.0, 1.0, 6.0, 0, 0, 0, 10), MakeVolumeProperty(0, 1.0));
  s.UseMultiVolume();
  const double pos[3] = { -20, -50, 60 }, foc[3] = { 24, 20, 0 };
  s.Camera(pos, foc);
  ok = CheckVolumeComparison(s.Compare("Thin"), "Thin", 0.4, 2, 2000);
  return CaseResult(ok, output);
}
