// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The demo scene (StrataDemoScene: three crossing horizons with holes, a well as a tube and a
// target sphere cut by the top horizon), at 200 x 150 pixels:
//  1. the horizons alone against the double-precision reference (ids and depth, the issue's
//     bounds: <= 0.5 % of covered pixels, no wrong region wider than one pixel);
//  2. occlusion between horizons and ordinary VTK geometry: the scene drawn whole must equal,
//     pixel by pixel, the nearer of the horizons drawn alone and the geometry drawn alone, in
//     depth and in colour; both orders (geometry in front, horizons in front) must occur;
//  3. the whole scene against a baseline image (vtkTesting, threshold stated below).
#include "StrataDemoScene.h"
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataRegressionImage.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "vtkActor.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>

int TestHeightFieldDemo(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  using namespace strata_test;
  auto* output = CapturingOutputWindow::Install();
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  const int w = 200, h = 150;
  MakeWindow(win, ren, w, h);
  DemoScene scene = AddDemoScene(ren);

  // 1. Horizons alone against the reference (on black: the id image reads colour as ids).
  scene.Well->VisibilityOff();
  scene.Target->VisibilityOff();
  ren->GradientBackgroundOff();
  double background[3];
  ren->GetBackground(background);
  ren->SetBackground(0, 0, 0);
  auto r =
    CompareWithReference(win, ren, scene.Stack, scene.Mapper, scene.Horizons, "Demo", paths.Output);
  Check(CheckReference(r, "Demo", 15000), "demo horizons against the reference");
  ren->SetBackground(background);
  ren->GradientBackgroundOn();

  // 2. Occlusion. (a) Compositing: the whole scene must equal, pixel by pixel, the nearer of the
  // horizons drawn alone and the geometry drawn alone (bit-identical depth, same colour), except
  // where the two depths tie within `tie`. (b) Truth: which side is nearer is decided with the
  // reference's exact hit depth, not the mapper's, so a gl_FragDepth that is consistently wrong
  // fails too; pixels within `margin` of a tie (the float bound of CompareWithReference) are
  // left out. The three frames draw each pixel by the same programs (the horizons' and VTK's
  // geometry's, whatever else is visible): bit-exact, ImagePolicy::SameProgramMax
  // (StrataImagePolicy.h rule 1).
  win->Render();
  const auto depthH = ReadDepth(win);
  const auto rgbH = ReadRGB(win);
  scene.Stack->VisibilityOff();
  scene.Well->VisibilityOn();
  scene.Target->VisibilityOn();
  win->Render();
  const auto depthG = ReadDepth(win);
  const auto rgbG = ReadRGB(win);
  scene.Stack->VisibilityOn();
  win->Render();
  const auto depthB = ReadDepth(win);
  const auto rgbB = ReadRGB(win);
  const float tie = 1e-6f;
  const double margin = 1e-5;
  auto sameColour = [&](const std::vector<unsigned char>& a, int i)
  {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(a[3 * i + c]) - int(rgbB[3 * i + c])));
    return worst <= ImagePolicy::SameProgramMax;
  };
  long geometryInFront = 0, horizonsInFront = 0, ties = 0, wrong = 0, wrongTruth = 0;
  for (int i = 0; i < w * h; ++i)
  {
    const float dh = depthH[i], dg = depthG[i];
    if (std::abs(dh - dg) > tie)
    {
      const bool geometry = dg < dh;
      if (depthB[i] != std::min(dh, dg) || !sameColour(geometry ? rgbG : rgbH, i))
      {
        ++wrong;
      }
    }
    else
    {
      ties += dh < 1.0f;
    }
    const double dRef = r.RefDepth[i];
    if (dRef < 1.0 && dg < 1.0f && std::abs(dRef - dg) > margin)
    {
      const bool geometry = dg < dRef;
      (geometry ? geometryInFront : horizonsInFront)++;
      wrongTruth += !sameColour(geometry ? rgbG : rgbH, i);
    }
  }
  std::cout << "Occlusion: geometry in front of horizons " << geometryInFront
            << " px, horizons in front of geometry " << horizonsInFront
            << " px (by reference depth), ties " << ties
            << ", pixels not the nearer of the two frames " << wrong
            << ", pixels showing the side the reference says is hidden " << wrongTruth << "\n";
  Check(geometryInFront >= 300, "the well or target is in front of a horizon in >= 300 pixels");
  Check(horizonsInFront >= 300, "a horizon hides the well or target in >= 300 pixels");
  Check(wrong == 0, "every pixel of the scene is the nearer of horizons and geometry");
  Check(wrongTruth <= 2, "at most 2 pixels show the side that the reference depth says is hidden");

  // 3. Baseline. Threshold 0.5 of vtkImageDifference's thresholded error (VTK's default is 10):
  // llvmpipe renders this scene bit for bit the same run to run; the slack covers other Mesa
  // builds' rounding of the shading, while a horizon, the tube or the sphere moved by a pixel
  // along its silhouette, or a change of colour map or lighting, exceeds it.
  Check(CompareWithBaseline(argc, argv, win, "TestHeightFieldDemo", 0.5), "regression image");

  Check(output->Errors == 0 && output->Warnings == 0, "no VTK errors or warnings");
  return Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}
