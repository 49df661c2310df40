// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The cases of the multi-volume ray caster, each compared pixel by pixel with the
// double-precision reference integrator (StrataVolumeScenes). One TestMultiVolume<Case>.cxx per
// case calls RunMultiVolumeCase so that each is its own CTest test.
//
// Bounds, in 8-bit units over all pixels: RMS <= 0.4 and max <= 2. Writing 8 bits alone costs up
// to 0.5 (RMS 0.29); the GPU samples every 1/4 voxel at segment midpoints along one lattice
// (second order: measured well under 0.3 of a step here) and filters in float. A half-voxel
// shift of the texture coordinates gives RMS 2.7-4.6, a colour 3 % off gives RMS 0.62-0.74:
// both fail.
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataRegressionImage.h"
#include "StrataTestHelpers.h"
#include "StrataVolumeScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageCast.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkLight.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiVolume.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkMultiVolumeReferenceIntegrator.h"
#include "vtkPagePoolReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace strata_test
{
namespace
{
const int Size = 128;

struct VolumeScene
{
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  vtkNew<vtkMultiVolumeRayCastMapper> Mapper;
  vtkNew<vtkMultiVolume> Multi;
  std::vector<vtkSmartPointer<vtkImageData>> Images;
  std::vector<vtkSmartPointer<vtkVolume>> Volumes;
  VolumeScene()
  {
    MakeWindow(this->Win, this->Ren, Size, Size);
    this->Mapper->SetSampleDistance(0.25);
    this->Multi->SetMapper(this->Mapper);
  }
  /// Adds an input on the next port, with a member volume carrying `property` and `transform`.
  vtkVolume* Add(vtkImageData* image,
    vtkVolumeProperty* property,
    vtkTransform* transform = nullptr)
  {
    const int port = static_cast<int>(this->Images.size());
    this->Mapper->SetInputDataObject(port, image);
    auto v = vtkSmartPointer<vtkVolume>::New();
    v->SetProperty(property);
    if (transform)
    {
      v->SetUserTransform(transform);
    }
    this->Multi->SetVolume(v, port);
    this->Images.emplace_back(image);
    this->Volumes.push_back(v);
    return v;
  }
  /// Single-volume use: an ordinary vtkVolume with this mapper.
  void UseSingleVolume()
  {
    this->Volumes[0]->SetMapper(this->Mapper);
    this->Ren->AddVolume(this->Volumes[0]);
  }
  void UseMultiVolume() { this->Ren->AddVolume(this->Multi); }
  /// Looks from the direction of `pos` - `focal` at the centre of the volumes' world bounds, from
  /// where their bounding sphere just fills the view (computed here: vtkMultiVolume's bounds need
  /// a rendered vtkGPUVolumeRayCastMapper).
  void Camera(const double pos[3], const double focal[3])
  {
    double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX },
           hi[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (size_t v = 0; v < this->Images.size(); ++v)
    {
      double b[6];
      this->Images[v]->GetBounds(b);
      this->Volumes[v]->ComputeMatrix();
      vtkMatrix4x4* m = this->Volumes[v]->GetMatrix();
      for (int corner = 0; corner < 8; ++corner)
      {
        const double p[4] = {
          b[corner & 1], b[2 + ((corner >> 1) & 1)], b[4 + ((corner >> 2) & 1)], 1.0
        };
        double w[4];
        m->MultiplyPoint(p, w);
        for (int c = 0; c < 3; ++c)
        {
          lo[c] = std::min(lo[c], w[c]);
          hi[c] = std::max(hi[c], w[c]);
        }
      }
    }
    double centre[3], dir[3], radius = 0.0, len = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      centre[c] = 0.5 * (lo[c] + hi[c]);
      radius += 0.25 * (hi[c] - lo[c]) * (hi[c] - lo[c]);
      dir[c] = pos[c] - focal[c];
      len += dir[c] * dir[c];
    }
    radius = std::sqrt(radius);
    len = std::sqrt(len);
    const double distance = 0.8 * radius / std::sin(15.0 * std::acos(-1.0) / 180.0);
    vtkCamera* cam = this->Ren->GetActiveCamera();
    cam->SetFocalPoint(centre);
    cam->SetPosition(centre[0] + distance * dir[0] / len,
      centre[1] + distance * dir[1] / len,
      centre[2] + distance * dir[2] / len);
    cam->SetViewUp(0, 0, 1);
    cam->SetViewAngle(30);
    this->Ren->ResetCameraClippingRange(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]);
  }
  VolumeComparison Compare(const std::string& name, int raysPerPixel = 1)
  {
    std::vector<std::pair<vtkImageData*, vtkVolume*>> list;
    for (size_t i = 0; i < this->Images.size(); ++i)
      list.emplace_back(this->Images[i], this->Volumes[i]);
    return CompareVolumesWithReference(this->Win, this->Ren, list, name, 1.0 / 16.0, raysPerPixel);
  }
};

vtkSmartPointer<vtkImageData> Blob(int nx,
  int ny,
  int nz,
  double s0,
  double s1,
  double s2,
  double o0,
  double o1,
  double o2,
  int seed)
{
  const double s[3] = { s0, s1, s2 }, o[3] = { o0, o1, o2 };
  return MakeBlobVolume(nx, ny, nz, s, o, seed);
}
}

int RunMultiVolumeCase(const std::string& name)
{
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  bool ok = true;
  if (name == "Single")
  {
    // One volume through an ordinary vtkVolume; also against VTK's own GPU ray caster at the
    // same sample distance.
    VolumeScene s;
    auto image = Blob(40, 36, 32, 1.0, 1.1, 0.9, 0, 0, 0, 1);
    auto prop = MakeVolumeProperty(0);
    s.Add(image, prop);
    s.UseSingleVolume();
    const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
    s.Camera(pos, foc);
    auto r = s.Compare("Single");
    ok = CheckVolumeComparison(r, "Single", 0.4, 2, 3000);

    vtkSmartPointer<vtkRenderWindow> win;
    vtkSmartPointer<vtkRenderer> ren;
    MakeWindow(win, ren, Size, Size);
    ren->SetBackground(
      128.0 / 255.0, 128.0 / 255.0, 128.0 / 255.0); // as CompareVolumesWithReference
    vtkNew<vtkGPUVolumeRayCastMapper> vtkMapper;
    vtkMapper->SetInputData(image);
    vtkMapper->AutoAdjustSampleDistancesOff();
    vtkMapper->SetSampleDistance(0.25);
    vtkNew<vtkVolume> vol;
    vol->SetMapper(vtkMapper);
    vol->SetProperty(prop);
    ren->AddVolume(vol);
    ren->SetActiveCamera(s.Ren->GetActiveCamera());
    win->Render();
    const auto theirs = ReadRGB(win);
    const ChannelError diff = ImageError(r.Gpu, std::vector<double>(theirs.begin(), theirs.end()));
    const double rms = diff.Rms, mx = diff.Max;
    std::cout << "Single vs vtkGPUVolumeRayCastMapper: RMS " << rms << ", max " << mx
              << " of 255\n";
    // VTK samples from each ray's entry point rather than on one lattice: RMS 0.6 / max 3 allow
    // for that and its 8-bit rounding.
    if (rms > 0.6 || mx > 3)
    {
      std::cerr << "FAILED: differs from vtkGPUVolumeRayCastMapper by more than RMS 0.6 / max 3\n";
      ok = false;
    }
  }
  else if (name == "Two" || name == "UTM")
  {
    // Two overlapping volumes of different resolution and spacing, the second turned 30 degrees
    // about z. "UTM" renders the same scene near the origin and at x = 6e5, y = 6.7e6.
    auto run = [&](double ox, double oy, const std::string& tag)
    {
      VolumeScene s;
      s.Add(Blob(40, 36, 32, 1.0, 1.0, 1.0, ox, oy, 0, 1), MakeVolumeProperty(0));
      vtkNew<vtkTransform> t;
      t->Translate(ox + 30, oy + 10, 4);
      t->RotateZ(30);
      t->Translate(-ox, -oy, 0);
      s.Add(Blob(24, 20, 18, 1.6, 1.5, 1.4, ox, oy, 0, 2), MakeVolumeProperty(1), t);
      s.UseMultiVolume();
      const double pos[3] = { ox - 50, oy - 70, 80 }, foc[3] = { ox + 30, oy + 25, 14 };
      s.Camera(pos, foc);
      auto r = s.Compare(tag);
      std::cout << tag << ": " << s.Mapper->GetNumberOfFragments() << " fragments\n";
      return r;
    };
    auto a = run(0, 0, name == "Two" ? "Two" : "UTM-origin");
    ok = CheckVolumeComparison(a, name == "Two" ? "Two" : "UTM-origin", 0.4, 2, 3000);
    if (name == "UTM")
    {
      auto b = run(600000, 6700000, "UTM-utm");
      ok = CheckVolumeComparison(b, "UTM-utm", 0.4, 2, 3000) && ok;
      long differ = 0;
      int mx = 0;
      for (size_t i = 0; i < a.Gpu.size(); ++i)
      {
        const int d = std::abs(int(a.Gpu[i]) - int(b.Gpu[i]));
        differ += d > 1;
        mx = std::max(mx, d);
      }
      std::cout << "UTM vs origin: " << differ << " channel values differ by more than 1, max "
                << mx << "\n";
      if (differ > 0)
      {
        std::cerr << "FAILED: the UTM-scale image differs from the one at the origin\n";
        ok = false;
      }
    }
  }
  else if (name == "Three")
  {
    // Three volumes of different resolution, orientation and scalar type (float, unsigned
    // 16-bit, signed 16-bit: the integer ones hold the blob values rounded, which the
    // reference reads as well), all overlapping in the middle.
    auto cast = [](vtkImageData* image, int type)
    {
      vtkNew<vtkImageCast> c;
      c->SetInputData(image);
      c->SetOutputScalarType(type);
      c->Update();
      auto out = vtkSmartPointer<vtkImageData>::New();
      out->ShallowCopy(c->GetOutput());
      return out;
    };
    VolumeScene s;
    s.Add(Blob(36, 36, 30, 1.0, 1.0, 1.0, 0, 0, 0, 1), MakeVolumeProperty(0));
    vtkNew<vtkTransform> t1;
    t1->Translate(20, 14, 6);
    t1->RotateWXYZ(40, 1, 1, 0);
    s.Add(cast(Blob(20, 22, 18, 1.5, 1.4, 1.3, 0, 0, 0, 2), VTK_UNSIGNED_SHORT),
      MakeVolumeProperty(1),
      t1);
    vtkNew<vtkTransform> t2;
    t2->Translate(8, 24, -4);
    t2->RotateZ(-25);
    s.Add(cast(Blob(30, 14, 24, 1.2, 2.0, 1.1, 0, 0, 0, 3), VTK_SHORT), MakeVolumeProperty(2), t2);
    s.UseMultiVolume();
    const double pos[3] = { -50, -70, 80 }, foc[3] = { 22, 22, 12 };
    s.Camera(pos, foc);
    ok = CheckVolumeComparison(s.Compare("Three"), "Three", 0.4, 2, 3000);
    std::cout << "Three: " << s.Mapper->GetNumberOfFragments() << " fragments\n";
  }
  else if (name == "Rotated")
  {
    // Rotation through the image's direction matrix and the prop's transform together.
    VolumeScene s;
    auto image = Blob(40, 30, 26, 1.0, 1.2, 0.8, 5, -3, 2, 1);
    const double c = std::cos(0.6), sn = std::sin(0.6);
    const double dir[9] = { c, 0, sn, 0, 1, 0, -sn, 0, c };
    image->SetDirectionMatrix(dir);
    vtkNew<vtkTransform> t;
    t->RotateWXYZ(50, 0.3, 0.2, 1.0);
    s.Add(image, MakeVolumeProperty(2, 0.5), t);
    s.UseMultiVolume();
    const double pos[3] = { -60, -60, 60 }, foc[3] = { 10, 10, 10 };
    s.Camera(pos, foc);
    ok = CheckVolumeComparison(s.Compare("Rotated"), "Rotated", 0.4, 2, 1000);
  }
  else if (name == "Nested")
  {
    // A fine volume inside a coarse one.
    VolumeScene s;
    s.Add(Blob(24, 24, 20, 2.5, 2.5, 2.5, 0, 0, 0, 5), MakeVolumeProperty(0, 2.0));
    s.Add(Blob(30, 30, 24, 0.6, 0.6, 0.6, 20, 18, 14, 6), MakeVolumeProperty(1));
    s.UseMultiVolume();
    const double pos[3] = { -50, -60, 90 }, foc[3] = { 30, 30, 24 };
    s.Camera(pos, foc);
    ok = CheckVolumeComparison(s.Compare("Nested"), "Nested", 0.4, 2, 3000);
    std::cout << "Nested: " << s.Mapper->GetNumberOfFragments() << " fragments\n";
  }
  else if (name == "Coincident")
  {
    // Two identical coincident volumes: one fragment covered by both; the media add up.
    VolumeScene s;
    auto image = Blob(36, 32, 28, 1.0, 1.0, 1.0, 0, 0, 0, 7);
    s.Add(image, MakeVolumeProperty(0));
    s.Add(image, MakeVolumeProperty(1));
    s.UseMultiVolume();
    const double pos[3] = { -40, -60, 70 }, foc[3] = { 18, 16, 14 };
    s.Camera(pos, foc);
    ok = CheckVolumeComparison(s.Compare("Coincident"), "Coincident", 0.4, 2, 3000);
    std::cout << "Coincident: " << s.Mapper->GetNumberOfFragments() << " fragments\n";
    if (s.Mapper->GetNumberOfFragments() != 1)
    {
      std::cerr << "FAILED: two coincident volumes must make one fragment\n";
      ok = false;
    }
  }
  else if (name == "SharedFace")
  {
    // Two volumes sharing a face: no seam, no double counting on it.
    VolumeScene s;
    s.Add(Blob(30, 30, 30, 1.0, 1.0, 1.0, 0, 0, 0, 8), MakeVolumeProperty(0));
    s.Add(Blob(20, 30, 30, 1.5, 1.0, 1.0, 29, 0, 0, 9), MakeVolumeProperty(1));
    s.UseMultiVolume();
    const double pos[3] = { -30, -70, 60 }, foc[3] = { 29, 15, 15 };
    s.Camera(pos, foc);
    ok = CheckVolumeComparison(s.Compare("SharedFace"), "SharedFace", 0.4, 2, 3000);
    std::cout << "SharedFace: " << s.Mapper->GetNumberOfFragments() << " fragments\n";
  }
  else if (name == "Thin")
  {
    // A one-voxel-thin volume (nz = 1): one spacing thick, seen obliquely.
    VolumeScene s;
    s.Add(Blob(48, 40, 1, 1.0, 1.0, 6.0, 0, 0, 0, 10), MakeVolumeProperty(0, 1.0));
    s.UseMultiVolume();
    const double pos[3] = { -20, -50, 60 }, foc[3] = { 24, 20, 0 };
    s.Camera(pos, foc);
    ok = CheckVolumeComparison(s.Compare("Thin"), "Thin", 0.4, 2, 2000);
  }
  else if (name == "Classification")
  {
    // Post-classification, pre-integration (full table and two-integral form) and both
    // compositing orders on two overlapping volumes, each against the reference; then a
    // transfer function with a sharp spike: pre-integration at step d must beat
    // post-classification at d / 4 (the reference integrates the spike exactly).
    using Cl = vtkMultiVolumeRayCastMapper::Classifications;
    using Or = vtkMultiVolumeRayCastMapper::CompositeOrders;
    VolumeScene s;
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
    VolumeScene spike;
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
  }
  else if (name == "RaysPerPixel")
  {
    // Several rays per pixel, each composited through all fragments on its own: against the
    // reference integrating the same sub-pixel rays. Coherence lets rays after the centre one
    // skip the empty space it crossed, exact wherever that space ends at the same depth across
    // the pixel, approximate at silhouettes.
    VolumeScene s;
    s.Add(Blob(40, 36, 32, 1.0, 1.0, 1.0, 0, 0, 0, 1), MakeVolumeProperty(0));
    vtkNew<vtkTransform> t;
    t->Translate(30, 10, 4);
    t->RotateZ(30);
    s.Add(Blob(24, 20, 18, 1.6, 1.5, 1.4, 0, 0, 0, 2), MakeVolumeProperty(1), t);
    s.UseMultiVolume();
    const double pos[3] = { -50, -70, 80 }, foc[3] = { 30, 25, 14 };
    s.Camera(pos, foc);
    // The first volume is visibly dense up to its faces: hard silhouettes to anti-alias.
    vtkPiecewiseFunction* pwf = s.Volumes[0]->GetProperty()->GetScalarOpacity(0);
    pwf->AddPoint(0, 0.6);
    pwf->AddPoint(20, 0.6);
    for (const auto& mode :
      { std::make_pair(2, false), std::make_pair(5, true), std::make_pair(5, false) })
    {
      s.Mapper->SetRaysPerPixel(mode.first);
      s.Mapper->SetRayCoherence(mode.second);
      const std::string tag =
        "Rays" + std::to_string(mode.first) + (mode.second ? "-coherent" : "");
      // Coherence is an accuracy knob: where a pixel straddles a silhouette, a sub-pixel ray can
      // enter the volume well before the centre ray's first non-empty sample and loses that
      // stretch. Measured here: 125 of 8075 covered pixels off by more than 4/255, at most 14.
      // Its bounds: RMS 1, max 16; without coherence the usual 0.4 and 2.
      const bool approx = mode.second;
      ok = CheckVolumeComparison(
             s.Compare(tag, mode.first), tag, approx ? 1.0 : 0.4, approx ? 16 : 2, 3000) &&
           ok;
    }
    // The mean of 5 rays is not the centre ray: compared with the centre-only reference the
    // error must grow at the hard silhouettes (so the rays really are spread over the pixel).
    auto centre = s.Compare("Rays5-vs-centre", 1);
    std::cout << "Rays5 against the centre-ray reference: RMS " << centre.Rms << ", max "
              << centre.Max << "\n";
    Check(
      centre.Max > 2.0, "5 rays per pixel differ from one centre ray somewhere by more than 2/255");
    ok = ok && Failures() == 0;
  }
  else if (name == "Shaded")
  {
    // Gradient shading against an analytic expectation. The field s = 2 i + j has one gradient
    // direction N everywhere; with one directional light L and a parallel camera (view V), every
    // sample's colour becomes c (ka + kd |N.L|) + ks |N.H|^p, H = (L + V) / |L + V|: the
    // reference with that colour table is the exact image, except in the outermost voxel layer,
    // where clamped lookups halve one component of the central difference and turn the normal
    // (measured: RMS 0.32, max 2.4 of 255). Bounds: RMS 0.6, max 4; a normal taken through the
    // Jacobian instead of its transpose gives RMS 25.6 here.
    VolumeScene s;
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
    const std::string src = s.Mapper->GetFragmentShaderSource(1);
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

    vtkMultiVolumeReferenceIntegrator ref;
    auto rv = ToReferenceVolume(image, s.Volumes[0]);
    for (double& c : rv.Classification.Color)
      c = c * factor + spec;
    ref.AddVolume(rv);
    s.Win->Render();
    const auto gpu = ReadRGB(s.Win);
    std::vector<double> rgba;
    ref.IntegrateImage(ClipToWorld(s.Ren)->GetData(), Size, Size, rgba);
    long covered = 0;
    for (int i = 0; i < Size * Size; ++i)
      covered += rgba[4 * i + 3] > 1.0 / 255;
    const ChannelError diff =
      ImageError(gpu, CompositeOver(rgba, std::vector<unsigned char>(gpu.size(), 0)));
    const double rms = diff.Rms, mx = diff.Max;
    std::cout << "Shaded: covered " << covered << " px, RMS " << rms << ", max " << mx
              << " of 255\n";
    Check(covered > 3000, "the shaded volume covers > 3000 pixels");
    Check(rms <= 0.6 && mx <= 4, "shaded image within RMS 0.6 / max 4 of the analytic expectation");
    ok = Failures() == 0;
  }
  else if (name == "Atlas")
  {
    // The brick atlas against plain 3-D textures, and its bookkeeping. 40 x 36 x 32 voxels in
    // bricks of 16 (stride 15): 3 x 3 x 3 level-0 bricks; with room for all, the image must equal
    // the unbricked one (same voxels, same trilinear filtering: the shared voxel layer makes
    // brick borders invisible). A budget of 4 bricks forces coarser levels: still every brick
    // within the budget and an image close to the full-resolution one.
    VolumeScene s;
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
    Check(mx <= 1, "the bricked image equals the plain one (max difference <= 1)");
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
  }
  else if (name == "Skipping")
  {
    // Empty-space skipping must not change the image: a sparse volume (two small blobs in
    // 72^3 voxels of air, and a second, rotated volume overlapping it) rendered with skipping
    // on and off, in both orders, post-classified and pre-integrated, bricked and plain.
    VolumeScene s;
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
          Check(covered > 3000 && mx <= 1, "skipping leaves the image unchanged (" + what + ")");
        }
    const std::string src = s.Mapper->GetFragmentShaderSource(1);
    Check(src.find("strataEmptyUntil") != std::string::npos,
      "the skipping shader probes the skip grid");
    s.Mapper->EmptySpaceSkippingOff();
    s.Win->Render();
    Check(s.Mapper->GetFragmentShaderSource(1).find("uSkip") == std::string::npos,
      "skipping off: no skipping code");
    s.Mapper->EmptySpaceSkippingOn();
    s.Mapper->SetClassification(C::PostClassification);
    s.Mapper->SetCompositeOrder(O::FrontToBack);
    s.Mapper->UseBrickAtlasOn();
    ok = CheckVolumeComparison(s.Compare("Skipping"), "Skipping", 0.4, 3, 3000) && ok;
    ok = ok && Failures() == 0;
  }
  else if (name == "Geometry")
  {
    // An opaque sphere inside a volume: rays stop at the scene's depth. Expected pixel:
    // C + (1 - A) scene, with (C, A) the reference integrated up to the depth of the scene
    // rendered without the volume, and `scene` that render's colour.
    VolumeScene s;
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
    vtkMultiVolumeReferenceIntegrator ref;
    ref.AddVolume(ToReferenceVolume(image, s.Volumes[0]));
    std::vector<double> stop(sceneDepth.begin(), sceneDepth.end()), rgba;
    ref.IntegrateImage(ClipToWorld(s.Ren)->GetData(), Size, Size, rgba, nullptr, stop.data());
    long hidden = 0;
    for (int i = 0; i < Size * Size; ++i)
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
  }
  else if (name == "ShaderSource")
  {
    // Only what a fragment needs: a fragment of one post-classified volume samples one volume
    // and reads no pre-integration table; one covered by two samples both; pre-integration
    // replaces the per-sample lookups; back-to-front has no early termination.
    VolumeScene s;
    s.Add(Blob(20, 20, 20, 1.0, 1.0, 1.0, 0, 0, 0, 1), MakeVolumeProperty(0));
    s.Add(Blob(20, 20, 20, 1.0, 1.0, 1.0, 10, 0, 0, 2), MakeVolumeProperty(1));
    s.UseMultiVolume();
    const double pos[3] = { -40, -60, 50 }, foc[3] = { 15, 10, 10 };
    s.Camera(pos, foc);
    s.Win->Render();
    const std::string one = s.Mapper->GetFragmentShaderSource(1);
    const std::string two = s.Mapper->GetFragmentShaderSource(2);
    auto has = [](const std::string& src, const char* what)
    { return src.find(what) != std::string::npos; };
    std::cout << "ShaderSource: " << s.Mapper->GetNumberOfFragments()
              << " fragments; 1-volume shader " << one.size() << " chars, 2-volume shader "
              << two.size() << " chars\n";
    Check(!one.empty() && !two.empty(), "shaders for 1 and 2 volumes were generated");
    Check(has(one, "strataScalarAt0") && !has(one, "strataScalarAt1"),
      "1-volume shader samples exactly one volume");
    Check(has(two, "strataScalarAt1") && !has(two, "strataScalarAt2"),
      "2-volume shader samples exactly two");
    Check(has(one, "uAtlas") && has(one, "uIndex0"),
      "bricked volumes are read through their index texture and the atlas");
    Check(!has(one, "uPreTable") && !has(one, "strataPair"),
      "post-classification has no pre-integration code");
    Check(!has(one, "uAccumulation") || has(one, "uTerminationOpacity"),
      "early termination only with its threshold");
    Check(!has(one, "ormal") && !has(one, "radient"), "unshaded: no gradient or normal code");
    s.Mapper->SetClassification(vtkMultiVolumeRayCastMapper::Classifications::PreIntegrated);
    s.Mapper->SetCompositeOrder(vtkMultiVolumeRayCastMapper::CompositeOrders::BackToFront);
    s.Win->Render();
    const std::string pre = s.Mapper->GetFragmentShaderSource(1);
    Check(has(pre, "uPreTable0") && !has(pre, "uTransfer0"),
      "pre-integrated shader reads the table, not the TF");
    Check(!has(pre, "uTerminationOpacity"), "back-to-front: no early termination code");
    // Level-of-detail feedback exists only where something is paged: in-core scenes carry no
    // image load/store, no extension line and no feedback lookups.
    for (const std::string* src : { &one, &two, &pre })
      Check(!has(*src, "#extension") && !has(*src, "uFeedback") && !has(*src, "gLack") &&
              !has(*src, "imageAtomic") && !has(*src, "imageStore"),
        "in core: no feedback code");
    // The same two volumes paged from pools: the shaders report the costliest lacking brick
    // of the feedback rays (fragments compare through the score image; front to back the
    // nearer wins a tie); with LevelOfDetailThreshold 0 level 0 is wanted everywhere, so there is
    // no footprint code.
    std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
    for (int i = 0; i < 2; ++i)
    {
      const std::string pool = OutputDirectory() + "/shader-source-" + std::to_string(i) + ".spp";
      vtkNew<vtkImageToPagePoolWriter> writer;
      writer->SetInputData(s.Images[i]);
      writer->SetFileName(pool.c_str());
      writer->SetPageSize(8);
      writer->Write();
      readers.push_back(vtkSmartPointer<vtkPagePoolReader>::New());
      readers.back()->SetFileName(pool.c_str());
      s.Mapper->SetInputConnection(i, readers.back()->GetOutputPort());
    }
    s.Mapper->SetClassification(vtkMultiVolumeRayCastMapper::Classifications::PostClassification);
    s.Mapper->SetCompositeOrder(vtkMultiVolumeRayCastMapper::CompositeOrders::FrontToBack);
    s.Win->Render();
    const std::string paged = s.Mapper->GetFragmentShaderSource(2);
    Check(has(paged, "#extension GL_ARB_shader_image_load_store : require") &&
            has(paged, "gLackVolume = better ? 1") && !has(paged, "uFeedbackSet2") &&
            has(paged, "gLackScore > imageLoad(uFeedbackScore") &&
            has(paged, "imageStore(uFeedback, texel") && has(paged, "strataPackPage") &&
            !has(paged, "gFootprint"),
      "paged: the 2-volume shader reports lacking bricks of both volumes into the feedback image");
    s.Mapper->SetCompositeOrder(vtkMultiVolumeRayCastMapper::CompositeOrders::BackToFront);
    s.Win->Render();
    const std::string pagedBack = s.Mapper->GetFragmentShaderSource(1);
    Check(has(pagedBack, "gLackScore >= imageLoad(uFeedbackScore") &&
            !has(pagedBack, "gTransmittance = (1.0 - prior)"),
      "paged, back to front: on equal cost the nearer (later) report wins; no transmittance is "
      "known");
    s.Mapper->LevelOfDetailFeedbackOff();
    s.Win->Render();
    const std::string pagedOff = s.Mapper->GetFragmentShaderSource(1);
    Check(!pagedOff.empty() && !has(pagedOff, "#extension") && !has(pagedOff, "uFeedback"),
      "paged with feedback off: no feedback code");
    for (int i = 0; i < 2; ++i)
      std::remove((OutputDirectory() + "/shader-source-" + std::to_string(i) + ".spp").c_str());
    ok = Failures() == 0;
  }
  else if (name == "Demo")
  {
    // The demo's scene (StrataVolumeScenes): the Bucky ball and two analytic volumes, against
    // the reference and a baseline image.
    vtkSmartPointer<vtkRenderWindow> win;
    vtkSmartPointer<vtkRenderer> ren;
    MakeWindow(win, ren, 160, 120);
    std::vector<std::pair<vtkSmartPointer<vtkImageData>, vtkSmartPointer<vtkVolume>>> inputs;
    auto multi = AddVolumeDemoScene(ren, TestDataDirectory(), inputs);
    if (!multi)
    {
      return EXIT_FAILURE;
    }
    std::vector<std::pair<vtkImageData*, vtkVolume*>> list;
    for (auto& p : inputs)
      list.emplace_back(p.first, p.second);
    ok = CheckVolumeComparison(
      CompareVolumesWithReference(win, ren, list, "VolumeDemo"), "VolumeDemo", 0.4, 2, 4000);
    auto* mapper = vtkMultiVolumeRayCastMapper::SafeDownCast(multi->GetMapper());
    std::cout << "VolumeDemo: " << mapper->GetNumberOfFragments() << " fragments\n";
    // Baseline: same thresholds as TestHeightFieldDemo (vtkTesting 0.5, and at most 0.2 % of
    // pixels off by more than 24/255).
    ok = CompareWithBaseline(win, "TestMultiVolumeDemo", 0.5) && ok;
  }
  else
  {
    std::cerr << "unknown case " << name << "\n";
    return EXIT_FAILURE;
  }
  if (output->Errors || output->Warnings)
  {
    std::cerr << "FAILED: VTK printed " << output->Errors << " errors and " << output->Warnings
              << " warnings\n";
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
}
