// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Single" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkMapper.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

int TestMultiVolumeSingle(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // One volume through an ordinary vtkVolume; also against VTK's own GPU ray caster at the
  // same sample distance.
  VolumeScene s(paths.Output);
  auto image = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1);
  auto prop = MakeVolumeProperty(0);
  s.Add(image, prop);
  s.UseSingleVolume();
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
  s.Camera(pos, foc);
  auto r = s.Compare("Single");
  ok = CheckVolumeComparison(r, "Single", 0.4, 2, 3000);

  // Over mid grey, as CompareVolumesWithReference.
  const auto theirs = RenderWithVtkGPUMapper(s, image, prop, vtkVolumeMapper::COMPOSITE_BLEND);
  const ChannelError diff = ImageError(r.Gpu, std::vector<double>(theirs.begin(), theirs.end()));
  const double rms = diff.Rms, mx = diff.Max;
  std::cout << "Single vs vtkGPUVolumeRayCastMapper: RMS " << rms << ", max " << mx << " of 255\n";
  // VTK samples from each ray's entry point rather than on one lattice: RMS 0.6 / max 3 allow
  // for that and its 8-bit rounding.
  if (rms > 0.6 || mx > 3)
  {
    std::cerr << "FAILED: differs from vtkGPUVolumeRayCastMapper by more than RMS 0.6 / max 3\n";
    ok = false;
  }
  return CaseResult(ok, output);
}
