// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Case "Shaded" of the multi-volume ray caster, compared pixel by pixel with the double-precision
// reference integrator; StrataMultiVolumeCase.h says where the bounds come from.
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "StrataMultiVolumeReferenceIntegrator.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

int TestMultiVolumeShaded(int argc, char* argv[])
{
  using namespace strata_test;
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  // Gradient shading against an analytic expectation. The field s = 2 i + j has one gradient
  // direction N everywhere; with one directional light L and a parallel camera (view V), every
  // sample's colour becomes c (ka + kd |N.L|) + ks |N.H|^p, H = (L + V) / |L + V|: the
  // reference with that colour table is the exact image, except in the outermost voxel layer,
  // where clamped lookups halve one component of the central difference and turn the normal
  // (measured: RMS 0.32, max 2.4 of 255). Bounds: RMS 0.6, max 4; a normal taken through the
  // Jacobian instead of its transpose gives RMS 25.6 here.
  VolumeScene s(paths.Output);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(32, 32, 32);
  vtkNew<vtkFloatArray> a;
  a->SetNumberOfValues(32 * 32 * 32);
  for (int k = 0; k < 32; ++k)
    for (int j = 0; j < 32; ++j)
      for (int i = 0; i < 32; ++i)
        a->SetValue((k * 32 + j) * 32 + i, float(2 * i + j));
  image->GetPointData()->SetScalars(a);
  image->SetSpacing(1.0, 1.5, 0.8); // anisotropic and turned: the normal needs the full Jacobian
  vtkNew<vtkTransform> turn;
  turn->RotateWXYZ(35, 1, 2, 0.5);
  auto prop = vtkSmartPointer<vtkVolumeProperty>::New();
  vtkNew<vtkColorTransferFunction> ctf;
  ctf->AddRGBPoint(0, 0.2, 0.4, 0.9);
  ctf->AddRGBPoint(93, 0.9, 0.5, 0.2);
  vtkNew<vtkPiecewiseFunction> pwf;
  pwf->AddPoint(0, 0.0);
  pwf->AddPoint(93, 0.12);
  prop->SetColor(ctf);
  prop->SetScalarOpacity(pwf);
  prop->SetInterpolationTypeToLinear();
  prop->ShadeOn();
  const double ka = 0.2, kd = 0.6, ks = 0.3, power = 8.0;
  prop->SetAmbient(ka);
  prop->SetDiffuse(kd);
  prop->SetSpecular(ks);
  prop->SetSpecularPower(power);
  s.Add(image, prop, turn);
  // World gradient of s = 2 i + j: R diag(1 / spacing) (2, 1, 0).
  double Nw[3] = { 2.0, 1.0 / 1.5, 0.0 };
  turn->TransformVector(Nw, Nw);
  const double nwl = std::sqrt(Nw[0] * Nw[0] + Nw[1] * Nw[1] + Nw[2] * Nw[2]);
  s.UseMultiVolume();
  s.Ren->AutomaticLightCreationOff();
  const double pos[3] = { -30, -45, 60 }, foc[3] = { 15.5, 15.5, 15.5 };
  s.Camera(pos, foc);
  s.Ren->GetActiveCamera()->ParallelProjectionOn();
  s.Ren->GetActiveCamera()->SetParallelScale(32);
  // The light halfway between the mirror image of the view about N and the view itself, so
  // that both the diffuse and the specular term are large.
  double Vc[3], Nc[3] = { Nw[0] / nwl, Nw[1] / nwl, Nw[2] / nwl };
  s.Ren->GetActiveCamera()->GetDirectionOfProjection(Vc);
  const double nv = -(Nc[0] * Vc[0] + Nc[1] * Vc[1] + Nc[2] * Vc[2]);
  double Lc[3];
  for (int c = 0; c < 3; ++c)
    Lc[c] = 2 * nv * Nc[c] + Vc[c] + 0.5 * Nc[c]; // mirror of -V, tilted towards N
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition(100 * Lc[0], 100 * Lc[1], 100 * Lc[2]);
  light->SetFocalPoint(0, 0, 0);
  s.Ren->AddLight(light);
  s.Win->Render();
  const std::string src = s.Mapper->GetShaderSource(1);
  Check(src.find("strataShade0") != std::string::npos &&
          src.find("uLightDirection") != std::string::npos,
    "a shaded volume's shader has gradient and lighting code");

  // Expected factor and specular term.
  auto unit = [](double v[3])
  {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int c = 0; c < 3; ++c)
      v[c] /= l;
  };
  double N[3] = { Nw[0], Nw[1], Nw[2] }, L[3] = { Lc[0], Lc[1], Lc[2] }, V[3];
  s.Ren->GetActiveCamera()->GetDirectionOfProjection(V);
  for (double& v : V)
    v = -v;
  unit(N);
  unit(L);
  unit(V);
  double H[3] = { L[0] + V[0], L[1] + V[1], L[2] + V[2] };
  unit(H);
  const double nl = std::abs(N[0] * L[0] + N[1] * L[1] + N[2] * L[2]);
  const double nh = std::abs(N[0] * H[0] + N[1] * H[1] + N[2] * H[2]);
  const double factor = ka + kd * nl, spec = ks * std::pow(nh, power);
  std::cout << "Shaded: |N.L| " << nl << ", |N.H| " << nh << ": colour x " << factor << " + "
            << spec << "\n";

  strata::MultiVolumeReferenceIntegrator ref;
  auto rv = ToReferenceVolume(image, s.Volumes[0]);
  for (double& c : rv.Classification.Color)
    c = c * factor + spec;
  ref.AddVolume(rv);
  s.Win->Render();
  const auto gpu = ReadRGB(s.Win);
  std::vector<double> rgba;
  ref.IntegrateImage(ClipToWorld(s.Ren)->GetData(), MultiVolumeCaseSize, MultiVolumeCaseSize, rgba);
  long covered = 0;
  for (int i = 0; i < MultiVolumeCaseSize * MultiVolumeCaseSize; ++i)
    covered += rgba[4 * i + 3] > 1.0 / 255;
  const ChannelError diff =
    ImageError(gpu, CompositeOver(rgba, std::vector<unsigned char>(gpu.size(), 0)));
  const double rms = diff.Rms, mx = diff.Max;
  std::cout << "Shaded: covered " << covered << " px, RMS " << rms << ", max " << mx << " of 255\n";
  Check(covered > 3000, "the shaded volume covers > 3000 pixels");
  Check(rms <= 0.6 && mx <= 4, "shaded image within RMS 0.6 / max 4 of the analytic expectation");
  ok = Failures() == 0;
  return CaseResult(ok, output);
}
