// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Atlas" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
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

int TestMultiVolumeAtlas(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // The brick atlas against plain 3-D textures, and its bookkeeping. 40 x 36 x 32 voxels in
  // bricks of 16 (stride 15): 3 x 3 x 3 level-0 bricks; with room for all, the image must equal
  // the unbricked one (same voxels, same trilinear filtering: the shared voxel layer makes
  // brick borders invisible) within ImagePolicy::TwoProgramsMax, 1 of 255: the atlas and the
  // plain texture are two programs (FragmentKey::Atlas), StrataImagePolicy.h rule 2; measured 1
  // on an H200. A budget of 4 bricks forces coarser levels: still every brick within the budget
  // and an image close to the full-resolution one.
  VolumeScene s(paths.Output);
  s.Add(Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1), MakeVolumeProperty(0));
  s.UseMultiVolume();
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
  s.Camera(pos, foc);
  s.Mapper->SetBrickSize(16);
  s.Mapper->UseBrickAtlasOff();
  s.Win->Render();
  const auto plain = ReadRGB(s.Win);
  s.Mapper->UseBrickAtlasOn();
  s.Win->Render();
  const auto bricked = ReadRGB(s.Win);
  const int mx = static_cast<int>(ImageError(bricked, plain).Max);
  std::cout << "Atlas: " << s.Mapper->GetNumberOfResidentBricks() << " resident bricks of "
            << s.Mapper->GetNumberOfAtlasSlots() << " slots; max difference to plain textures "
            << mx << "\n";
  Check(mx <= ImagePolicy::TwoProgramsMax,
    "the bricked image equals the plain one (max difference <= 1)");
  Check(s.Mapper->GetNumberOfResidentBricks() > 0 && s.Mapper->GetNumberOfResidentBricks() <= 27,
    "at most the 27 level-0 bricks are resident, transparent ones not at all");
  ok = CheckVolumeComparison(s.Compare("Atlas"), "Atlas", 0.4, 2, 3000) && ok;

  // Budget of 4 bricks: 16^3 floats are 16 KiB, so 0.0625 MiB.
  s.Mapper->SetAtlasBudget(4 * 16.0 * 16 * 16 * 4 / (1024.0 * 1024.0));
  s.Win->Render();
  const auto coarse = ReadRGB(s.Win);
  const double coarseRms = ImageError(coarse, plain).Rms;
  std::cout << "Atlas with 4 slots: " << s.Mapper->GetNumberOfResidentBricks()
            << " resident; RMS to full resolution " << coarseRms << "\n";
  Check(s.Mapper->GetNumberOfAtlasSlots() == 4 && s.Mapper->GetNumberOfResidentBricks() <= 4,
    "a 4-brick budget gives 4 slots and at most 4 resident bricks");
  Check(coarseRms < 8.0, "coarser levels stay close to the full-resolution image (RMS < 8)");
  ok = ok && Failures() == 0;
  return CaseResult(ok, output);
}
