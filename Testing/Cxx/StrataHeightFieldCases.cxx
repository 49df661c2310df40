// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The hard cases of the stacked height-field ray caster, each compared pixel by pixel with the
// double-precision reference (StrataHeightFieldScenes). One TestHeightField<Case>.cxx per case
// calls RunHeightFieldCase so that each is its own CTest test.
#include "StrataHeightFieldScenes.h"
#include "StrataImageHelpers.h"
#include "StrataTestHelpers.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"

#include <cmath>
#include <iostream>
#include <limits>

namespace strata_test
{
namespace
{
struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  vtkNew<vtkStackedHeightFieldMapper> Mapper;
  vtkNew<vtkActor> Actor;
  std::vector<vtkSmartPointer<vtkImageData>> Images;
  Scene(const std::vector<vtkSmartPointer<vtkImageData>>& images, int w = 200, int h = 160)
    : Images(images)
  {
    MakeWindow(this->Win, this->Ren, w, h);
    for (auto& image : images)
    {
      this->Mapper->AddInputDataObject(image);
    }
    this->Mapper->SetTileSize(16);
    this->Actor->SetMapper(this->Mapper);
    this->Ren->AddActor(this->Actor);
  }
  void Camera(const double pos[3], const double focal[3], const double up[3])
  {
    vtkCamera* c = this->Ren->GetActiveCamera();
    c->SetPosition(pos[0], pos[1], pos[2]);
    c->SetFocalPoint(focal[0], focal[1], focal[2]);
    c->SetViewUp(up[0], up[1], up[2]);
    this->Ren->ResetCameraClippingRange();
  }
  bool Check(const std::string& name, long minCovered)
  {
    return CheckReference(
      CompareWithReference(this->Win, this->Ren, this->Actor, this->Mapper, this->Images, name),
      name,
      minCovered);
  }
};

std::vector<float> Field(int nx, int ny, int seed, double base, double amp)
{
  std::vector<float> h(static_cast<size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      h[static_cast<size_t>(j) * nx + i] =
        static_cast<float>(base + amp * FractalNoise(i * 0.07, j * 0.07, seed, 5));
  return h;
}

void Center(vtkImageData* image, double c[3])
{
  double b[6];
  image->GetBounds(b);
  c[0] = 0.5 * (b[0] + b[1]);
  c[1] = 0.5 * (b[2] + b[3]);
  c[2] = 0.0;
}
}

int RunHeightFieldCase(const std::string& name)
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  bool ok = true;
  if (name == "Vertical")
  {
    // Rays straight down: zero lateral direction for the centre ray, parallel projection makes
    // it zero for all of them.
    Scene s(MakeDemoHorizons(81, 61));
    double c[3];
    Center(s.Images[0], c);
    const double pos[3] = { c[0], c[1], 3000 }, foc[3] = { c[0], c[1], 0 }, up[3] = { 0, 1, 0 };
    s.Camera(pos, foc, up);
    ok = s.Check("Vertical-perspective", 5000);
    s.Ren->GetActiveCamera()->ParallelProjectionOn();
    s.Ren->GetActiveCamera()->SetParallelScale(420);
    s.Ren->ResetCameraClippingRange();
    ok = s.Check("Vertical-parallel", 15000) && ok;
  }
  else if (name == "AxisParallel")
  {
    // Parallel projection along +x and then +y, tilted down 30 degrees: every ray has an exactly
    // zero lateral component across the other axis.
    Scene s(MakeDemoHorizons(81, 61));
    s.Ren->GetActiveCamera()->ParallelProjectionOn();
    double c[3];
    Center(s.Images[0], c);
    const double foc[3] = { c[0], c[1], -420 }, up[3] = { 0, 0, 1 };
    const double posX[3] = { c[0] - 2000, c[1], -420 + 2000 * std::tan(0.5236) };
    s.Camera(posX, foc, up);
    s.Ren->GetActiveCamera()->SetParallelScale(300);
    s.Ren->ResetCameraClippingRange();
    ok = s.Check("AxisParallel-x", 10000);
    const double posY[3] = { c[0], c[1] - 2000, -420 + 2000 * std::tan(0.5236) };
    s.Camera(posY, foc, up);
    s.Ren->ResetCameraClippingRange();
    ok = s.Check("AxisParallel-y", 10000) && ok;
  }
  else if (name == "Grazing")
  {
    // Camera 1 degree above the mean plane of a gently rolling horizon, looking across it.
    const int n = 129;
    std::vector<float> h = Field(n, n, 5, 0.0, 6.0);
    Scene s({ MakeHorizon(n, n, 0, 0, 10, 10, 0, h) });
    const double pos[3] = { -200, 640, 20 + 1200 * std::tan(std::acos(-1.0) / 180.0) };
    const double foc[3] = { 1000, 640, 20 }, up[3] = { 0, 0, 1 };
    s.Camera(pos, foc, up);
    ok = s.Check("Grazing", 3000);
  }
  else if (name == "Inside")
  {
    // Camera inside the box, between two horizons, looking obliquely: both are visible.
    const int n = 101;
    std::vector<float> top = Field(n, n, 1, 100.0, 25.0), bottom = Field(n, n, 2, -100.0, 25.0);
    Scene s(
      { MakeHorizon(n, n, 0, 0, 10, 10, 0, top), MakeHorizon(n, n, 0, 0, 10, 10, 0, bottom) });
    const double pos[3] = { 300, 500, 0 }, foc[3] = { 800, 500, 20 }, up[3] = { 0, 0, 1 };
    s.Camera(pos, foc, up);
    s.Ren->GetActiveCamera()->SetViewAngle(90);
    s.Ren->GetActiveCamera()->SetClippingRange(1.0, 3000.0);
    ok = s.Check("Inside", 25000);
  }
  else if (name == "Touching")
  {
    // Two horizons equal over the left third, touching at one point on the right, apart elsewhere.
    const int n = 97;
    std::vector<float> a(n * n), b(n * n);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double base = 30.0 * FractalNoise(i * 0.05, j * 0.05, 9, 4);
        const double dx = i - 72.0, dy = j - 48.0;
        const double gap = i < 32 ? 0.0 : std::min(40.0, 0.02 * (dx * dx + dy * dy));
        a[j * n + i] = static_cast<float>(base);
        b[j * n + i] = static_cast<float>(base - gap);
      }
    Scene s({ MakeHorizon(n, n, 0, 0, 10, 10, 0, a), MakeHorizon(n, n, 0, 0, 10, 10, 0, b) });
    const double pos[3] = { 480, -700, 900 }, foc[3] = { 480, 480, -10 }, up[3] = { 0, 0, 1 };
    s.Camera(pos, foc, up);
    ok = s.Check("Touching-above", 15000);
    const double below[3] = { 480, -700, -900 };
    s.Camera(below, foc, up);
    ok = s.Check("Touching-below", 15000) && ok;
  }
  else if (name == "Thin")
  {
    // 1 x N and N x 1 grids: drawn as ribbons one spacing wide.
    const int n = 60;
    std::vector<float> line(n);
    for (int i = 0; i < n; ++i)
      line[i] = static_cast<float>(20.0 * std::sin(i * 0.2));
    Scene sx({ MakeHorizon(1, n, 0, 0, 25, 10, 0, line) });
    const double pos[3] = { 300, -250, 400 }, foc[3] = { 0, 300, 0 }, up[3] = { 0, 0, 1 };
    sx.Camera(pos, foc, up);
    ok = sx.Check("Thin-1xN", 300);
    Scene sy({ MakeHorizon(n, 1, 0, 0, 10, 25, 0, line) });
    const double pos2[3] = { 300, -400, 300 }, foc2[3] = { 300, 0, 0 };
    sy.Camera(pos2, foc2, up);
    ok = sy.Check("Thin-Nx1", 300) && ok;
  }
  else if (name == "UTM")
  {
    // The same stack at the origin and at UTM scale (x = 600000, y = 6700000, 12.5 m spacing),
    // camera moved with it: the two id images must agree as well as each match the reference.
    Scene a(MakeDemoHorizons(161, 121, 0, 0, 12.5, 0));
    Scene b(MakeDemoHorizons(161, 121, 600000, 6700000, 12.5, 0));
    const double pos[3] = { -300, -900, 1200 }, foc[3] = { 1000, 750, -400 }, up[3] = { 0, 0, 1 };
    a.Camera(pos, foc, up);
    const double posU[3] = { 600000 - 300, 6700000 - 900, 1200 },
                 focU[3] = { 601000, 6700750, -400 };
    b.Camera(posU, focU, up);
    b.Ren->GetActiveCamera()->SetClippingRange(a.Ren->GetActiveCamera()->GetClippingRange());
    auto ra = CompareWithReference(a.Win, a.Ren, a.Actor, a.Mapper, a.Images, "UTM-origin");
    auto rb = CompareWithReference(b.Win, b.Ren, b.Actor, b.Mapper, b.Images, "UTM-utm");
    ok = CheckReference(ra, "UTM-origin", 20000);
    ok = CheckReference(rb, "UTM-utm", 20000) && ok;
    const auto same = CompareIds(ra.GpuIds, rb.GpuIds, 200, 160);
    std::cout << "UTM vs origin: " << same.Mismatched << " of " << same.Covered
              << " pixels differ\n";
    if (same.MismatchFraction() > 0.001 || same.WideRegion)
    {
      std::cerr << "FAILED: the UTM-scale image differs from the one at the origin\n";
      ok = false;
    }
  }
  else if (name == "Holes")
  {
    // NaN holes and null-value (-999.25) holes in two horizons above a third.
    const int n = 101;
    std::vector<float> a = Field(n, n, 3, 80, 20), b = Field(n, n, 4, 0, 20),
                       c = Field(n, n, 6, -80, 20);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        if ((i - 30) * (i - 30) + (j - 50) * (j - 50) < 300)
          a[j * n + i] = nan;
        if (std::abs(i - j) < 6 || (i > 70 && j < 30))
          b[j * n + i] = -999.25f;
      }
    Scene s({ MakeHorizon(n, n, 0, 0, 10, 10, 0, a),
      MakeHorizon(n, n, 0, 0, 10, 10, 0, b),
      MakeHorizon(n, n, 0, 0, 10, 10, 0, c) });
    s.Mapper->UseNullValueOn();
    s.Mapper->SetNullValue(-999.25);
    const double pos[3] = { 500, -300, 1400 }, foc[3] = { 500, 500, 0 }, up[3] = { 0, 0, 1 };
    s.Camera(pos, foc, up);
    auto r = CompareWithReference(s.Win, s.Ren, s.Actor, s.Mapper, s.Images, "Holes");
    ok = CheckReference(r, "Holes", 20000);
    // Rays through the holes must reach the lower horizons: ids 1 and 2 both visible.
    long seen[3] = { 0, 0, 0 };
    for (int id : r.GpuIds)
      if (id >= 0 && id < 3)
        ++seen[id];
    std::cout << "Holes: pixels per horizon " << seen[0] << " " << seen[1] << " " << seen[2]
              << "\n";
    if (seen[1] < 1000 || seen[2] < 100)
    {
      std::cerr << "FAILED: too few rays pass through the holes\n";
      ok = false;
    }
    if (s.Mapper->GetFragmentShaderSource().find("isnan") == std::string::npos)
    {
      std::cerr << "FAILED: a stack with holes must be drawn with the hole test\n";
      ok = false;
    }
  }
  else if (name == "Rotated")
  {
    // The demo stack on a grid rotated by 140 degrees, viewed obliquely.
    Scene s(MakeDemoHorizons(121, 91, 5000, 2000, 12.5, 140.0));
    double b[6];
    s.Mapper->GetBounds(b);
    const double c[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), -420 };
    const double pos[3] = { c[0] + 900, c[1] - 1500, 1200 }, up[3] = { 0, 0, 1 };
    s.Camera(pos, c, up);
    ok = s.Check("Rotated", 15000);
  }
  else if (name == "LargeGrid")
  {
    // A 2048 x 1536 grid (thousands of cells along each ray) seen from far away: the traversal
    // must advance by whole nodes and cells however coarse the float rounding of t is there.
    // A walk that re-derived its node from positions stalled here and left streaks of misses.
    Scene s(MakeDemoHorizons(2048, 1536, 0, 0, 2000.0 / 2048, 0));
    s.Mapper->SetTileSize(64);
    const double a = 0.6 + 2.2, cx = 1000, cy = 750;
    const double pos[3] = { cx - 2200 * std::cos(a), cy - 2200 * std::sin(a), 1200 };
    const double foc[3] = { cx, cy, -420 }, up[3] = { 0, 0, 1 };
    s.Camera(pos, foc, up);
    ok = s.Check("LargeGrid", 15000);
  }
  else
  {
    std::cerr << "unknown case " << name << "\n";
    return EXIT_FAILURE;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
}
