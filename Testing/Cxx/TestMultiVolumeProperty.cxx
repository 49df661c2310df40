// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkVolumeProperty settings per volume in one scene of vtkMultiVolumeRayCastMapper, against the
// double-precision reference: InterpolationType (one volume nearest, the overlapping one linear,
// and the other way round) and ScalarOpacityUnitDistance (0.5 on one volume, 2 on the other; and
// per component, 0.5 and 2 on the two independent components of one volume).
//
// Bounds, in 8-bit units: RMS 0.4 / max 2 as StrataMultiVolumeCase.h where the classification is
// smooth (unit distances; measured RMS 0.22 / 0.30, max 1.23 / 1.24 per volume / per component).
// Nearest-point data is piecewise constant with jumps on the half-integer planes; the reference
// cuts its pieces there, the GPU's step across one takes the value at the step's midpoint (a
// quarter of a world unit of the wrong side, the voxels here about 4.4 units): measured RMS
// 0.30 / 0.24, max 3.6 / 2.6 (nearest on port 0 / port 1), bounds RMS 0.5 / max 5.
// Each setting is checked to matter: the reference with the setting ignored (both linear; the
// unit distances swapped; both components at unit distance 1) is compared with the same
// rendering: measured RMS 3.1 / 1.3, max 41 / 24 (nearest), RMS 13.2 / 22.9, max 86 / 140 (unit
// distances), asserted above twice the RMS bound and 4 times the max bound.
#include "StrataMultiVolumeCase.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "StrataMultiVolumeReferenceIntegrator.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace strata_test;
using Ref = strata::MultiVolumeReferenceIntegrator;

/// The reference of the scene's volumes, each description changed by `change` (its port, its
/// description), through the scene's camera over mid grey, in 8-bit units.
std::vector<double> ChangedReference(VolumeScene& s,
  const std::function<void(int, Ref::Volume&)>& change)
{
  Ref ref;
  for (size_t i = 0; i < s.Images.size(); ++i)
  {
    Ref::Volume v = ToReferenceVolume(s.Images[i], s.Volumes[i], s.Mapper, static_cast<int>(i));
    change(static_cast<int>(i), v);
    Check(
      ref.AddVolume(std::move(v)) >= 0, "the reference takes the volume: " + ref.GetLastError());
  }
  std::vector<double> rgba;
  const int w = MultiVolumeCaseSize;
  ref.IntegrateImage(ClipToWorld(s.Ren)->GetData(), w, w, rgba);
  return CompositeOver(rgba, std::vector<unsigned char>(3 * size_t(w) * w, 128));
}

/// Checks that the rendering `c` differs from the changed reference by more than `rms` RMS and
/// `max` at most.
void CheckMatters(VolumeScene& s,
  const VolumeComparison& c,
  const std::string& name,
  double rms,
  double max,
  const std::function<void(int, Ref::Volume&)>& change)
{
  const ChannelError e = ImageError(c.Gpu, ChangedReference(s, change));
  std::cout << name << " against the reference with the setting ignored: RMS " << e.Rms << ", max "
            << e.Max << "\n";
  Check(e.Rms > rms && e.Max > max,
    name + ": ignoring the setting differs by more than RMS " + std::to_string(rms) + " / max " +
      std::to_string(max));
}

/// RenderTwoVolumes' kind of scene: a 40 x 36 x 32 volume and a coarser one turned 30 degrees
/// overlapping it; `coarse`: both with voxels of about 4 units (10 x 9 x 8 and 8 x 7 x 6), so that
/// nearest-point and linear interpolation differ visibly.
void TwoVolumes(VolumeScene& s, vtkVolumeProperty* p0, vtkVolumeProperty* p1, bool coarse = false)
{
  s.Add(coarse ? Blob(10, 9, 8, 4.3, 4.3, 4.3, 0, 0, 0, 1)
               : Blob(40, 36, 32, 1.0, 1.0, 1.0, 0, 0, 0, 1),
    p0);
  vtkNew<vtkTransform> t;
  t->Translate(30, 10, 4);
  t->RotateZ(30);
  s.Add(
    coarse ? Blob(8, 7, 6, 4.7, 4.6, 4.4, 0, 0, 0, 2) : Blob(24, 20, 18, 1.6, 1.5, 1.4, 0, 0, 0, 2),
    p1,
    t);
  s.UseMultiVolume();
  const double pos[3] = { -50, -70, 80 }, foc[3] = { 30, 25, 14 };
  s.Camera(pos, foc);
}

// Nearest on one volume, linear on the other, both ways round.
void Interpolation(const TestPaths& paths, int nearestPort)
{
  VolumeScene s(paths.Output);
  auto p0 = MakeVolumeProperty(0), p1 = MakeVolumeProperty(1);
  (nearestPort == 0 ? p0 : p1)->SetInterpolationTypeToNearest();
  TwoVolumes(s, p0, p1, true);
  const std::string name = "PropertyNearest" + std::to_string(nearestPort);
  const VolumeComparison c = s.Compare(name);
  Check(CheckVolumeComparison(c, name, 0.5, 5, 2500),
    name + ": nearest on port " + std::to_string(nearestPort) + " matches the reference");
  CheckMatters(
    s, c, name, 1.0, 20, [](int, Ref::Volume& v) { v.Sampling = Ref::Interpolation::Linear; });
}

// Unit distance 0.5 on one volume and 2 on the other.
void UnitDistance(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  TwoVolumes(s, MakeVolumeProperty(0, 0.5), MakeVolumeProperty(1, 2.0));
  const VolumeComparison c = s.Compare("PropertyUnitDistance");
  Check(CheckVolumeComparison(c, "PropertyUnitDistance", 0.4, 2, 2500),
    "unit distances 0.5 and 2 match the reference");
  CheckMatters(s,
    c,
    "PropertyUnitDistance",
    1.6,
    8,
    [](int port, Ref::Volume& v) { v.Classification.UnitDistance = port == 0 ? 2.0 : 0.5; });
}

// Unit distance per component: two independent components at 0.5 and 2.
void ComponentUnitDistance(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  auto image = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1);
  auto second = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 2);
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfComponents(2);
  values->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    values->SetComponent(i, 0, image->GetPointData()->GetScalars()->GetComponent(i, 0));
    values->SetComponent(i, 1, second->GetPointData()->GetScalars()->GetComponent(i, 0));
  }
  image->GetPointData()->SetScalars(values);
  auto p = MakeVolumeProperty(0);
  auto other = MakeVolumeProperty(1);
  p->SetColor(1, other->GetRGBTransferFunction(0));
  p->SetScalarOpacity(1, other->GetScalarOpacity(0));
  p->SetScalarOpacityUnitDistance(0, 0.5);
  p->SetScalarOpacityUnitDistance(1, 2.0);
  s.Add(image, p);
  s.UseSingleVolume();
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
  s.Camera(pos, foc);
  const VolumeComparison c = s.Compare("PropertyComponentUnitDistance");
  Check(CheckVolumeComparison(c, "PropertyComponentUnitDistance", 0.4, 2, 2500),
    "component unit distances 0.5 and 2 match the reference");
  CheckMatters(s,
    c,
    "PropertyComponentUnitDistance",
    1.6,
    8,
    [](int, Ref::Volume& v)
    {
      v.Classification.UnitDistance = 1.0;
      v.ComponentClassifications[0].UnitDistance = 1.0;
    });
}
}

int TestMultiVolumeProperty(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  std::vector<SubTest> parts;
  parts.push_back({ "nearest on port 0", [&paths] { Interpolation(paths, 0); } });
  parts.push_back({ "nearest on port 1", [&paths] { Interpolation(paths, 1); } });
  parts.push_back({ "unit distance per volume", [&paths] { UnitDistance(paths); } });
  parts.push_back({ "unit distance per component", [&paths] { ComponentUnitDistance(paths); } });
  parts.push_back({ "no VTK errors or warnings", [output] { CheckNoVtkMessages(output); } });
  return RunSubTests(parts, Failures);
}
