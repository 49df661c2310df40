// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Classification" of the multi-volume ray caster, compared pixel by pixel with the
// double-precision reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkImageData.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestMultiVolumeClassification(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // Post-classification, pre-integration (full table and two-integral form) and both
  // compositing orders on two overlapping volumes, each against the reference; then a
  // transfer function with a sharp spike: pre-integration at step d must beat
  // post-classification at d / 4 (the reference integrates the spike exactly).
  using Cl = vtkMultiVolumeRayCastMapper::Classifications;
  using Or = vtkMultiVolumeRayCastMapper::CompositeOrders;
  VolumeScene s(paths.Output);
  s.Add(Blob(40, 36, 32, 1.0, 1.0, 1.0, 0, 0, 0, 1), MakeVolumeProperty(0));
  vtkNew<vtkTransform> t;
  t->Translate(30, 10, 4);
  t->RotateZ(30);
  s.Add(Blob(24, 20, 18, 1.6, 1.5, 1.4, 0, 0, 0, 2), MakeVolumeProperty(1), t);
  s.UseMultiVolume();
  const double pos[3] = { -50, -70, 80 }, foc[3] = { 30, 25, 14 };
  s.Camera(pos, foc);
  const struct
  {
    Cl Classification;
    Or Order;
    const char* Name;
  } modes[] = { { Cl::PostClassification, Or::BackToFront, "Post-BackToFront" },
    { Cl::PreIntegrated, Or::FrontToBack, "Pre-FrontToBack" },
    { Cl::PreIntegrated, Or::BackToFront, "Pre-BackToFront" },
    { Cl::PreIntegratedApproximate, Or::FrontToBack, "PreApprox-FrontToBack" } };
  for (const auto& m : modes)
  {
    s.Mapper->SetClassification(m.Classification);
    s.Mapper->SetCompositeOrder(m.Order);
    // Pre-integration reads the scalar linearly between samples: its own error (second order
    // in the step, the same as the midpoint rule) stays within the same bounds here.
    ok = CheckVolumeComparison(s.Compare(m.Name), m.Name, 0.4, 2, 3000) && ok;
  }

  // The spike: opacity 0 except a peak 1.5 wide at scalar 60.
  VolumeScene spike(paths.Output);
  auto prop = MakeVolumeProperty(2);
  vtkPiecewiseFunction* pwf = prop->GetScalarOpacity(0);
  pwf->RemoveAllPoints();
  pwf->AddPoint(0, 0.0);
  pwf->AddPoint(59.25, 0.0);
  pwf->AddPoint(60, 0.9);
  pwf->AddPoint(60.75, 0.0);
  pwf->AddPoint(100, 0.0);
  spike.Add(Blob(40, 36, 32, 1.0, 1.0, 1.0, 0, 0, 0, 3), prop);
  spike.UseMultiVolume();
  spike.Camera(pos, foc);
  spike.Mapper->SetSampleDistance(1.0);
  spike.Mapper->SetClassification(Cl::PreIntegrated);
  auto pre = spike.Compare("Spike-pre-d");
  spike.Mapper->SetSampleDistance(0.25);
  spike.Mapper->SetClassification(Cl::PostClassification);
  auto post = spike.Compare("Spike-post-d4");
  std::cout << "Spike: pre-integrated at d = 1 voxel RMS " << pre.Rms << " max " << pre.Max
            << "; post-classified at d / 4 RMS " << post.Rms << " max " << post.Max << "\n";
  if (!(pre.Rms < post.Rms) || pre.Covered < 1000)
  {
    std::cerr << "FAILED: pre-integration at d must beat post-classification at d / 4\n";
    ok = false;
  }
  return CaseResult(ok, output);
}
