// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Geometry" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "StrataMultiVolumeReferenceIntegrator.h"
#include "vtkActor.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

int TestMultiVolumeGeometry(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // An opaque sphere inside a volume: rays stop at the scene's depth. Expected pixel:
  // C + (1 - A) scene, with (C, A) the reference integrated up to the depth of the scene
  // rendered without the volume, and `scene` that render's colour.
  VolumeScene s(paths.Output);
  auto image = Blob(40, 36, 32, 1.0, 1.0, 1.0, 0, 0, 0, 1);
  s.Add(image, MakeVolumeProperty(0, 0.5));
  s.UseMultiVolume();
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 18, 16 };
  s.Camera(pos, foc);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(22, 16, 14);
  sphere->SetRadius(9);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> sm;
  sm->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> ball;
  ball->SetMapper(sm);
  ball->GetProperty()->SetColor(0.9, 0.9, 0.9);
  s.Ren->AddActor(ball);
  s.Ren->SetBackground(128 / 255.0, 128 / 255.0, 128 / 255.0);
  s.Multi->VisibilityOff();
  s.Win->Render();
  const auto sceneRgb = ReadRGB(s.Win);
  const auto sceneDepth = ReadDepth(s.Win);
  s.Multi->VisibilityOn();
  s.Win->Render();
  const auto gpu = ReadRGB(s.Win);
  strata::MultiVolumeReferenceIntegrator ref;
  ref.AddVolume(ToReferenceVolume(image, s.Volumes[0]));
  std::vector<double> stop(sceneDepth.begin(), sceneDepth.end()), rgba;
  ref.IntegrateImage(ClipToWorld(s.Ren)->GetData(),
    MultiVolumeCaseSize,
    MultiVolumeCaseSize,
    rgba,
    nullptr,
    stop.data());
  long hidden = 0;
  for (int i = 0; i < MultiVolumeCaseSize * MultiVolumeCaseSize; ++i)
    hidden += sceneDepth[i] < 1.0f && rgba[4 * i + 3] > 0.05;
  const ChannelError diff = ImageError(gpu, CompositeOver(rgba, sceneRgb));
  const double rms = diff.Rms, mx = diff.Max;
  std::cout << "Geometry: " << hidden << " sphere pixels behind > 5 % volume opacity; RMS " << rms
            << ", max " << mx << " of 255\n";
  Check(hidden > 200, "the sphere is partly inside the volume (> 200 pixels behind some of it)");
  // The sphere's own 8-bit colour enters twice (scene and expected): bound one step more.
  Check(rms <= 0.5 && mx <= 3,
    "volume over geometry within RMS 0.5 / max 3 of the reference stopped at the scene depth");
  ok = Failures() == 0;
  return CaseResult(ok, output);
}
