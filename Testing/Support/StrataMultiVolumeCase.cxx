// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataMultiVolumeCase.h"

#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataTestHelpers.h"

#include "vtkCamera.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>

namespace strata_test
{
VolumeScene::VolumeScene(const std::string& imageDirectory)
  : ImageDirectory(imageDirectory)
{
  MakeWindow(this->Win, this->Ren, MultiVolumeCaseSize, MultiVolumeCaseSize);
  this->Mapper->SetSampleDistance(0.25);
  this->Multi->SetMapper(this->Mapper);
}

vtkVolume* VolumeScene::Add(vtkImageData* image,
  vtkVolumeProperty* property,
  vtkTransform* transform)
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

void VolumeScene::UseSingleVolume()
{
  this->Volumes[0]->SetMapper(this->Mapper);
  this->Ren->AddVolume(this->Volumes[0]);
}

void VolumeScene::UseMultiVolume()
{
  this->Ren->AddVolume(this->Multi);
}

void VolumeScene::Camera(const double pos[3], const double focal[3])
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

VolumeComparison VolumeScene::Compare(const std::string& name, int raysPerPixel)
{
  std::vector<std::pair<vtkImageData*, vtkVolume*>> list;
  for (size_t i = 0; i < this->Images.size(); ++i)
    list.emplace_back(this->Images[i], this->Volumes[i]);
  return CompareVolumesWithReference(
    this->Win, this->Ren, list, name, this->ImageDirectory, 1.0 / 16.0, raysPerPixel, this->Mapper);
}

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

void AddTwoVolumes(VolumeScene& s, double ox, double oy)
{
  s.Add(Blob(40, 36, 32, 1.0, 1.0, 1.0, ox, oy, 0, 1), MakeVolumeProperty(0));
  vtkNew<vtkTransform> t;
  t->Translate(ox + 30, oy + 10, 4);
  t->RotateZ(30);
  t->Translate(-ox, -oy, 0);
  s.Add(Blob(24, 20, 18, 1.6, 1.5, 1.4, ox, oy, 0, 2), MakeVolumeProperty(1), t);
  s.UseMultiVolume();
  const double pos[3] = { ox - 50, oy - 70, 80 }, foc[3] = { ox + 30, oy + 25, 14 };
  s.Camera(pos, foc);
}

VolumeComparison RenderTwoVolumes(double ox,
  double oy,
  const std::string& tag,
  const std::string& imageDirectory)
{
  VolumeScene s(imageDirectory);
  AddTwoVolumes(s, ox, oy);
  auto r = s.Compare(tag);
  std::cout << tag << ": " << s.Mapper->GetNumberOfFragments() << " fragments\n";
  return r;
}

TranslucentPlane::TranslucentPlane(const double o[3],
  const double p1[3],
  const double p2[3],
  const double rgb[3])
{
  this->Source->SetOrigin(o[0], o[1], o[2]);
  this->Source->SetPoint1(p1[0], p1[1], p1[2]);
  this->Source->SetPoint2(p2[0], p2[1], p2[2]);
  this->Mapper->SetInputConnection(this->Source->GetOutputPort());
  this->Actor->SetMapper(this->Mapper);
  vtkProperty* p = this->Actor->GetProperty();
  p->SetColor(rgb[0], rgb[1], rgb[2]);
  p->SetAmbient(1.0);
  p->SetDiffuse(0.0);
  p->SetSpecular(0.0);
  p->SetOpacity(0.4);
  for (int i = 0; i < 3; ++i)
  {
    this->Surface.Corner[i] = o[i];
    this->Surface.Edge1[i] = p1[i] - o[i];
    this->Surface.Edge2[i] = p2[i] - o[i];
    this->Surface.Color[i] = 0.4 * rgb[i];
  }
  this->Surface.Color[3] = 0.4;
}

void AddSceneVolumes(VolumeScene& s, strata::MultiVolumeReferenceIntegrator& ref, bool volumes)
{
  ref.SetStepFraction(1.0 / 16.0);
  for (size_t i = 0; i < s.Images.size(); ++i)
  {
    auto v = ToReferenceVolume(s.Images[i], s.Volumes[i], s.Mapper, static_cast<int>(i));
    if (!volumes)
      std::fill(v.Classification.Opacity.begin(), v.Classification.Opacity.end(), 0.0);
    ref.AddVolume(std::move(v));
  }
}

std::vector<double> ReferenceWithSurfaces(VolumeScene& s,
  const std::vector<strata::MultiVolumeReferenceIntegrator::Surface>& surfaces,
  bool volumes,
  const double* stop,
  std::vector<bool>* edges)
{
  using Ref = strata::MultiVolumeReferenceIntegrator;
  const int rays = s.Mapper->GetRaysPerPixel(), n = MultiVolumeCaseSize;
  Ref ref;
  AddSceneVolumes(s, ref, volumes);
  for (const Ref::Surface& surface : surfaces)
    ref.AddSurface(surface);
  std::vector<double> rgba(4 * size_t(n) * n, 0.0), one, first;
  for (int ray = 0; ray < rays; ++ray)
  {
    ref.IntegrateImage(SubPixelClipToWorld(ClipToWorld(s.Ren), ray, rays, n, n)->GetData(),
      n,
      n,
      one,
      nullptr,
      stop);
    for (size_t i = 0; i < one.size(); ++i)
      rgba[i] += one[i] / rays;
    if (ray == 0)
      first = one;
    if (edges && ray == 0)
      edges->assign(size_t(n) * n, false);
    for (size_t i = 0; edges && i < edges->size(); ++i)
      for (int c = 0; c < 4; ++c)
        (*edges)[i] = (*edges)[i] || std::abs(one[4 * i + c] - first[4 * i + c]) > 1e-9;
  }
  return rgba;
}

int CaseResult(bool ok, const CapturingOutputWindow* output)
{
  if (output->Errors || output->Warnings)
  {
    std::cerr << "FAILED: VTK printed " << output->Errors << " errors and " << output->Warnings
              << " warnings\n";
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}

std::vector<unsigned char> RenderWithVtkGPUMapper(VolumeScene& s,
  vtkImageData* image,
  vtkVolumeProperty* property,
  int blendMode,
  const std::function<void(vtkGPUVolumeRayCastMapper*)>& configure)
{
  vtkSmartPointer<vtkRenderWindow> win;
  vtkSmartPointer<vtkRenderer> ren;
  MakeWindow(win, ren, MultiVolumeCaseSize, MultiVolumeCaseSize);
  ren->SetBackground(128.0 / 255.0, 128.0 / 255.0, 128.0 / 255.0);
  vtkNew<vtkGPUVolumeRayCastMapper> vtkMapper;
  vtkMapper->SetInputData(image);
  vtkMapper->AutoAdjustSampleDistancesOff();
  vtkMapper->SetSampleDistance(0.25);
  vtkMapper->SetBlendMode(blendMode);
  if (configure)
    configure(vtkMapper);
  vtkNew<vtkVolume> vol;
  vol->SetMapper(vtkMapper);
  vol->SetProperty(property);
  ren->AddVolume(vol);
  ren->SetActiveCamera(s.Ren->GetActiveCamera());
  win->Render();
  return ReadRGB(win);
}

void CheckAgainstVtkGPUMapper(const std::vector<unsigned char>& ours,
  const std::vector<unsigned char>& theirs,
  const std::string& name,
  const std::string& directory)
{
  const ChannelError diff = ImageError(ours, theirs);
  const int w = MultiVolumeCaseSize;
  WritePNG(directory + "/" + name + "-strata.png", ours, w, w);
  WritePNG(directory + "/" + name + "-vtk.png", theirs, w, w);
  std::cout << name << " vs vtkGPUVolumeRayCastMapper: RMS " << diff.Rms << ", max " << diff.Max
            << " of 255, " << PixelsOff(ours, theirs, 2) << " pixels off by more than 2\n";
  Check(diff.Rms <= 0.6 && diff.Max <= 6,
    name + " matches vtkGPUVolumeRayCastMapper within RMS 0.6 / max 6");
  Check(PixelsOff(ours, std::vector<unsigned char>(ours.size(), 128), 2) > 2000,
    name + " draws something (over 2000 pixels not background)");
}

vtkSmartPointer<vtkPagePoolReader> WritePagedTwin(vtkImageData* image,
  const std::string& path,
  int pageSize)
{
  vtkNew<vtkImageToPagePoolWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->SetPageSize(pageSize);
  Check(writer->Write() != 0, "the pool " + path + " is written");
  auto reader = vtkSmartPointer<vtkPagePoolReader>::New();
  reader->SetFileName(path.c_str());
  return reader;
}

int RenderUntilConverged(VolumeScene& s, int maxFrames)
{
  for (int f = 1; f <= maxFrames; ++f)
  {
    s.Win->Render();
    if (s.Mapper->GetPagingStatistics().Converged)
      return f;
    s.Mapper->WaitForPages(1.0);
  }
  return -1;
}
}
