// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Skipping" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkImageData.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

int TestMultiVolumeSkipping(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // Empty-space skipping must not change the image: a sparse volume (two small blobs in
  // 72^3 voxels of air, and a second, rotated volume overlapping it) rendered with skipping
  // on and off, in both orders, post-classified and pre-integrated, bricked and plain. Skipping
  // on and off are two programs (FragmentKey::Skipping): within ImagePolicy::TwoProgramsMax, 1 of
  // 255 (StrataImagePolicy.h rule 2).
  VolumeScene s(paths.Output);
  const int n = 72;
  auto sparse = vtkSmartPointer<vtkImageData>::New();
  sparse->SetDimensions(n, n, n);
  sparse->AllocateScalars(VTK_FLOAT, 1);
  float* v = static_cast<float*>(sparse->GetScalarPointer());
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
      {
        const double r1 =
          std::sqrt((x - 20.0) * (x - 20.0) + (y - 50.0) * (y - 50.0) + (z - 22.0) * (z - 22.0));
        const double r2 =
          std::sqrt((x - 52.0) * (x - 52.0) + (y - 18.0) * (y - 18.0) + (z - 48.0) * (z - 48.0));
        v[x + n * (y + n * z)] =
          static_cast<float>(255.0 * std::exp(-0.006 * std::min(r1, r2) * std::min(r1, r2)));
      }
  s.Add(sparse, MakeVolumeProperty(0));
  vtkNew<vtkTransform> turn;
  turn->Translate(30, 10, 20);
  turn->RotateZ(25);
  s.Add(Blob(24, 20, 18, 1.0, 1.0, 1.0, 0, 0, 0, 2), MakeVolumeProperty(1), turn);
  s.UseMultiVolume();
  const double pos[3] = { -60, -90, 110 }, foc[3] = { 36, 36, 36 };
  s.Camera(pos, foc);
  using C = vtkMultiVolumeRayCastMapper::Classifications;
  using O = vtkMultiVolumeRayCastMapper::CompositeOrders;
  int worst = 0;
  for (C c : { C::PostClassification, C::PreIntegrated })
    for (O o : { O::FrontToBack, O::BackToFront })
      for (bool atlas : { true, false })
      {
        s.Mapper->SetClassification(c);
        s.Mapper->SetCompositeOrder(o);
        s.Mapper->SetUseBrickAtlas(atlas);
        s.Mapper->EmptySpaceSkippingOff();
        s.Win->Render();
        const auto plain = ReadRGB(s.Win);
        s.Mapper->EmptySpaceSkippingOn();
        s.Win->Render();
        const auto skipped = ReadRGB(s.Win);
        const int mx = static_cast<int>(ImageError(skipped, plain).Max);
        const long covered = static_cast<long>(
          std::count_if(plain.begin(), plain.end(), [](unsigned char c) { return c > 0; }));
        worst = std::max(worst, mx);
        const std::string what = std::string(c == C::PostClassification ? "post" : "pre") +
                                 (o == O::FrontToBack ? ", front to back" : ", back to front") +
                                 (atlas ? ", atlas" : ", plain");
        std::cout << "Skipping (" << what << "): " << covered
                  << " non-black channels; max difference " << mx << "\n";
        Check(covered > 3000 && mx <= ImagePolicy::TwoProgramsMax,
          "skipping leaves the image unchanged (" + what + ")");
      }
  const std::string src = s.Mapper->GetShaderSource(1);
  Check(
    src.find("strataEmptyUntil") != std::string::npos, "the skipping shader probes the skip grid");
  s.Mapper->EmptySpaceSkippingOff();
  s.Win->Render();
  Check(s.Mapper->GetShaderSource(1).find("uSkip") == std::string::npos,
    "skipping off: no skipping code");
  s.Mapper->EmptySpaceSkippingOn();
  s.Mapper->SetClassification(C::PostClassification);
  s.Mapper->SetCompositeOrder(O::FrontToBack);
  s.Mapper->UseBrickAtlasOn();
  ok = CheckVolumeComparison(s.Compare("Skipping"), "Skipping", 0.4, 3, 3000) && ok;
  ok = ok && Failures() == 0;
  return CaseResult(ok, output);
}
