// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The hybrid point + volume renderer against its parts: a volume with thin features the
// factor-4 volume blurs away. Asserts that the points bring the image closer to the
// full-resolution rendering than the low-resolution volume alone (squares and splats), that
// no points (a constant error of zero, or points adding no opacity) give exactly the
// low-resolution rendering however many depth slabs, and that the generated point shaders
// hold only what the settings use; and that two boxes of a region cut (sort-last parallel
// rendering) blend into the whole image, each point drawn by one.
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataVolumeScenes.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkHybridVolumeFilter.h"
#include "vtkHybridVolumeMapper.h"
#include "vtkImageData.h"
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

using namespace strata_test;

namespace
{
const int Size = 128;

// A soft blob with thin rods and a thin shell through it: 65 x 57 x 49 points (not multiples
// of the factor).
vtkSmartPointer<vtkImageData> ThinFeatures()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(65, 57, 49);
  image->AllocateScalars(VTK_FLOAT, 1);
  float* v = static_cast<float*>(image->GetScalarPointer());
  for (int z = 0; z < 49; ++z)
    for (int y = 0; y < 57; ++y)
      for (int x = 0; x < 65; ++x)
      {
        const double r =
          std::sqrt((x - 32.0) * (x - 32.0) + (y - 28.0) * (y - 28.0) + (z - 24.0) * (z - 24.0));
        double s = 90.0 * std::exp(-r * r / 300.0);
        if ((x == 20 && z == 30) || (y == 40 && z == 12) || (x == 45 && y == 15))
          s = 230.0; // one-voxel rods along three axes
        if (std::abs(r - 19.0) < 0.5)
          s = std::max(s, 200.0); // a thin shell
        v[x + 65 * (y + 57 * z)] = static_cast<float>(s);
      }
  return image;
}

vtkSmartPointer<vtkVolumeProperty> Property()
{
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0, 0.2, 0.3, 0.9);
  color->AddRGBPoint(100, 0.9, 0.8, 0.3);
  color->AddRGBPoint(255, 1.0, 0.3, 0.2);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(40, 0.0);
  opacity->AddPoint(100, 0.05);
  opacity->AddPoint(255, 0.6);
  auto p = vtkSmartPointer<vtkVolumeProperty>::New();
  p->SetColor(color);
  p->SetScalarOpacity(opacity);
  p->SetInterpolationTypeToLinear();
  p->ShadeOff();
  return p;
}

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  vtkNew<vtkVolume> Volume;
  Scene(vtkVolumeProperty* property)
  {
    MakeWindow(this->Win, this->Ren, Size, Size);
    this->Volume->SetProperty(property);
    this->Ren->AddVolume(this->Volume);
    vtkCamera* cam = this->Ren->GetActiveCamera();
    cam->SetFocalPoint(32, 28, 24);
    cam->SetPosition(32 - 80, 28 - 110, 24 + 70);
    cam->SetViewUp(0, 0, 1);
    cam->SetViewAngle(30);
    this->Ren->ResetCameraClippingRange();
  }
  std::vector<unsigned char> Render(vtkVolumeMapper* mapper)
  {
    this->Volume->SetMapper(mapper);
    this->Ren->ResetCameraClippingRange();
    this->Win->Render();
    return ReadRGB(this->Win);
  }
};

/// What the parts share: the thin-feature volume, its property and scene, the full-resolution
/// and low-resolution mappers, the hybrid filter (factor 4, cubic, threshold 25) and mapper, and
/// the images and shader sources the last part checks.
struct HybridFixture
{
  HybridFixture()
    : Original(ThinFeatures())
    , VolumeProperty(Property())
    , S(this->VolumeProperty)
  {
  }
  vtkSmartPointer<vtkImageData> Original;
  vtkSmartPointer<vtkVolumeProperty> VolumeProperty;
  Scene S;
  vtkNew<vtkMultiVolumeRayCastMapper> FullMapper, LowMapper;
  vtkNew<vtkHybridVolumeFilter> Filter;
  vtkNew<vtkImageData> Low;
  vtkNew<vtkHybridVolumeMapper> Hybrid;
  std::vector<unsigned char> Full, LowImage, Splats;
  std::string SquareVS, SquareFS, SplatFS;
};

void SquaresAndSplats(HybridFixture& fx)
{
  vtkImageData* original = fx.Original;
  Scene& scene = fx.S;
  vtkMultiVolumeRayCastMapper* fullMapper = fx.FullMapper;
  fullMapper->SetInputData(original);
  fullMapper->SetSampleDistance(0.5);
  fx.Full = scene.Render(fullMapper);
  const auto& full = fx.Full;

  vtkHybridVolumeFilter* filter = fx.Filter;
  filter->SetInputData(original);
  filter->SetFactor(4, 4, 4);
  filter->SetFilterToCubic();
  filter->SetThreshold(25.0);
  filter->Update();
  vtkPolyData* points = filter->GetPointsOutput();
  vtkImageData* low = fx.Low;
  low->DeepCopy(filter->GetLowResolutionOutput());
  std::cout << "Hybrid: low-resolution " << low->GetDimensions()[0] << "x"
            << low->GetDimensions()[1] << "x" << low->GetDimensions()[2] << ", "
            << points->GetNumberOfPoints() << " points\n";

  vtkMultiVolumeRayCastMapper* lowMapper = fx.LowMapper;
  lowMapper->SetInputData(low);
  lowMapper->SetSampleDistance(0.5);
  fx.LowImage = scene.Render(lowMapper);
  const auto& lowImage = fx.LowImage;

  vtkHybridVolumeMapper* hybrid = fx.Hybrid;
  hybrid->SetInputData(low);
  hybrid->SetPointsInputData(points);
  hybrid->GetVolumeMapper()->SetSampleDistance(0.5);
  const auto squares = scene.Render(hybrid);
  const vtkIdType drawn = hybrid->GetNumberOfPointsDrawn();
  fx.SquareVS = hybrid->GetPointVertexShaderSource();
  fx.SquareFS = hybrid->GetPointFragmentShaderSource();
  hybrid->SetPointShape(vtkHybridVolumeMapper::PointShapes::GaussianSplats);
  fx.Splats = scene.Render(hybrid);
  const auto& splats = fx.Splats;
  fx.SplatFS = hybrid->GetPointFragmentShaderSource();

  const double lowRms = ImageError(lowImage, full).Rms, squareRms = ImageError(squares, full).Rms,
               splatRms = ImageError(splats, full).Rms;
  std::cout << "Hybrid: RMS against full resolution: low-resolution alone " << lowRms
            << ", squares " << squareRms << ", splats " << splatRms << " (" << drawn
            << " points drawn)\n";
  Check(points->GetNumberOfPoints() > 100 && drawn == points->GetNumberOfPoints(),
    "points were made and all drawn");
  Check(lowRms > 2.0, "the thin features make the low-resolution image wrong (RMS > 2)");
  Check(squareRms < 0.6 * lowRms,
    "squares bring the image closer to full resolution (RMS < 0.6 x low-resolution's)");
  Check(splatRms < 0.6 * lowRms,
    "splats bring the image closer to full resolution (RMS < 0.6 x low-resolution's)");
}

void OpacityRanking(HybridFixture& fx)
{
  vtkImageData* original = fx.Original;
  vtkVolumeProperty* property = fx.VolumeProperty;
  Scene& scene = fx.S;
  vtkMultiVolumeRayCastMapper* fullMapper = fx.FullMapper;
  vtkHybridVolumeMapper* hybrid = fx.Hybrid;
  vtkImageData* low = fx.Low;
  // Ranked by the opacity the low-resolution volume misses (the transfer function known at
  // preprocessing), on the volume plus a plate of -300 the transfer function hides: every point
  // misses more opacity than the threshold, exactly the points that do are kept, and with as
  // many points the image is closer than with |error| ranking (which spends them on the plate).
  {
    vtkNew<vtkImageData> plated;
    plated->DeepCopy(original);
    float* pv = static_cast<float*>(plated->GetScalarPointer());
    for (int z = 0; z < 49; ++z)
      for (int y = 0; y < 57; ++y)
        pv[55 + 65 * (y + 57 * z)] = -300.0f;
    fullMapper->SetInputData(plated);
    const auto platedFull = scene.Render(fullMapper);
    vtkPiecewiseFunction* f = property->GetScalarOpacity(0);
    auto make = [&](vtkPiecewiseFunction* opacity, double threshold, vtkIdType budget)
    {
      auto filter = vtkSmartPointer<vtkHybridVolumeFilter>::New();
      filter->SetInputData(plated);
      filter->SetFactor(4, 4, 4);
      filter->SetFilterToCubic();
      filter->SetOpacityFunction(opacity);
      filter->SetThreshold(threshold);
      filter->SetPointBudget(budget);
      filter->Update();
      return filter;
    };
    auto missing = [f](vtkPolyData* p, vtkIdType i)
    {
      const double s = p->GetPointData()->GetArray("Value")->GetComponent(i, 0);
      return f->GetValue(s) -
             f->GetValue(s - p->GetPointData()->GetArray("Error")->GetComponent(i, 0));
    };
    auto weighted = make(f, 0.02, 0);
    auto all = make(nullptr, 0.0, 0); // every point with an error: the brute force
    vtkPolyData* wp = weighted->GetPointsOutput();
    vtkIdType below = 0, expected = 0;
    for (vtkIdType i = 0; i < wp->GetNumberOfPoints(); ++i)
      below += missing(wp, i) > 0.02 ? 0 : 1;
    for (vtkIdType i = 0; i < all->GetPointsOutput()->GetNumberOfPoints(); ++i)
      expected += missing(all->GetPointsOutput(), i) > 0.02 ? 1 : 0;
    std::cout << "Hybrid: ranked by missing opacity > 0.02: " << wp->GetNumberOfPoints()
              << " points (brute force " << expected << "), " << below << " below the threshold\n";
    Check(wp->GetNumberOfPoints() == expected && below == 0 && expected > 0,
      "opacity ranking keeps exactly the points missing more opacity than the threshold");
    const vtkIdType n = wp->GetNumberOfPoints();
    auto byError = make(nullptr, 0.0, n);
    vtkNew<vtkImageData> wl;
    wl->DeepCopy(weighted->GetLowResolutionOutput());
    hybrid->SetInputData(wl);
    hybrid->SetPointShape(vtkHybridVolumeMapper::PointShapes::Squares);
    hybrid->SetPointsInputData(wp);
    const double weightedRms = ImageError(scene.Render(hybrid), platedFull).Rms;
    hybrid->SetPointsInputData(byError->GetPointsOutput());
    const double errorRms = ImageError(scene.Render(hybrid), platedFull).Rms;
    std::cout << "Hybrid: " << n << " points: RMS ranked by missing opacity " << weightedRms
              << ", by |error| " << errorRms << "\n";
    Check(weightedRms < errorRms - 1.0,
      "with as many points, ranking by missing opacity gives the closer image (by > 1 RMS level)");
    hybrid->SetInputData(low);
    hybrid->SetPointShape(vtkHybridVolumeMapper::PointShapes::GaussianSplats);
  }
}

void SilentPoints(HybridFixture& fx)
{
  Scene& scene = fx.S;
  vtkHybridVolumeMapper* hybrid = fx.Hybrid;
  vtkPolyData* points = fx.Filter->GetPointsOutput();
  const std::vector<unsigned char>& lowImage = fx.LowImage;
  // Points that add no opacity (error 0): every slab is drawn, nothing added.
  vtkNew<vtkPolyData> silent;
  silent->DeepCopy(points);
  vtkFloatArray* err = vtkFloatArray::SafeDownCast(silent->GetPointData()->GetArray("Error"));
  for (vtkIdType i = 0; i < err->GetNumberOfTuples(); ++i)
    err->SetValue(i, 0.0f);
  hybrid->SetPointsInputData(silent);
  // Each slab is blended into the 8-bit window on its own: up to half a level of rounding per
  // slab, about S / 4 levels in all.
  for (int slabs : { 1, 4, 16 })
  {
    hybrid->SetNumberOfSlabs(slabs);
    const int mx = static_cast<int>(ImageError(scene.Render(hybrid), lowImage).Max);
    std::cout << "Hybrid: " << slabs
              << " slabs, points adding nothing: max difference to the low-resolution image " << mx
              << "\n";
    Check(mx <= std::max(1, slabs / 4),
      "depth slabs recompose the low-resolution image (" + std::to_string(slabs) +
        " slabs: max difference <= " + std::to_string(std::max(1, slabs / 4)) + " of 255)");
  }
}

void ConstantVolume(HybridFixture& fx)
{
  vtkImageData* original = fx.Original;
  Scene& scene = fx.S;
  vtkMultiVolumeRayCastMapper* lowMapper = fx.LowMapper;
  vtkHybridVolumeMapper* hybrid = fx.Hybrid;
  // A constant volume: no error, no points, the low-resolution rendering exactly. Without points
  // the hybrid mapper renders its inner vtkMultiVolumeRayCastMapper alone, with the settings of
  // LowMapper (sample distance 0.5, no clipping plane): the same program twice, bit-exact
  // (ImagePolicy::SameProgramMax, StrataImagePolicy.h rule 1). On an H200 it was 1 off before the
  // texture barrier after the integration buffers' clears (a stale texel read), 0 after.
  vtkNew<vtkImageData> constant;
  constant->DeepCopy(original);
  std::fill_n(static_cast<float*>(constant->GetScalarPointer()), 65 * 57 * 49, 120.0f);
  vtkNew<vtkHybridVolumeFilter> flat;
  flat->SetInputData(constant);
  flat->SetFactor(4, 4, 4);
  flat->Update();
  vtkNew<vtkImageData> flatLow;
  flatLow->DeepCopy(flat->GetLowResolutionOutput());
  hybrid->SetInputData(flatLow);
  hybrid->SetPointsInputData(flat->GetPointsOutput());
  const auto flatHybrid = scene.Render(hybrid);
  lowMapper->SetInputData(flatLow);
  const auto flatPlain = scene.Render(lowMapper);
  const int flatDiff = static_cast<int>(ImageError(flatHybrid, flatPlain).Max);
  std::cout << "Hybrid: constant volume: " << flat->GetPointsOutput()->GetNumberOfPoints()
            << " points; max difference to the low-resolution rendering " << flatDiff << "\n";
  Check(
    flat->GetPointsOutput()->GetNumberOfPoints() == 0 && flatDiff <= ImagePolicy::SameProgramMax,
    "a constant volume gives no points and renders as the low-resolution volume alone");
}

void ShaderSources(HybridFixture& fx)
{
  vtkVolumeProperty* property = fx.VolumeProperty;
  Scene& scene = fx.S;
  vtkHybridVolumeMapper* hybrid = fx.Hybrid;
  vtkImageData* low = fx.Low;
  vtkPolyData* points = fx.Filter->GetPointsOutput();
  auto has = [](const std::string& s, const char* what)
  { return s.find(what) != std::string::npos; };
  Check(!has(fx.SquareFS, "gl_PointCoord") && !has(fx.SquareFS, "exp("),
    "squares: no splat kernel code");
  Check(has(fx.SplatFS, "gl_PointCoord") && has(fx.SplatFS, "exp("), "splats: the Gaussian kernel");
  Check(!has(fx.SquareVS, "ormal"), "shading off: no normals");
  // Shading on: the points are lit with their normals (and only then is normal code compiled).
  property->ShadeOn();
  hybrid->SetInputData(low);
  hybrid->SetPointsInputData(points);
  const auto shadedImage = scene.Render(hybrid);
  const double shadedRms = ImageError(shadedImage, fx.Splats).Rms;
  std::cout << "Hybrid: shaded, RMS to the unshaded image " << shadedRms << "\n";
  Check(has(hybrid->GetPointVertexShaderSource(), "pointNormal") && shadedRms > 0.5,
    "shading on: the points are lit with their normals");
  property->ShadeOff();
}

// SetRegion, as sort-last parallel rendering uses it: the scene cut by the plane x = 30.3
// (through the blob, the shell and two rods, off the lattice) into two boxes, each rendered alone
// as premultiplied RGBA over transparent black and blended front box over back box, against the
// whole scene; the boxes together draw every point exactly once. The two do not order alike:
// the whole image orders a point against the volume only by its depth slab (the slab's volume
// first, then its points), the boxes also by box (the front box's volume, in the point's slab,
// over the back box's points), so they differ by up to one slab's ordering error: measured with
// 1 slab 18 of 255, 2 slabs 6.5, 8 (the default, here) 4.6, 16 4.7 (the floor: each slab's pass
// is blended in 8 bits). Bound 5.5 of 255; blended in the wrong order, above 10 (measured 21).
void Region(HybridFixture& fx)
{
  Scene s(fx.VolumeProperty);
  s.Win->SetAlphaBitPlanes(1);
  s.Ren->SetBackgroundAlpha(0.0);
  vtkNew<vtkHybridVolumeFilter> filter;
  filter->SetInputData(fx.Original);
  filter->SetFactor(4, 4, 4);
  filter->SetFilterToCubic();
  filter->SetThreshold(25.0);
  filter->Update();
  vtkNew<vtkHybridVolumeMapper> hybrid;
  hybrid->SetInputData(filter->GetLowResolutionOutput());
  hybrid->SetPointsInputData(filter->GetPointsOutput());
  hybrid->SetPointShape(vtkHybridVolumeMapper::PointShapes::GaussianSplats);
  hybrid->GetVolumeMapper()->SetSampleDistance(0.5);
  s.Volume->SetMapper(hybrid);
  s.Ren->ResetCameraClippingRange();
  // The eye is at x < 30.3: the box below the face is in front.
  const std::vector<float> whole = RenderRGBA(s.Win);
  const vtkIdType all = hybrid->GetNumberOfPointsDrawn();
  const double near[6] = { -1e3, 30.3, -1e3, 1e3, -1e3, 1e3 };
  const double far[6] = { 30.3, 1e3, -1e3, 1e3, -1e3, 1e3 };
  hybrid->SetRegion(near);
  const std::vector<float> front = RenderRGBA(s.Win);
  const vtkIdType inFront = hybrid->GetNumberOfPointsDrawn();
  hybrid->SetRegion(far);
  const std::vector<float> back = RenderRGBA(s.Win);
  const vtkIdType inBack = hybrid->GetNumberOfPointsDrawn();
  double box[6];
  Check(hybrid->GetRegion(box) && box[0] == 30.3, "GetRegion gives the box set");
  hybrid->RemoveRegion();
  Check(!hybrid->GetRegion(box) && (RenderRGBA(s.Win), hybrid->GetNumberOfPointsDrawn()) == all,
    "without the region every point is drawn again");
  const OverDifference right = CompareOver(front, back, whole),
                       wrong = CompareOver(back, front, whole);
  std::cout << "Hybrid region: points drawn " << inFront << " + " << inBack << " of " << all
            << "; front over back vs whole: max " << right.Max << " of 255, " << right.Off
            << " pixels off by more than 1; back over front: max " << wrong.Max << "\n";
  Check(inFront > 0 && inBack > 0 && inFront + inBack == all,
    "the two boxes draw every point once, each some");
  Check(right.Max <= 5.5, "the two boxes blended in order equal the whole scene (5.5 of 255)");
  Check(wrong.Max > 10.0, "blended in the wrong order they do not (above 10 of 255)");
}
}

int TestHybridVolumeMapper(int, char*[])
{
  CapturingOutputWindow* output = CapturingOutputWindow::Install();
  HybridFixture fx;
  RunSubTests(
    {
      { "SquaresAndSplats", [&] { SquaresAndSplats(fx); } },
      { "OpacityRanking", [&] { OpacityRanking(fx); } },
      { "SilentPoints", [&] { SilentPoints(fx); } },
      { "ConstantVolume", [&] { ConstantVolume(fx); } },
      { "ShaderSources", [&] { ShaderSources(fx); } },
      { "Region", [&] { Region(fx); } },
    },
    Failures);
  Check(output->Errors == 0 && output->Warnings == 0, "no VTK errors or warnings");
  std::cout << (Failures() ? "FAILED" : "passed") << "\n";
  return Failures() ? EXIT_FAILURE : EXIT_SUCCESS;
}
