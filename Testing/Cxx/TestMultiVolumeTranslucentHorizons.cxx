// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Translucent horizons inside volumes, the combined model of issue 15: a stack of three
// horizons (vtkStackedHeightFieldMapper) crossing two overlapping volumes at UTM coordinates,
// its actor in the renderer (the opaque horizons) and given to the volume ray caster
// (AddTranslucentActor: the translucent ones, peeled into its surface layers). Compared pixel
// by pixel with the double-precision reference: strata::MultiVolumeReferenceIntegrator with the
// horizons' every crossing (strata::HeightFieldReferenceCaster::CastAll) composited at its exact
// depth, stopped at the opaque scene's depth.
//
// The stack, on a 2 m grid around the volumes: H0 (opacity 0.45) a tilted, undulating surface
// with a hole of radius 5 m inside the first volume; H1 (0.35) equal to H0 where x < 28 m
// (the two touch over a region: one merged layer there, composited H0 then H1, and through
// H0's hole H1 alone) and rising above it beyond; H2 a deeper surface, opaque in the first case
// (it stops the rays) and translucent (0.5) in the others.
//
// Cases: looking down (H0, H1 translucent, H2 opaque), looking up from below (all three
// translucent: the reverse order), H2 flat and translucent exactly on a brick face (z = 16)
// with the volumes paged from page pools of 16^3 bricks and in core, and the translucent horizons
// without a volume ray caster (the renderer's translucent pass blends them front to back, against
// the reference with transparent volumes). Bounds, in 8-bit units over all pixels: those of the
// translucent actors, RMS 0.4 and max 2 (TestMultiVolumeTranslucentGeometry), the max off the
// reference's edges, where a silhouette or hole rim within float rounding of a pixel centre puts
// the GPU's ray and the reference's on different sides (at most 2 such pixels); the horizons add no
// discretisation: each layer is composited at its crossing found by the caster's search and
// bisection, with the layer's depth in float. The test can fail: the rendering is compared with the
// volumes without the horizons and with the horizons blended over the volumes' composite, each must
// be off by more than 2 RMS; H1 drawn where it touches H0 but unmerged (one layer lost) is
// checked through the merged pixels' count and error.
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataMultiVolumeCase.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"
#include "StrataVolumeScenes.h"

#include "StrataMultiVolumeReferenceIntegrator.h"
#include "vtkActor.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageToPagePoolWriter.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"
#include "vtkTransform.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <thread>
#include <vector>

namespace
{
using namespace strata_test;
using Ref = strata::MultiVolumeReferenceIntegrator;

const double OX = 456000.0, OY = 6780000.0; // UTM easting, northing of the volumes' corner
const double Colors[3][3] = { { 0.95, 0.35, 0.15 }, { 0.15, 0.45, 0.95 }, { 0.35, 0.8, 0.3 } };

double Base(double x, double y)
{
  return 14.0 + 0.12 * x - 0.08 * y + 2.0 * std::sin(0.2 * x);
}

/// Horizon k on 36 x 30 points at 2 m from (OX - 6, OY - 6); heights are world z.
vtkSmartPointer<vtkImageData> Horizon(int k)
{
  std::vector<float> z(36 * 30);
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 36; ++i)
    {
      const double x = -6.0 + 2.0 * i, y = -6.0 + 2.0 * j;
      double h = Base(x, y);
      if (k == 0 && std::hypot(x - 15.0, y - 18.0) < 5.0)
        h = std::numeric_limits<double>::quiet_NaN();
      if (k == 1)
        h += std::max(0.0, 0.3 * (x - 28.0));
      if (k == 2)
        h = 5.0 + 0.1 * y + 0.05 * x;
      z[j * 36 + i] = static_cast<float>(h);
    }
  return MakeHorizon(36, 30, OX - 6.0, OY - 6.0, 2.0, 2.0, 0.0, z);
}

struct Images
{
  std::vector<unsigned char> Gpu;
  std::vector<double> Expected, NoHorizons, HorizonsOver; ///< 8-bit units
};

/// The reference of the scene's volumes (transparent with `volumes` false) with the horizons'
/// crossings when `horizons`, stopped at the window depths `stop`.
std::vector<double> Reference(VolumeScene& s,
  vtkStackedHeightFieldMapper* hf,
  bool volumes,
  bool horizons,
  const double* stop)
{
  Ref ref;
  AddSceneVolumes(s, ref, volumes);
  if (horizons)
    ref.AddSurfaceCrossings(HorizonCrossings(hf,
      { { Colors[0][0], Colors[0][1], Colors[0][2] },
        { Colors[1][0], Colors[1][1], Colors[1][2] },
        { Colors[2][0], Colors[2][1], Colors[2][2] } }));
  std::vector<double> rgba;
  ref.IntegrateImage(
    ClipToWorld(s.Ren)->GetData(), MultiVolumeCaseSize, MultiVolumeCaseSize, rgba, nullptr, stop);
  return rgba;
}

/// Renders the scene: first the opaque part alone (volumes hidden, the horizon actor forced
/// opaque: its opaque horizons) for the reference's background and stop depth, then all, the
/// actor given to the ray caster when `peeled` (else the renderer's translucent pass blends it
/// and the volumes are hidden).
Images Render(VolumeScene& s,
  vtkStackedHeightFieldMapper* hf,
  vtkActor* actor,
  bool peeled,
  const std::string& name,
  bool paged = false)
{
  s.Ren->SetBackground(128 / 255.0, 128 / 255.0, 128 / 255.0);
  s.Mapper->RemoveAllTranslucentActors();
  s.Multi->VisibilityOff();
  actor->ForceOpaqueOn();
  s.Win->Render();
  const auto sceneRgb = ReadRGB(s.Win);
  const auto depth = ReadDepth(s.Win);
  actor->ForceOpaqueOff();
  s.Multi->SetVisibility(peeled);
  if (peeled)
    s.Mapper->AddTranslucentActor(actor);
  // Paged volumes: until the cut has converged (then the image is the in-core one).
  for (int frame = 0; frame < 400; ++frame)
  {
    s.Win->Render();
    if (!paged || s.Mapper->GetPagingStatistics().Converged)
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  Images r;
  r.Gpu = ReadRGB(s.Win);
  const std::vector<double> stop(depth.begin(), depth.end());
  r.Expected = CompositeOver(Reference(s, hf, peeled, true, stop.data()), sceneRgb);
  const std::vector<double> volumesOnly = Reference(s, hf, peeled, false, stop.data());
  r.NoHorizons = CompositeOver(volumesOnly, sceneRgb);
  std::vector<double> over = Reference(s, hf, false, true, stop.data());
  r.HorizonsOver = CompositeOver(Over(over, volumesOnly), sceneRgb);
  WriteComparisonImages(
    s.ImageDirectory, name, r.Gpu, r.Expected, MultiVolumeCaseSize, MultiVolumeCaseSize);
  s.Multi->VisibilityOn();
  return r;
}

/// Pixels on an edge of the reference (a channel more than 8 from a 4-neighbour's): there a
/// horizon's silhouette, hole rim or boundary can pass within float rounding of the pixel
/// centre, and the GPU's float ray and the reference's double one fall on different sides.
std::vector<bool> EdgePixels(const std::vector<double>& expected)
{
  const int n = MultiVolumeCaseSize;
  std::vector<bool> edge(size_t(n) * n, false);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
    {
      const int nb[4][2] = { { x - 1, y }, { x + 1, y }, { x, y - 1 }, { x, y + 1 } };
      for (const auto& q : nb)
      {
        if (q[0] < 0 || q[0] >= n || q[1] < 0 || q[1] >= n)
          continue;
        for (int c = 0; c < 3; ++c)
          if (std::abs(expected[3 * (size_t(y) * n + x) + c] -
                       expected[3 * (size_t(q[1]) * n + q[0]) + c]) > 8.0)
            edge[size_t(y) * n + x] = true;
      }
    }
  return edge;
}

/// RMS over all pixels within 0.4, max 2 off the reference's edges, and at most 2 pixels (of
/// 16384) off by more than 2, on an edge (measured: 0, 0 and 1, by 32, in the three cases);
/// both wrong models off by > 2 RMS.
void CheckCase(const Images& r, const std::string& name, bool checkWrongModels)
{
  const ChannelError e = ImageError(r.Gpu, r.Expected);
  const std::vector<bool> edge = EdgePixels(r.Expected);
  double maxInside = 0.0;
  long edges = 0, edgesOff = 0;
  for (size_t i = 0; i < edge.size(); ++i)
  {
    double off = 0.0;
    for (int c = 0; c < 3; ++c)
      off = std::max(off, std::abs(r.Gpu[3 * i + c] - r.Expected[3 * i + c]));
    edges += edge[i];
    edgesOff += edge[i] && off > 2.0;
    if (!edge[i])
      maxInside = std::max(maxInside, off);
  }
  const ChannelError none = ImageError(r.Gpu, r.NoHorizons);
  const ChannelError over = ImageError(r.Gpu, r.HorizonsOver);
  std::cout << name << ": RMS " << e.Rms << ", max " << maxInside << " of 255 off the " << edges
            << " edge pixels (" << edgesOff << " of them off by more than 2, max " << e.Max
            << "); without the horizons RMS " << none.Rms << "; horizons over the volumes RMS "
            << over.Rms << "\n";
  Check(e.Rms <= 0.4 && maxInside <= 2.0, name + ": within RMS 0.4 / max 2 of the reference");
  Check(edgesOff <= 2, name + ": at most 2 edge pixels off by more than 2");
  Check(none.Rms > 2.0, name + ": differs from the scene without the horizons by > 2 RMS");
  if (checkWrongModels)
    Check(over.Rms > 2.0, name + ": differs from the horizons blended over the volumes by > 2 RMS");
}
}

int TestMultiVolumeTranslucentHorizons(int argc, char* argv[])
{
  const TestPaths paths = TestPaths::FromArguments(argc, argv);
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  VolumeScene s(paths.Output);
  s.Add(Blob(40, 36, 32, 1.0, 1.0, 1.0, OX, OY, 0, 1), MakeVolumeProperty(0));
  vtkNew<vtkTransform> t;
  t->Translate(OX + 30, OY + 10, 4);
  t->RotateZ(30);
  s.Add(Blob(24, 20, 18, 1.6, 1.5, 1.4, 0, 0, 0, 2), MakeVolumeProperty(1), t);
  s.UseMultiVolume();

  vtkNew<vtkStackedHeightFieldMapper> hf;
  std::vector<vtkSmartPointer<vtkImageData>> horizons;
  for (int k = 0; k < 3; ++k)
  {
    horizons.push_back(Horizon(k));
    hf->AddInputData(horizons.back());
    hf->SetHorizonColor(k, Colors[k][0], Colors[k][1], Colors[k][2]);
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(hf);
  actor->GetProperty()->LightingOff();
  s.Ren->AddActor(actor);

  // All opaque: no translucency code in the horizons' shader.
  const double down[3] = { OX - 50, OY - 70, 80 }, focal[3] = { OX + 30, OY + 25, 14 };
  s.Camera(down, focal);
  s.Win->Render();
  const std::string opaque = hf->GetShaderSource();
  Check(!opaque.empty() && opaque.find("strataHorizonOpacity(layer) < 1.0") == std::string::npos &&
          opaque.find("uPeel") == std::string::npos &&
          opaque.find("layerAlpha") == std::string::npos,
    "opaque horizons: the height-field shader holds no translucency code");

  hf->SetHorizonOpacity(0, 0.45);
  hf->SetHorizonOpacity(1, 0.35);
  CheckCase(Render(s, hf, actor, true, "HorizonsDown"), "HorizonsDown", true);
  const std::string layer = hf->GetShaderSource();
  Check(layer.find("uPeelPrevious") != std::string::npos,
    "a peel of translucent horizons reads the previous layer's depth");
  Check(s.Mapper->GetShaderSource(2).find("strataSurfacesBefore") != std::string::npos,
    "with translucent horizons the two-volume fragment composites surface layers");

  // From below, all three translucent: the layers come in the reverse order.
  hf->SetHorizonOpacity(2, 0.5);
  const double up[3] = { OX - 40, OY - 60, -70 };
  s.Camera(up, focal);
  CheckCase(Render(s, hf, actor, true, "HorizonsUp"), "HorizonsUp", true);

  // The volumes paged from page pools (bricks of 16^3), looking down, H2 flat and translucent
  // exactly on the bricks' face z = 16 of the first volume (the brick and page boundary).
  s.Camera(down, focal);
  auto* flat = vtkFloatArray::SafeDownCast(horizons[2]->GetPointData()->GetScalars());
  for (vtkIdType p = 0; p < flat->GetNumberOfTuples(); ++p)
    flat->SetValue(p, 16.0f);
  flat->Modified();
  horizons[2]->Modified();
  std::vector<vtkSmartPointer<vtkPagePoolReader>> readers;
  for (size_t i = 0; i < s.Images.size(); ++i)
  {
    const std::string pool = paths.Output + "/translucent-horizons-" + std::to_string(i) + ".spp";
    vtkNew<vtkImageToPagePoolWriter> writer;
    writer->SetInputData(s.Images[i]);
    writer->SetFileName(pool.c_str());
    writer->SetPageSize(16);
    Check(writer->Write(), "pool written");
    readers.push_back(vtkSmartPointer<vtkPagePoolReader>::New());
    readers.back()->SetFileName(pool.c_str());
    s.Mapper->SetInputConnection(static_cast<int>(i), readers.back()->GetOutputPort());
  }
  s.Mapper->SetBrickSize(16);
  CheckCase(Render(s, hf, actor, true, "HorizonsPaged", true), "HorizonsPaged", true);
  Check(s.Mapper->GetPagingStatistics().Converged, "the paged volumes converged");
  std::cout << "HorizonsPaged: " << s.Mapper->GetNumberOfResidentBricks() << " bricks resident\n";
  for (size_t i = 0; i < s.Images.size(); ++i)
    s.Mapper->SetInputDataObject(static_cast<int>(i), s.Images[i]);
  CheckCase(Render(s, hf, actor, true, "HorizonsOnBrickFace"), "HorizonsOnBrickFace", true);

  // No ray caster: the renderer's translucent pass blends the stack front to back (H2 opaque).
  hf->SetHorizonOpacity(2, 1.0);
  horizons[2] = Horizon(2);
  hf->RemoveAllInputs();
  for (auto& h : horizons)
    hf->AddInputData(h);
  CheckCase(Render(s, hf, actor, false, "HorizonsBlended"), "HorizonsBlended", false);

  return CaseResult(Failures() == 0, output);
}
