// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// vtkSubsurfacePicker on a subsurface scene at UTM coordinates: the demo's three crossing
// horizons with holes (MakeDemoHorizons, 64 x 48 at 12.5 m, turned 30 degrees) and a volume
// above them whose values are a linear function of world position (trilinear interpolation
// reproduces it exactly), in core and paged (tile pools and a brick pool read through
// vtkPagePoolReader). On a 12 x 10 grid of pixel centres of a 96 x 80 window:
// - horizons: the picked horizon is the one strata::HeightFieldReferenceCaster finds for that pixel
//   in CompareWithReference (rays built there from VTK's camera, independently of the picker),
//   and the picked point's window depth equals the reference's within 1e-6; the GPU's
//   HorizonId image agrees with both wherever it agrees with the reference;
// - volume (horizons not pickable): every sample's value equals the linear function at the
//   sample's world position (1e-3: float storage of values near 50); where the ray reaches the
//   opacity threshold 0.5, strata::MultiVolumeReferenceIntegrator composites the ray from the near
//   plane to the picked point to opacity 0.5 +- 0.01 (the mapper's own sampling, 1/4 voxel at
//   midpoints, against the reference at 1/16: StrataMultiVolumeCase.h's max bound, 2 / 255);
//   elsewhere the last sample's accumulated opacity is the reference's for the whole ray +-0.01;
//   both kinds of rays occur;
// - both pickable: the pick is the nearer hit, and no ray sample lies beyond a nearer horizon;
// - paged: every pick (ids, positions, values, opacities) equals the in-core one exactly;
// - a vtkMultiVolume of two overlapping volumes, the second moved by its prop's transform:
//   each volume's values are the field at the sample (NaN outside it) and the opacity is the
//   reference's for both together within 0.01 as above (measured 0.0033: steps that straddle
//   the second volume's faces count it for the whole step or not at all).
#include "StrataHeightFieldCase.h"
#include "StrataHeightFieldScenes.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkSubsurfacePicker.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace strata_test;

constexpr int W = 96, H = 80;
const double Centre[3] = { 456200.0, 6780250.0, -200.0 };

double Field(const double p[3])
{
  return 50.0 + 0.08 * (p[0] - Centre[0]) + 0.05 * (p[1] - Centre[1]) - 0.3 * (p[2] - Centre[2]);
}

/// 28 x 24 x 12 points, 25 m x 25 m x 15 m, turned 30 degrees, from z = -285 to -120.
vtkSmartPointer<vtkImageData> MakeRampVolume()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(28, 24, 12);
  image->SetSpacing(25.0, 25.0, 15.0);
  const double a = vtkMath::RadiansFromDegrees(30.0), c = std::cos(a), s = std::sin(a);
  const double d[9] = { c, -s, 0, s, c, 0, 0, 0, 1 };
  image->SetDirectionMatrix(d);
  image->SetOrigin(Centre[0] - c * 337.5 + s * 287.5, Centre[1] - s * 337.5 - c * 287.5, -285.0);
  vtkNew<vtkFloatArray> v;
  v->SetName("value");
  v->SetNumberOfTuples(28 * 24 * 12);
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 28; ++i)
      {
        double p[3];
        image->TransformIndexToPhysicalPoint(i, j, k, p);
        v->SetValue((k * 24 + j) * 28 + i, static_cast<float>(Field(p)));
      }
  image->GetPointData()->SetScalars(v);
  return image;
}

/// What one pick found, to compare in core and paged.
struct PickResult
{
  int Horizon = -1;
  double Position[3] = { 0, 0, 0 };
  bool Picked = false, VolumeHit = false;
  std::vector<double> Values, Opacity, Points;
  /// The same pick: ids and flags equal, values equal (NaN outside the volume), positions
  /// within 1 micrometre and opacities within 1e-12 (the paged ray is clipped to the pages it
  /// read, which can change the last bits of its last step).
  bool operator==(const PickResult& o) const
  {
    auto close = [](const std::vector<double>& x, const std::vector<double>& y, double tol)
    {
      if (x.size() != y.size())
        return false;
      for (size_t i = 0; i < x.size(); ++i)
        if (!(std::abs(x[i] - y[i]) <= tol || (std::isnan(x[i]) && std::isnan(y[i]))))
          return false;
      return true;
    };
    return this->Horizon == o.Horizon && this->Picked == o.Picked &&
           this->VolumeHit == o.VolumeHit &&
           close({ this->Position, this->Position + 3 }, { o.Position, o.Position + 3 }, 1e-6) &&
           close(this->Values, o.Values, 0.0) && close(this->Opacity, o.Opacity, 1e-12) &&
           close(this->Points, o.Points, 1e-6);
  }
};

PickResult Pick(vtkSubsurfacePicker* picker, vtkRenderer* ren, int i, int j)
{
  PickResult r;
  r.Picked = picker->Pick(i + 0.5, j + 0.5, 0.0, ren) != 0;
  r.Horizon = picker->GetHorizonId();
  picker->GetPickPosition(r.Position);
  r.VolumeHit = picker->GetVolumeHit();
  for (vtkIdType n = 0; n < picker->GetRayValues()->GetNumberOfValues(); ++n)
    r.Values.push_back(picker->GetRayValues()->GetValue(n));
  for (vtkIdType n = 0; n < picker->GetRayOpacity()->GetNumberOfValues(); ++n)
    r.Opacity.push_back(picker->GetRayOpacity()->GetValue(n));
  for (vtkIdType n = 0; n < picker->GetRayPoints()->GetNumberOfPoints(); ++n)
    for (int c = 0; c < 3; ++c)
      r.Points.push_back(picker->GetRayPoints()->GetPoint(n)[c]);
  return r;
}

/// The pixel centre's ray, near plane (t = 0) to far plane (t = 1), in world coordinates.
void Ray(vtkRenderer* ren, int i, int j, double p1[3], double p2[3])
{
  auto clipToWorld = ClipToWorld(ren);
  const double x = 2.0 * (i + 0.5) / W - 1.0, y = 2.0 * (j + 0.5) / H - 1.0;
  for (int end = 0; end < 2; ++end)
  {
    const double in[4] = { x, y, end ? 1.0 : -1.0, 1.0 };
    double out[4];
    clipToWorld->MultiplyPoint(in, out);
    for (int c = 0; c < 3; ++c)
      (end ? p2 : p1)[c] = out[c] / out[3];
  }
}

double WindowDepth(vtkRenderer* ren, const double p[3])
{
  ren->SetWorldPoint(p[0], p[1], p[2], 1.0);
  ren->WorldToDisplay();
  return ren->GetDisplayPoint()[2];
}

struct Scene
{
  HeightFieldScene Horizons;
  vtkSmartPointer<vtkImageData> Volume = MakeRampVolume();
  vtkNew<vtkMultiVolumeRayCastMapper> VolumeMapper;
  vtkNew<vtkVolume> Prop;
  explicit Scene(const std::string& out)
    : Horizons(out, MakeDemoHorizons(64, 48, 456000, 6780000, 12.5, 30), W, H)
  {
    this->VolumeMapper->SetInputDataObject(0, this->Volume);
    this->Prop->SetMapper(this->VolumeMapper);
    this->Prop->SetProperty(MakeVolumeProperty(0, 30.0));
    const double pos[3] = { 455700, 6779500, 900 }, foc[3] = { 456250, 6780250, -350 },
                 up[3] = { 0, 0, 1 };
    this->Horizons.Camera(pos, foc, up);
  }
};

bool CheckHorizons(Scene& s, const std::string& out)
{
  auto ref = CompareWithReference(s.Horizons.Win,
    s.Horizons.Ren,
    s.Horizons.Actor,
    s.Horizons.Mapper,
    s.Horizons.Images,
    "picker-horizons",
    out);
  s.Horizons.Mapper->SetOutputMode(vtkStackedHeightFieldMapper::OutputModes::Shaded);
  vtkNew<vtkSubsurfacePicker> picker;
  long hits = 0, wrongId = 0, gpuAgree = 0, gpuChecked = 0;
  double worstDepth = 0.0;
  for (int j = 3; j < H; j += 8)
  {
    for (int i = 3; i < W; i += 8)
    {
      const PickResult r = Pick(picker, s.Horizons.Ren, i, j);
      const int p = j * W + i;
      wrongId += r.Horizon != ref.RefIds[p];
      if (r.Horizon >= 0 && r.Horizon == ref.RefIds[p])
      {
        ++hits;
        worstDepth =
          std::max(worstDepth, std::abs(WindowDepth(s.Horizons.Ren, r.Position) - ref.RefDepth[p]));
      }
      if (ref.GpuIds[p] == ref.RefIds[p])
      {
        ++gpuChecked;
        gpuAgree += ref.GpuIds[p] == r.Horizon;
      }
    }
  }
  std::cout << "horizons: " << hits << " of 120 pixels hit, " << wrongId
            << " picks off the reference, window depth within " << worstDepth << "; GPU agrees on "
            << gpuAgree << " of " << gpuChecked << "\n";
  const bool ok = hits >= 50 && wrongId == 0 && worstDepth < 1e-6 && gpuAgree == gpuChecked;
  if (!ok)
    std::cerr << "FAILED: horizon picks against strata::HeightFieldReferenceCaster and the GPU\n";
  return ok;
}

bool CheckVolume(Scene& s, std::vector<PickResult>& picks)
{
  vtkRenderer* ren = s.Horizons.Ren;
  vtkNew<vtkSubsurfacePicker> picker;
  picker->PickFromListOn();
  picker->AddPickList(s.Prop);
  strata::MultiVolumeReferenceIntegrator ref;
  ref.AddVolume(ToReferenceVolume(s.Volume, s.Prop));
  long hits = 0, misses = 0, samples = 0;
  double worstValue = 0.0, worstAlpha = 0.0;
  for (int j = 3; j < H; j += 8)
  {
    for (int i = 3; i < W; i += 8)
    {
      const PickResult r = Pick(picker, ren, i, j);
      picks.push_back(r);
      for (size_t n = 0; n < r.Values.size(); ++n)
      {
        if (std::isnan(r.Values[n]))
          continue;
        ++samples;
        worstValue = std::max(worstValue, std::abs(r.Values[n] - Field(&r.Points[3 * n])));
      }
      if (r.Opacity.empty())
        continue;
      double p1[3], p2[3], dir[3];
      Ray(ren, i, j, p1, p2);
      for (int c = 0; c < 3; ++c)
        dir[c] = p2[c] - p1[c];
      if (r.VolumeHit)
      {
        ++hits;
        const double t = picker->GetVolumeT();
        worstAlpha = std::max(worstAlpha, std::abs(ref.IntegrateRay(p1, dir, 0.0, t)[3] - 0.5));
      }
      else
      {
        ++misses;
        worstAlpha =
          std::max(worstAlpha, std::abs(ref.IntegrateRay(p1, dir, 0.0, 1.0)[3] - r.Opacity.back()));
      }
    }
  }
  std::cout << "volume: " << hits << " rays reach opacity 0.5, " << misses << " do not; " << samples
            << " samples within " << worstValue << " of the field, opacity within " << worstAlpha
            << " of the reference\n";
  const bool ok =
    hits > 5 && misses > 5 && samples > 1000 && worstValue < 1e-3 && worstAlpha < 0.01;
  if (!ok)
    std::cerr
      << "FAILED: volume picks against the field and strata::MultiVolumeReferenceIntegrator\n";
  return ok;
}

bool CheckBoth(Scene& s, std::vector<PickResult>& picks)
{
  vtkRenderer* ren = s.Horizons.Ren;
  vtkNew<vtkSubsurfacePicker> picker;
  long stoppedByHorizon = 0, bad = 0;
  for (int j = 3; j < H; j += 8)
  {
    for (int i = 3; i < W; i += 8)
    {
      const PickResult r = Pick(picker, ren, i, j);
      picks.push_back(r);
      const double h = picker->GetHorizonT(), v = picker->GetVolumeT();
      double p1[3], p2[3];
      Ray(ren, i, j, p1, p2);
      const double nearer = std::min(h, v);
      if (nearer < VTK_DOUBLE_MAX)
      {
        double expected[3];
        for (int c = 0; c < 3; ++c)
          expected[c] = p1[c] + nearer * (p2[c] - p1[c]);
        bad += std::sqrt(vtkMath::Distance2BetweenPoints(expected, r.Position)) > 1e-6 * 1e3;
      }
      if (h < VTK_DOUBLE_MAX && !r.Points.empty())
      {
        const double horizon =
          std::sqrt(vtkMath::Distance2BetweenPoints(p1, picker->GetHorizonPosition()));
        const double last =
          std::sqrt(vtkMath::Distance2BetweenPoints(p1, &r.Points[r.Points.size() - 3]));
        bad += last > horizon + 1e-9;
        stoppedByHorizon += !r.VolumeHit;
      }
    }
  }
  std::cout << "both: " << stoppedByHorizon << " rays through the volume stopped by a horizon, "
            << bad << " inconsistent picks\n";
  const bool ok = bad == 0 && stoppedByHorizon > 5;
  if (!ok)
    std::cerr << "FAILED: the pick is the nearer hit, and the samples stop at the horizon\n";
  return ok;
}

/// Two overlapping volumes of the same field in one vtkMultiVolume, the second on another grid
/// and moved by its prop's position (its samples hold the field at their moved places): each
/// sample's value of each volume is the field there (NaN outside), and the opacity is the
/// reference's for both volumes together.
bool CheckMultiVolume(const std::string& out)
{
  Scene s(out);
  vtkRenderer* ren = s.Horizons.Ren;
  auto second = MakeRampVolume();
  second->SetDimensions(14, 12, 12);
  second->SetSpacing(30.0, 30.0, 12.0);
  vtkNew<vtkFloatArray> v;
  v->SetNumberOfTuples(14 * 12 * 12);
  const double shift[3] = { 150.0, 60.0, 20.0 };
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 14; ++i)
      {
        double p[3];
        second->TransformIndexToPhysicalPoint(i, j, k, p);
        for (int c = 0; c < 3; ++c)
          p[c] += shift[c];
        v->SetValue((k * 12 + j) * 14 + i, static_cast<float>(Field(p)));
      }
  second->GetPointData()->SetScalars(v);
  vtkNew<vtkMultiVolumeRayCastMapper> mapper;
  mapper->SetInputDataObject(0, s.Volume);
  mapper->SetInputDataObject(1, second);
  vtkNew<vtkVolume> a, b;
  a->SetProperty(MakeVolumeProperty(0, 30.0));
  b->SetProperty(MakeVolumeProperty(1, 30.0));
  b->SetPosition(shift[0], shift[1], shift[2]);
  vtkNew<vtkMultiVolume> multi;
  multi->SetMapper(mapper);
  multi->SetVolume(a, 0);
  multi->SetVolume(b, 1);
  ren->AddVolume(multi);
  s.Horizons.Win->Render();
  vtkNew<vtkSubsurfacePicker> picker;
  picker->PickFromListOn();
  picker->AddPickList(multi);
  strata::MultiVolumeReferenceIntegrator ref;
  ref.AddVolume(ToReferenceVolume(s.Volume, a));
  ref.AddVolume(ToReferenceVolume(second, b));
  long hits = 0, both = 0, samples = 0;
  double worstValue = 0.0, worstAlpha = 0.0;
  for (int j = 3; j < H; j += 8)
  {
    for (int i = 3; i < W; i += 8)
    {
      const PickResult r = Pick(picker, ren, i, j);
      const size_t n = r.Opacity.size();
      for (size_t q = 0; q < n; ++q)
      {
        const double* p = &r.Points[3 * q];
        const double va = r.Values[2 * q], vb = r.Values[2 * q + 1];
        both += !std::isnan(va) && !std::isnan(vb);
        samples += !std::isnan(va) + !std::isnan(vb);
        if (!std::isnan(va))
          worstValue = std::max(worstValue, std::abs(va - Field(p)));
        if (!std::isnan(vb))
          worstValue = std::max(worstValue, std::abs(vb - Field(p)));
      }
      if (n == 0)
        continue;
      double p1[3], p2[3], dir[3];
      Ray(ren, i, j, p1, p2);
      for (int c = 0; c < 3; ++c)
        dir[c] = p2[c] - p1[c];
      hits += r.VolumeHit;
      const double expected = r.VolumeHit ? 0.5 : r.Opacity.back();
      const double t = r.VolumeHit ? picker->GetVolumeT() : 1.0;
      worstAlpha = std::max(worstAlpha, std::abs(ref.IntegrateRay(p1, dir, 0.0, t)[3] - expected));
    }
  }
  std::cout << "multi-volume: " << hits << " rays reach opacity 0.5; " << samples << " samples ("
            << both << " in both volumes) within " << worstValue << " of the field, opacity within "
            << worstAlpha << " of the reference\n";
  const bool ok = hits > 5 && both > 100 && worstValue < 1e-3 && worstAlpha < 0.01;
  if (!ok)
    std::cerr << "FAILED: multi-volume picks against the field and the reference\n";
  return ok;
}

/// The scene with its horizons and volume read back from page pools.
bool CheckPaged(Scene& s,
  const std::vector<PickResult>& volumePicks,
  const std::vector<PickResult>& bothPicks,
  const std::string& out)
{
  std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
  auto pool = [&](vtkImageData* image, const std::string& name)
  {
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName((out + "/" + name + ".spp").c_str());
    writer->SetPageSize(8);
    writer->Write();
    auto r = vtkSmartPointer<vtkPagePoolReader>::New();
    r->SetFileName((out + "/" + name + ".spp").c_str());
    readers.push_back(r);
    return r;
  };
  s.Horizons.Mapper->RemoveAllInputConnections(0);
  for (size_t k = 0; k < s.Horizons.Images.size(); ++k)
    s.Horizons.Mapper->AddInputConnection(
      0, pool(s.Horizons.Images[k], "horizon" + std::to_string(k))->GetOutputPort());
  s.VolumeMapper->SetInputConnection(0, pool(s.Volume, "volume")->GetOutputPort());
  s.Horizons.Win->Render();
  vtkNew<vtkSubsurfacePicker> volumeOnly, both;
  volumeOnly->PickFromListOn();
  volumeOnly->AddPickList(s.Prop);
  long differ = 0;
  size_t n = 0;
  for (int j = 3; j < H; j += 8)
  {
    for (int i = 3; i < W; i += 8, ++n)
    {
      const PickResult a = Pick(volumeOnly, s.Horizons.Ren, i, j),
                       b = Pick(both, s.Horizons.Ren, i, j);
      differ += !(a == volumePicks[n]);
      differ += !(b == bothPicks[n]);
    }
  }
  std::cout << "paged: " << differ << " of " << 2 * n << " picks differ from the in-core ones\n";
  if (differ > 0)
    std::cerr << "FAILED: paged picks equal the in-core ones\n";
  return differ == 0;
}
}

int TestSubsurfacePicker(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  const std::string out = paths.Output + "/TestSubsurfacePicker";
  vtksys::SystemTools::MakeDirectory(out);
  Scene s(out);
  bool ok = CheckHorizons(s, out);
  s.Horizons.Ren->AddVolume(s.Prop);
  s.Horizons.Win->Render();
  std::vector<PickResult> volumePicks, bothPicks;
  ok = CheckVolume(s, volumePicks) && ok;
  ok = CheckBoth(s, bothPicks) && ok;
  ok = CheckPaged(s, volumePicks, bothPicks, out) && ok;
  ok = CheckMultiVolume(out) && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
