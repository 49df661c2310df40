// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Gradient opacity per volume (vtkVolumeProperty::SetGradientOpacity): one volume with it, and two
// overlapping volumes of which only one has it, compared pixel by pixel with the double-precision
// reference integrator (the same gradient: central differences one voxel apart, to world units);
// only the volume that has it carries its code; and the same volume paged from a pool.
//
// Bounds, in 8-bit units: the composite cases' RMS 0.4 / max 2 (StrataMultiVolumeCase.h) plus
// the gradient opacity table's resolution (256 entries, linear, against the reference's exact
// function of the same 256 entries: none) and the float gradient (six fetches a sample, rounding
// to 1e-6 of the scalar range): RMS 0.5, max 3. The function below (0 at |grad s| = 0 to 1 at 10
// per unit; the blobs' flanks reach about 9) thins every blob towards its core: ignoring it
// changes the image by RMS 3.7 (measured; checked to be above 2), seven times the bound.
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataMultiVolumeCase.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkImageData.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
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

namespace
{
using namespace strata_test;

vtkSmartPointer<vtkVolumeProperty> WithGradientOpacity(int variant)
{
  auto p = MakeVolumeProperty(variant);
  vtkNew<vtkPiecewiseFunction> go;
  go->AddPoint(0.0, 0.0);
  go->AddPoint(10.0, 1.0);
  p->SetGradientOpacity(go);
  return p;
}

void Single(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  auto prop = MakeVolumeProperty(0);
  s.Add(Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1), prop);
  s.UseSingleVolume();
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
  s.Camera(pos, foc);
  const VolumeComparison without = s.Compare("GradientOpacityNone");
  s.Volumes[0]->SetProperty(WithGradientOpacity(0));
  const VolumeComparison with = s.Compare("GradientOpacitySingle");
  Check(CheckVolumeComparison(with, "GradientOpacitySingle", 0.5, 3, 2000),
    "one volume with gradient opacity matches the reference");
  const ChannelError change = ImageError(with.Gpu, without.Gpu);
  std::cout << "GradientOpacitySingle: RMS " << change.Rms << " from the image without it\n";
  Check(change.Rms > 2.0, "gradient opacity changes the image by more than RMS 2");
  const std::string src = s.Mapper->GetShaderSource(1);
  Check(src.find("strataGradientTau0") != std::string::npos, "its source has gradient opacity");
  s.Mapper->SetClassification(vtkMultiVolumeRayCastMapper::Classifications::PreIntegrated);
  s.Win->Render();
  Check(s.Mapper->GetShaderSource(1).find("strataGradientTau") == std::string::npos,
    "pre-integration has no gradient opacity code (documented: not supported there)");
}

// Paged from a pool of 8^3 pages (the gradient's neighbours a voxel away often in the next
// brick), converged: the in-core image with gradient opacity (the same level-0 values through
// the same atlas lookups), so the reference's bounds as well. Paged vs in core are two programs
// (the paged one has the feedback code): within ImagePolicy::TwoProgramsMax, 1 of 255
// (StrataImagePolicy.h rule 2). Measured 0 on llvmpipe, 1 on an H200.
void Paged(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  s.Add(Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1), WithGradientOpacity(0));
  s.UseSingleVolume();
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
  s.Camera(pos, foc);
  s.Mapper->SetBrickSize(8);
  s.Win->Render();
  const auto inCore = ReadRGB(s.Win);
  const std::string pool = paths.Output + "/gradient-opacity-paged.spp";
  auto reader = WritePagedTwin(s.Images[0], pool, 8);
  s.Mapper->SetInputConnection(0, reader->GetOutputPort());
  const int frames = RenderUntilConverged(s, 100);
  const bool converged = frames > 0;
  const double mx = ImageError(ReadRGB(s.Win), inCore).Max;
  std::cout << "GradientOpacityPaged: converged " << converged << " after " << frames
            << " frames; max difference to in core " << mx << "\n";
  Check(converged, "the paged volume converges");
  Check(mx <= ImagePolicy::TwoProgramsMax,
    "paged with gradient opacity equals the in-core image (max 1/255)");
  Check(
    CheckVolumeComparison(s.Compare("GradientOpacityPaged"), "GradientOpacityPaged", 0.5, 3, 2000),
    "a paged volume with gradient opacity matches the reference");
}

void Mixed(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  s.Add(Blob(40, 36, 32, 1.0, 1.0, 1.0, 0, 0, 0, 1), WithGradientOpacity(0));
  vtkNew<vtkTransform> t;
  t->Translate(30, 10, 4);
  t->RotateZ(30);
  s.Add(Blob(24, 20, 18, 1.6, 1.5, 1.4, 0, 0, 0, 2), MakeVolumeProperty(1), t);
  s.UseMultiVolume();
  const double pos[3] = { -50, -70, 80 }, foc[3] = { 30, 25, 14 };
  s.Camera(pos, foc);
  Check(
    CheckVolumeComparison(s.Compare("GradientOpacityMixed"), "GradientOpacityMixed", 0.5, 3, 3000),
    "volumes with and without gradient opacity in one scene match the reference");
  const std::string two = s.Mapper->GetShaderSource(2);
  Check(two.find("strataGradientTau0") != std::string::npos &&
          two.find("strataGradientTau1") == std::string::npos,
    "only the volume with gradient opacity has its code");
  s.Mapper->SetCompositeOrder(vtkMultiVolumeRayCastMapper::CompositeOrders::BackToFront);
  Check(CheckVolumeComparison(s.Compare("GradientOpacityMixedBackToFront"),
          "GradientOpacityMixedBackToFront",
          0.5,
          3,
          3000),
    "the same back to front");
}
}

int TestMultiVolumeGradientOpacity(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  std::vector<SubTest> parts = {
    { "one volume", [&] { Single(paths); } },
    { "with and without in one scene", [&] { Mixed(paths); } },
    { "paged", [&] { Paged(paths); } },
    { "no VTK errors or warnings", [output] { CheckNoVtkMessages(output); } },
  };
  return RunSubTests(parts, Failures);
}
