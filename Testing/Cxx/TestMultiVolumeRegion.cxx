// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkMultiVolumeRayCastMapper::SetRegion, as sort-last parallel rendering uses it: two
// overlapping volumes cut by the plane x = 20 (through both) into two boxes, each rendered alone
// as premultiplied RGBA over transparent black, blended front box over back box in float, equal
// the whole scene rendered at once. Bound: 2.5 of 255 per channel. The window is 8-bit RGBA: the
// front box's colour and opacity (times the back's colour) and the back box's colour are each
// rounded by up to 0.5, the whole image too, 2 in all; 0.5 more for the one lattice step that
// crosses the face, split there in two (as one rendering splits steps at every BSP face; at a
// sample distance of 1/4 voxel far less). Measured: 1.56. Blended in the wrong order the two
// boxes are off by far more (asserted above 10 of 255: 39), so the bound can fail.
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace
{
long Covered(const std::vector<float>& rgba)
{
  long n = 0;
  for (size_t p = 3; p < rgba.size(); p += 4)
    n += rgba[p] > 0.05f ? 1 : 0;
  return n;
}
}

int TestMultiVolumeRegion(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  VolumeScene s(paths.Output);
  s.Win->SetAlphaBitPlanes(1);
  s.Ren->SetBackgroundAlpha(0.0);
  s.Add(Blob(30, 30, 30, 1.0, 1.0, 1.0, 0, 0, 0, 8), MakeVolumeProperty(0));
  s.Add(Blob(20, 30, 30, 1.5, 1.0, 1.0, 15, 0, 0, 9), MakeVolumeProperty(1));
  s.UseMultiVolume();
  const double pos[3] = { -30, -70, 60 }, foc[3] = { 29, 15, 15 };
  s.Camera(pos, foc); // the eye at x < 20: the box x <= 20 is in front
  const std::vector<float> whole = RenderRGBA(s.Win);
  const double near[6] = { -1e3, 20.0, -1e3, 1e3, -1e3, 1e3 };
  const double far[6] = { 20.0, 1e3, -1e3, 1e3, -1e3, 1e3 };
  s.Mapper->SetRegion(near);
  const std::vector<float> front = RenderRGBA(s.Win);
  const int frontFragments = s.Mapper->GetNumberOfFragments();
  s.Mapper->SetRegion(far);
  const std::vector<float> back = RenderRGBA(s.Win);
  s.Mapper->RemoveRegion();
  const int allFragments = (RenderRGBA(s.Win), s.Mapper->GetNumberOfFragments());

  const long cw = Covered(whole), cf = Covered(front), cb = Covered(back);
  std::cout << "covered pixels: whole " << cw << ", front box " << cf << ", back box " << cb
            << "; fragments drawn: " << frontFragments << " of " << allFragments << "\n";
  Check(cf > 1000 && cb > 1000 && cf < cw && cb < cw, "both boxes draw part of the scene");
  const double error = CompareOver(front, back, whole).Max,
               wrong = CompareOver(back, front, whole).Max;
  std::cout << "front over back vs whole: max " << error << " of 255; back over front: max "
            << wrong << "\n";
  Check(error <= 2.5, "the two boxes blended in order equal the whole scene (2.5 of 255)");
  Check(wrong > 10.0, "blended in the wrong order they do not (above 10 of 255)");
  return CaseResult(Failures() == 0, output);
}
