// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkStackedHeightFieldMapper::SetRegion, as sort-last parallel rendering uses it: the demo
// stack (UTM coordinates, 1.5x in z) cut by a vertical plane through its middle into two boxes,
// each drawn alone over transparent black, blended front box over back box, equals the whole
// stack drawn at once. The surfaces are opaque, so a pixel is its first hit's colour: in the
// front box where the ray hits there, else in the back box. Each box searches its part of the ray
// only, so the linear search's samples, and the bisection refining a hit, start elsewhere: a hit
// may move within the refinement's tolerance and its shading by a unit of 255. Bound: no channel
// more than 2 of 255 off, and at most 0.5% of the covered pixels off by more than 1 (a pixel
// whose first hit lies in the other box would be off by the whole colour difference). Blended in
// the wrong order the boxes differ on far more pixels (asserted: over 200), so it can fail.
// Measured: identical (max 0); the wrong order 1978 pixels.
#include "StrataDemoScene.h"
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataTestHelpers.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <vector>

int TestHeightFieldRegion(int, char*[])
{
  using namespace strata_test;
  auto* output = CapturingOutputWindow::Install();
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  MakeWindow(win, ren, 200, 150);
  win->SetAlphaBitPlanes(1);
  DemoScene scene = AddDemoScene(ren);
  scene.Well->VisibilityOff();
  scene.Target->VisibilityOff();
  ren->GradientBackgroundOff();
  ren->SetBackground(0, 0, 0);
  ren->SetBackgroundAlpha(0.0);
  const std::vector<float> whole = RenderRGBA(win);
  double b[6];
  scene.Stack->GetBounds(b);
  const double mid = 0.5 * (b[0] + b[1]), big = 1e9;
  const double west[6] = { -big, mid, -big, big, -big, big };
  const double east[6] = { mid, big, -big, big, -big, big };
  const bool westInFront = ren->GetActiveCamera()->GetPosition()[0] < mid;
  scene.Mapper->SetRegion(west);
  const std::vector<float> w = RenderRGBA(win);
  scene.Mapper->SetRegion(east);
  const std::vector<float> e = RenderRGBA(win);
  scene.Mapper->RemoveRegion();

  long covered = 0, coveredWest = 0, coveredEast = 0;
  for (size_t p = 3; p < whole.size(); p += 4)
  {
    covered += whole[p] > 0.5f ? 1 : 0;
    coveredWest += w[p] > 0.5f ? 1 : 0;
    coveredEast += e[p] > 0.5f ? 1 : 0;
  }
  std::cout << "covered pixels: whole " << covered << ", west box " << coveredWest << ", east box "
            << coveredEast << "; the " << (westInFront ? "west" : "east") << " box is in front\n";
  Check(coveredWest > 1000 && coveredEast > 1000 && coveredWest < covered && coveredEast < covered,
    "both boxes draw part of the stack");
  const OverDifference right = westInFront ? CompareOver(w, e, whole) : CompareOver(e, w, whole);
  const OverDifference wrong = westInFront ? CompareOver(e, w, whole) : CompareOver(w, e, whole);
  std::cout << "in order: max " << right.Max << " of 255, " << right.Off
            << " pixels off by more than 1; wrong order: " << wrong.Off << " pixels\n";
  Check(right.Max <= 2.0 && right.Off <= covered / 200,
    "the two boxes blended in order equal the whole stack (2 of 255, 0.5% of pixels above 1)");
  Check(wrong.Off > 200, "blended in the wrong order they do not (over 200 pixels)");
  if (output->Errors || output->Warnings)
    Check(false, "VTK printed no errors or warnings");
  return Failures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
