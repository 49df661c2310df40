// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Demo" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataMultiVolumeCase.h"
#include "StrataRegressionImage.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkImageData.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTesting.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cstdlib>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

int TestMultiVolumeDemo(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  using namespace strata_test;
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // The demo's scene (StrataVolumeScenes): the Bucky ball and two analytic volumes, against
  // the reference and a baseline image.
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  MakeWindow(win, ren, 160, 120);
  std::vector<std::pair<vtkSmartPointer<vtkImageData>, vtkSmartPointer<vtkVolume>>> inputs;
  auto multi = AddVolumeDemoScene(ren, paths.Data, inputs);
  if (!multi)
  {
    return EXIT_FAILURE;
  }
  std::vector<std::pair<vtkImageData*, vtkVolume*>> list;
  for (auto& p : inputs)
    list.emplace_back(p.first, p.second);
  ok =
    CheckVolumeComparison(CompareVolumesWithReference(win, ren, list, "VolumeDemo", paths.Output),
      "VolumeDemo",
      0.4,
      2,
      4000);
  auto* mapper = vtkMultiVolumeRayCastMapper::SafeDownCast(multi->GetMapper());
  std::cout << "VolumeDemo: " << mapper->GetNumberOfFragments() << " fragments\n";
  // Baseline: same thresholds as TestHeightFieldDemo (vtkTesting 0.5, and at most 0.2 % of
  // pixels off by more than 24/255).
  ok = CompareWithBaseline(argc, argv, win, "TestMultiVolumeDemo", 0.5) && ok;
  return CaseResult(ok, output);
}
