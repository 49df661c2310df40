// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Translucent geometry among the volumes (vtkMultiVolumeRayCastMapper::AddTranslucentActor):
// planes of opacity 0.4 crossing two overlapping volumes, in front of them, behind them, and
// with opaque geometry, compared pixel by pixel with the reference integrator, whose surfaces
// are composited at their exact depths (strata::MultiVolumeReferenceIntegrator::Surface); and the
// two crossing planes with the first volume drawn in each other blend mode (MIP, MinIP,
// average, additive: its reduced layer composited at its own depth in ray order with the
// surfaces; isosurface).
//
// Bounds, in 8-bit units over all pixels (grey background): those of the volume cases, RMS 0.4
// and max 2 (StrataMultiVolumeCase.h: 8-bit output, quarter-voxel midpoint samples). The
// surfaces add no discretisation of their own: the reference composites them at their exact
// crossing and the ray caster splits its step there, with the layer's depth from the
// rasteriser in float (measured RMS 0.22-0.30, max 1.27 in all five cases). A reduced volume's
// layer or an isosurface and a surface at nearly the same depth (the average's and the
// additive's layer lie on the box's face, which the planes cross; a MIP extreme near a plane;
// the contour where a plane crosses it) may be composited in the other order than the
// reference's, a pixel along that line off by up to 102 (opaque grey over or under the plane):
// rule 4 of StrataImagePolicy.h, at most ImagePolicy::CrossingPixels(16384) = 16 pixels (0.1 %)
// may be off by more than 2, measured 8 / 0 / 10 / 10 / 0 (MIP, MinIP, average, additive,
// isosurface) on llvmpipe, and 1 in the isosurface case on an H200 (a plane crossing the
// contour); the rest RMS 0.21-0.29, max 1.35. The two planes crossing each other take the same
// allowance (1 pixel off by more than 2 on the H200, 0 on llvmpipe).
// Before the fix that orders the two kinds where a fragment has only layers, the
// average and the additive cases were RMS 21.5 off: all of their layers went in before the
// surfaces in front of them. With two rays per
// pixel the layers are still peeled once per pixel, at its centre, so pixels whose sub-pixel
// rays cross different surfaces (146 edge pixels of 16384 here, off by up to 34) are left out
// of that case's comparison: surfaces are not anti-aliased. The test can fail:
// the rendering is compared with the two wrong models too, the volumes without the surfaces
// (RMS 8.9-25.7 measured) and the surfaces blended over the volumes' composite, what a renderer
// drawing the translucent actors after the volumes gives (RMS 7.7-16.1 where the planes cross
// or lie behind volumes); each must be off by more than 2 RMS, five times the bound.
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "StrataMultiVolumeReferenceIntegrator.h"
#include "vtkActor.h"
#include "vtkContourValues.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using namespace strata_test;
using Ref = strata::MultiVolumeReferenceIntegrator;

using Plane = TranslucentPlane;

struct Images
{
  std::vector<unsigned char> Gpu;
  std::vector<double> Expected, NoSurfaces, SurfacesOver; ///< 8-bit units
  /// Pixels whose sub-pixel rays cross different surfaces (a surface's edge): the layers are
  /// peeled once per pixel, at its centre, so there several rays per pixel do not anti-alias.
  std::vector<bool> Edges;
};

/// Renders the scene with `planes` given to the mapper; the expected image is the reference
/// with the planes' surfaces over the scene rendered without the volumes (grey, plus any opaque
/// actor), stopped at that render's depth.
Images Render(VolumeScene& s, const std::vector<Plane*>& planes, const std::string& name)
{
  s.Ren->SetBackground(128 / 255.0, 128 / 255.0, 128 / 255.0);
  s.Mapper->RemoveAllTranslucentActors();
  s.Multi->VisibilityOff();
  s.Win->Render();
  const auto sceneRgb = ReadRGB(s.Win);
  const auto depth = ReadDepth(s.Win);
  s.Multi->VisibilityOn();
  std::vector<Ref::Surface> surfaces;
  for (Plane* p : planes)
  {
    s.Mapper->AddTranslucentActor(p->Actor);
    surfaces.push_back(p->Surface);
  }
  s.Win->Render();
  Images r;
  r.Gpu = ReadRGB(s.Win);
  const std::vector<double> stop(depth.begin(), depth.end());
  r.Expected = CompositeOver(ReferenceWithSurfaces(s, surfaces, true, stop.data()), sceneRgb);
  const std::vector<double> volumesOnly = ReferenceWithSurfaces(s, {}, true, stop.data());
  r.NoSurfaces = CompositeOver(volumesOnly, sceneRgb);
  // The surfaces blended over the volumes' composite: S + (1 - S.a) V.
  std::vector<double> over = ReferenceWithSurfaces(s, surfaces, false, stop.data(), &r.Edges);
  r.SurfacesOver = CompositeOver(Over(over, volumesOnly), sceneRgb);
  WriteComparisonImages(
    s.ImageDirectory, name, r.Gpu, r.Expected, MultiVolumeCaseSize, MultiVolumeCaseSize);
  return r;
}

/// Asserts the rendering within RMS 0.4 and max `maxBound`, and that the wrong models asked for
/// are off by more than 2 RMS (for a plane in front of every volume, "over the volumes" is the
/// right model). Up to `outliers` pixels off by more than `maxBound` are counted and left out
/// of the RMS (a reduced volume's layer or an isosurface and a surface at nearly the same
/// depth: ImagePolicy::CrossingPixels of the window's pixels).
void CheckCase(const Images& r,
  const std::string& name,
  bool checkOver,
  double maxBound = 2.0,
  long outliers = 0)
{
  // Edge pixels (only with several rays per pixel) left out of the comparison with the reference.
  std::vector<unsigned char> gpu;
  std::vector<double> expected;
  long edges = 0, off = 0;
  for (size_t i = 0; i < r.Edges.size(); ++i)
  {
    double worst = 0.0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(r.Gpu[3 * i + c] - r.Expected[3 * i + c]));
    const bool outlier = !r.Edges[i] && worst > maxBound;
    edges += r.Edges[i];
    off += outlier;
    for (int c = 0; c < 3 && !r.Edges[i] && !outlier; ++c)
    {
      gpu.push_back(r.Gpu[3 * i + c]);
      expected.push_back(r.Expected[3 * i + c]);
    }
  }
  const ChannelError e = ImageError(gpu, expected);
  const ChannelError none = ImageError(r.Gpu, r.NoSurfaces);
  const ChannelError over = ImageError(r.Gpu, r.SurfacesOver);
  std::cout << name << ": RMS " << e.Rms << ", max " << e.Max << " of 255 (" << edges
            << " edge pixels left out, " << off << " pixels off by more than " << maxBound
            << "); without surfaces RMS " << none.Rms << "; surfaces over the volumes RMS "
            << over.Rms << "\n";
  Check(e.Rms <= 0.4 && e.Max <= maxBound && off <= outliers,
    name + ": within RMS 0.4 / max " + std::to_string(maxBound) + " of the reference (at most " +
      std::to_string(outliers) + " pixels more)");
  Check(none.Rms > 2.0, name + ": differs from the volumes without the surfaces by > 2 RMS");
  if (checkOver)
    Check(over.Rms > 2.0, name + ": differs from the surfaces blended over the volumes by > 2 RMS");
}
}

int TestMultiVolumeTranslucentGeometry(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  VolumeScene s(paths.Output);
  AddTwoVolumes(s);

  // No translucent actor: no surface code in the shaders.
  s.Win->Render();
  Check(s.Mapper->GetShaderSource(2).find("Surface") == std::string::npos,
    "without translucent actors the two-volume fragment has no surface code");

  // Two planes through both volumes: a vertical one across the overlap and a tilted one.
  const double red[3] = { 1.0, 0.2, 0.1 }, blue[3] = { 0.1, 0.3, 1.0 };
  const double o1[3] = { -5, 18, -5 }, a1[3] = { 60, 18, -5 }, b1[3] = { -5, 18, 40 };
  Plane vertical(o1, a1, b1, red);
  const double o2[3] = { 20, -10, -5 }, a2[3] = { 20, 50, -5 }, b2[3] = { 45, -10, 40 };
  Plane tilted(o2, a2, b2, blue);
  // The two planes cross each other inside the volumes: at most rule 4's crossing pixels where
  // they meet (1 pixel off by more than 2 on an H200, 0 on llvmpipe).
  const long crossing =
    ImagePolicy::CrossingPixels(long(MultiVolumeCaseSize) * MultiVolumeCaseSize);
  CheckCase(Render(s, { &vertical, &tilted }, "TranslucentCrossing"),
    "TranslucentCrossing",
    true,
    2.0,
    crossing);
  const std::string source = s.Mapper->GetShaderSource(2);
  Check(source.find("strataSurfacesBefore") != std::string::npos,
    "with translucent actors the two-volume fragment composites surface layers");

  // The other blend modes under the same planes: volume 0 reduced (its result one layer at its
  // own depth) or an isosurface, volume 1 composite; the surfaces are composited in ray order
  // with that layer and the media of volume 1. Each crosses the planes: rule 4's allowance.
  const std::pair<int, const char*> modes[] = {
    { vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, "Maximum" },
    { vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, "Minimum" },
    { vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, "Average" },
    { vtkVolumeMapper::ADDITIVE_BLEND, "Additive" },
    { vtkVolumeMapper::ISOSURFACE_BLEND, "Isosurface" },
  };
  s.Volumes[0]->GetProperty()->GetIsoSurfaceValues()->SetValue(0, 120.0);
  for (const auto& [mode, label] : modes)
  {
    s.Mapper->SetInputBlendMode(0, mode);
    const std::string name = std::string("Translucent") + label;
    CheckCase(Render(s, { &vertical, &tilted }, name), name, true, 2.0, crossing);
  }
  s.Mapper->SetInputBlendMode(0, -1);

  // Two rays per pixel with pre-integration: ray 1's progress is the second 3 bits.
  s.Mapper->SetRaysPerPixel(2);
  s.Mapper->SetClassification(vtkMultiVolumeRayCastMapper::Classifications::PreIntegrated);
  CheckCase(
    Render(s, { &vertical, &tilted }, "TranslucentRays"), "TranslucentRays", true, 2.0, crossing);
  s.Mapper->SetRaysPerPixel(1);
  s.Mapper->SetClassification(vtkMultiVolumeRayCastMapper::Classifications::PostClassification);

  // One plane in front of both volumes (towards the camera) and one behind them.
  const double o3[3] = { -30, -30, 40 }, a3[3] = { 10, -60, 40 }, b3[3] = { -30, -30, 70 };
  Plane front(o3, a3, b3, red);
  CheckCase(Render(s, { &front }, "TranslucentFront"), "TranslucentFront", false);
  const double o4[3] = { 40, 60, -30 }, a4[3] = { 100, 20, -30 }, b4[3] = { 40, 60, 40 };
  Plane behind(o4, a4, b4, blue);
  CheckCase(Render(s, { &behind }, "TranslucentBehind"), "TranslucentBehind", true);

  // Opaque geometry still stops the rays and hides the translucent plane behind it.
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
  CheckCase(Render(s, { &vertical }, "TranslucentOpaque"), "TranslucentOpaque", true);
  s.Ren->RemoveActor(ball);

  return CaseResult(Failures() == 0, output);
}
