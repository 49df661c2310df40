// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Cropping per volume (vtkVolumeMapper's 27 regions; the mapper's own settings or
// vtkMultiVolumeRayCastMapper::SetInputCropping per port), compared pixel by pixel with the
// double-precision reference integrator, which cuts rays exactly at the crop planes, and with
// vtkGPUVolumeRayCastMapper; the generated source has crop code only for cropped volumes.
//
// Bounds against the reference, in 8-bit units: the composite cases' RMS 0.4 / max 2
// (StrataMultiVolumeCase.h) do not hold at a crop plane, where the GPU decides a whole lattice step
// by its midpoint and the reference cuts the step: up to half a step of medium (opacity 0.3 per
// unit at most, 1/8 voxel: under 4 %, about 10 units on a bright pixel) may fall on the wrong side
// along the planes seen edge on. RMS 0.6, max 12. A MIP ray that crosses a plane at a grazing
// angle moves its crossing by half a step over the sine of the angle, and its maximum with it where
// the data rise along the ray: one pixel measured 24 off, the next 8: max 32 for MIP. Every case
// also differs from the uncropped image by more than RMS 2, so that cropping nothing fails.
// Cropping the wrong region (a flag bit off by one
// region, planes in world instead of data coordinates, which here differ by the origin) moves a
// whole slab: tens of units RMS.
#include "StrataHeightFieldScenes.h" // For MakeWindow
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "vtkContourValues.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace strata_test;

// Planes through the blob volume of SingleVolume (origin (3, -2, 1), 40 x 36 x 32 points of
// spacing (1, 1.1, 0.9)), in its data coordinates.
const double Planes[6] = { 13.0, 31.0, 6.0, 30.0, 9.0, 24.0 };

VolumeScene& SingleScene(VolumeScene& s)
{
  s.Add(Blob(40, 36, 32, 1.0, 1.1, 0.9, 3, -2, 1, 1), MakeVolumeProperty(0));
  s.UseSingleVolume();
  const double pos[3] = { -40, -60, 70 }, foc[3] = { 20, 20, 14 };
  s.Camera(pos, foc);
  return s;
}

void Single(const TestPaths& paths, int flags, const std::string& name, int mode, double max)
{
  VolumeScene s(paths.Output);
  SingleScene(s);
  s.Volumes[0]->GetProperty()->GetIsoSurfaceValues()->SetValue(0, 50.0);
  s.Volumes[0]->GetProperty()->GetIsoSurfaceValues()->SetValue(1, 70.0);
  s.Mapper->SetBlendMode(mode);
  s.Ren->SetBackground(128.0 / 255.0, 128.0 / 255.0, 128.0 / 255.0);
  s.Win->Render();
  const auto uncropped = ReadRGB(s.Win);
  s.Mapper->CroppingOn();
  s.Mapper->SetCroppingRegionPlanes(Planes);
  s.Mapper->SetCroppingRegionFlags(flags);
  const VolumeComparison c = s.Compare(name);
  Check(CheckVolumeComparison(c, name, 0.6, max, 300), name + " matches the reference");
  const ChannelError change = ImageError(c.Gpu, uncropped);
  std::cout << name << ": RMS " << change.Rms << " from the uncropped image\n";
  Check(change.Rms > 2.0, name + " differs from the uncropped image by more than RMS 2");
}

// Two overlapping volumes, only the second cropped (its own setting; the mapper's cropping, on,
// is overridden for the first by an uncropped one of its own).
void PerVolume(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  s.Add(Blob(40, 36, 32, 1.0, 1.0, 1.0, 0, 0, 0, 1), MakeVolumeProperty(0));
  vtkNew<vtkTransform> t;
  t->Translate(30, 10, 4);
  t->RotateZ(30);
  s.Add(Blob(24, 20, 18, 1.6, 1.5, 1.4, 0, 0, 0, 2), MakeVolumeProperty(1), t);
  s.UseMultiVolume();
  const double second[6] = { 8.0, 30.0, -1.0, 20.0, 5.0, 30.0 };
  s.Mapper->CroppingOn();
  s.Mapper->SetCroppingRegionPlanes(Planes);
  s.Mapper->SetInputCropping(0, false, Planes, VTK_CROP_SUBVOLUME);
  s.Mapper->SetInputCropping(1, true, second, VTK_CROP_INVERTED_CROSS);
  double planes[6];
  int flags = 0;
  Check(!s.Mapper->GetEffectiveCropping(0, planes, flags) &&
          s.Mapper->GetEffectiveCropping(1, planes, flags) && flags == VTK_CROP_INVERTED_CROSS,
    "port 0 uncropped by its own setting, port 1 cropped by its own");
  const double pos[3] = { -50, -70, 80 }, foc[3] = { 30, 25, 14 };
  s.Camera(pos, foc);
  Check(CheckVolumeComparison(s.Compare("CropPerVolume"), "CropPerVolume", 0.6, 12, 3000),
    "one of two overlapping volumes cropped matches the reference");
  const std::string two = s.Mapper->GetShaderSource(2);
  Check(
    two.find("strataCrop1") != std::string::npos && two.find("strataCrop0") == std::string::npos,
    "only the cropped volume has crop code");
  s.Mapper->RemoveInputCropping(0);
  s.Mapper->RemoveInputCropping(1);
  s.Mapper->CroppingOff();
  s.Win->Render();
  Check(s.Mapper->GetShaderSource(2).find("strataCrop") == std::string::npos,
    "without cropping no crop code");
}

// Paged from a pool (its header's origin and spacing place the planes), converged: the same
// image as the reference of the full data.
void Paged(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  SingleScene(s);
  const std::string pool = paths.Output + "/crop-paged.spp";
  auto reader = WritePagedTwin(s.Images[0], pool, 8);
  s.Mapper->SetInputConnection(0, reader->GetOutputPort());
  s.Mapper->CroppingOn();
  s.Mapper->SetCroppingRegionPlanes(Planes);
  s.Mapper->SetCroppingRegionFlagsToInvertedCross();
  Check(RenderUntilConverged(s, 60) > 0, "the paged volume converges");
  Check(CheckVolumeComparison(s.Compare("CropPaged"), "CropPaged", 0.6, 12, 1500),
    "a paged cropped volume matches the reference");
}

// VTK's own mapper with the same cropping: it decides per sample too, from each ray's entry.
// Measured RMS 0.68, max 7 (the planes' edge-on pixels, where the two lattices put a step on
// either side of them); bound RMS 0.8, max 24.
void AgainstVtk(const TestPaths& paths)
{
  VolumeScene s(paths.Output);
  SingleScene(s);
  s.Mapper->CroppingOn();
  s.Mapper->SetCroppingRegionPlanes(Planes);
  s.Mapper->SetCroppingRegionFlagsToCross();
  s.Ren->SetBackground(128.0 / 255.0, 128.0 / 255.0, 128.0 / 255.0);
  s.Win->Render();
  const auto ours = ReadRGB(s.Win);
  const auto theirs = RenderWithVtkGPUMapper(s,
    s.Images[0],
    s.Volumes[0]->GetProperty(),
    vtkVolumeMapper::COMPOSITE_BLEND,
    [](vtkGPUVolumeRayCastMapper* m)
    {
      m->CroppingOn();
      m->SetCroppingRegionPlanes(Planes);
      m->SetCroppingRegionFlagsToCross();
    });
  const int w = MultiVolumeCaseSize;
  WritePNG(paths.Output + "/CropVtk-strata.png", ours, w, w);
  WritePNG(paths.Output + "/CropVtk-vtk.png", theirs, w, w);
  const ChannelError diff = ImageError(ours, theirs);
  std::cout << "Cross crop vs vtkGPUVolumeRayCastMapper: RMS " << diff.Rms << ", max " << diff.Max
            << " of 255\n";
  Check(diff.Rms <= 0.8 && diff.Max <= 24,
    "cross crop matches vtkGPUVolumeRayCastMapper within RMS 0.8 / max 24");
}
}

int TestMultiVolumeCropping(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  const int composite = vtkVolumeMapper::COMPOSITE_BLEND;
  std::vector<SubTest> parts = {
    { "subvolume", [&] { Single(paths, VTK_CROP_SUBVOLUME, "CropSubVolume", composite, 12); } },
    { "cross", [&] { Single(paths, VTK_CROP_CROSS, "CropCross", composite, 12); } },
    { "inverted cross",
      [&] { Single(paths, VTK_CROP_INVERTED_CROSS, "CropInvertedCross", composite, 12); } },
    { "two odd regions",
      [&] { Single(paths, (1 << 14) | (1 << 22), "CropRegions14And22", composite, 12); } },
    { "MIP inverted cross",
      [&]
      {
        Single(paths,
          VTK_CROP_INVERTED_CROSS,
          "CropInvertedCrossMaximum",
          vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
          32);
      } },
    { "isosurface subvolume",
      [&] {
        Single(
          paths, VTK_CROP_SUBVOLUME, "CropSubVolumeIso", vtkVolumeMapper::ISOSURFACE_BLEND, 12);
      } },
    { "per volume", [&] { PerVolume(paths); } },
    { "paged", [&] { Paged(paths); } },
    { "against VTK", [&] { AgainstVtk(paths); } },
    { "no VTK errors or warnings", [output] { CheckNoVtkMessages(output); } },
  };
  return RunSubTests(parts, Failures);
}
