// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataHeightFieldScenes.h"

#include "StrataHeightFieldReferenceCaster.h"
#include "StrataHeightFieldStack.h"
#include "StrataImageHelpers.h"
#include "StrataImagePolicy.h"
#include "StrataTestHelpers.h"
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStackedHeightFieldMapper.h"

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>

namespace strata_test
{
namespace
{
double Hash(int x, int y, int seed)
{
  uint32_t h = static_cast<uint32_t>(x) * 374761393u + static_cast<uint32_t>(y) * 668265263u +
               static_cast<uint32_t>(seed) * 2246822519u;
  h = (h ^ (h >> 13)) * 1274126177u;
  h ^= h >> 16;
  return (h & 0xffffff) / double(0xffffff) * 2.0 - 1.0;
}
double ValueNoise(double x, double y, int seed)
{
  const int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
  double fx = x - xi, fy = y - yi;
  fx = fx * fx * (3 - 2 * fx);
  fy = fy * fy * (3 - 2 * fy);
  const double a = Hash(xi, yi, seed), b = Hash(xi + 1, yi, seed);
  const double c = Hash(xi, yi + 1, seed), d = Hash(xi + 1, yi + 1, seed);
  return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
}
}

double FractalNoise(double x, double y, int seed, int octaves)
{
  double sum = 0, amp = 1, norm = 0;
  for (int o = 0; o < octaves; ++o)
  {
    sum += amp * ValueNoise(x, y, seed + 17 * o);
    norm += amp;
    x *= 2.0;
    y *= 2.0;
    amp *= 0.5;
  }
  return sum / norm;
}

vtkSmartPointer<vtkImageData> MakeHorizon(int nx,
  int ny,
  double ox,
  double oy,
  double sx,
  double sy,
  double rotationDeg,
  const std::vector<float>& heights)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, 1);
  image->SetOrigin(ox, oy, 0.0);
  image->SetSpacing(sx, sy, 1.0);
  const double r = rotationDeg * std::acos(-1.0) / 180.0;
  const double dir[9] = { std::cos(r), -std::sin(r), 0, std::sin(r), std::cos(r), 0, 0, 0, 1 };
  image->SetDirectionMatrix(dir);
  vtkNew<vtkFloatArray> a;
  a->SetName("depth");
  a->SetNumberOfValues(static_cast<vtkIdType>(nx) * ny);
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    a->SetValue(i, heights[i]);
  }
  image->GetPointData()->SetScalars(a);
  return image;
}

std::vector<vtkSmartPointer<vtkImageData>> MakeDemoHorizons(int nx,
  int ny,
  double ox,
  double oy,
  double spacing,
  double rot)
{
  std::vector<vtkSmartPointer<vtkImageData>> out;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int k = 0; k < 3; ++k)
  {
    std::vector<float> h(static_cast<size_t>(nx) * ny);
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        const double u = double(i) / (nx - 1), v = double(j) / (ny - 1);
        // Mean depths 300, 420, 520 m with tilts that make them cross; 60-90 m of relief.
        double z = 300.0 + 120.0 * k + (k == 1 ? 220.0 * (u - 0.5) : 0.0) +
                   (k == 2 ? -160.0 * (v - 0.5) : 0.0) +
                   (70.0 + 10 * k) * FractalNoise(4 * u + 3.1 * k, 4 * v + 1.7 * k, 11 + k, 6);
        // Holes: a round one in the top horizon, a fault-like band in the middle one.
        const bool hole = (k == 0 && (u - 0.3) * (u - 0.3) + (v - 0.6) * (v - 0.6) < 0.02) ||
                          (k == 1 && std::abs(u + 0.5 * v - 0.9) < 0.03);
        h[static_cast<size_t>(j) * nx + i] = hole ? nan : static_cast<float>(-z);
      }
    }
    out.push_back(MakeHorizon(nx, ny, ox, oy, spacing, spacing, rot, h));
  }
  return out;
}

ReferenceResult CompareWithReference(vtkRenderWindow* win,
  vtkRenderer* ren,
  vtkActor* actor,
  vtkStackedHeightFieldMapper* mapper,
  const std::vector<vtkSmartPointer<vtkImageData>>& images,
  const std::string& name,
  const std::string& imageDirectory)
{
  ReferenceResult r;
  const auto oldMode = mapper->GetOutputMode();
  mapper->SetOutputMode(vtkStackedHeightFieldMapper::OutputModes::HorizonId);
  win->Render();
  const int w = win->GetSize()[0], h = win->GetSize()[1];
  r.GpuIds = DecodeIds(ReadRGB(win));
  const auto depth = ReadDepth(win);
  mapper->SetOutputMode(oldMode);

  // The stack, built from the images as the mapper documents it.
  vtkImageData* first = images[0];
  int dims[3];
  first->GetDimensions(dims);
  strata::HeightFieldStack stack;
  stack.Initialize(dims[0], dims[1]);
  for (const auto& image : images)
  {
    auto* a = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
    stack.AddLayer(a->GetPointer(0), mapper->GetUseNullValue(), mapper->GetNullValue());
  }
  // Grid -> world from the image's own geometry: origin + D diag(sx, sy, scale) (x + off, y + off,
  // z).
  vtkNew<vtkMatrix4x4> gridToWorld;
  const double* o = first->GetOrigin();
  const double* s = first->GetSpacing();
  const double* d = first->GetDirectionMatrix()->GetData();
  const double sc[3] = { s[0], s[1], mapper->GetHeightScale() };
  const double off[2] = { dims[0] == 1 ? -0.5 : 0.0, dims[1] == 1 ? -0.5 : 0.0 };
  for (int row = 0; row < 3; ++row)
  {
    for (int c = 0; c < 3; ++c)
      gridToWorld->SetElement(row, c, d[3 * row + c] * sc[c]);
    gridToWorld->SetElement(
      row, 3, o[row] + d[3 * row] * s[0] * off[0] + d[3 * row + 1] * s[1] * off[1]);
  }
  vtkNew<vtkMatrix4x4> model, gridToClip, clipToGrid;
  vtkMatrix4x4::Multiply4x4(actor->GetMatrix(), gridToWorld, model);
  vtkMatrix4x4::Multiply4x4(ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
                              ren->GetTiledAspectRatio(), -1, 1),
    model,
    gridToClip);
  vtkMatrix4x4::Invert(gridToClip, clipToGrid);

  strata::HeightFieldReferenceCaster caster(stack);
  std::vector<double> points;
  caster.CastImage(clipToGrid->GetData(), w, h, r.RefIds, points);
  r.RefPoints = points;

  const IdComparison cmp = CompareIds(r.GpuIds, r.RefIds, w, h);
  r.Covered = cmp.Covered;
  r.Mismatched = cmp.Mismatched;
  r.WideRegion = cmp.WideRegion;

  // Depth: both as eye distances along the view axis (linearised from window depth).
  double range[2];
  ren->GetActiveCamera()->GetClippingRange(range);
  const double n = range[0], f = range[1];
  const bool parallel = ren->GetActiveCamera()->GetParallelProjection() != 0;
  auto eyeDepth = [&](double zw)
  {
    const double zn = 2.0 * zw - 1.0;
    return parallel ? 0.5 * (zn + 1.0) * (f - n) + n : 2.0 * f * n / (f + n - zn * (f - n));
  };
  r.RefDepth.assign(size_t(w) * h, 1.0);
  for (int i = 0; i < w * h; ++i)
  {
    if (r.RefIds[i] >= 0)
    {
      const double p[4] = { points[3 * i], points[3 * i + 1], points[3 * i + 2], 1.0 };
      double c[4];
      gridToClip->MultiplyPoint(p, c);
      r.RefDepth[i] = 0.5 * (c[2] / c[3]) + 0.5;
    }
  }
  for (int i = 0; i < w * h; ++i)
  {
    if (r.GpuIds[i] < 0 || r.GpuIds[i] != r.RefIds[i])
    {
      continue;
    }
    const double p[4] = { points[3 * i], points[3 * i + 1], points[3 * i + 2], 1.0 };
    double c[4];
    gridToClip->MultiplyPoint(p, c);
    const double dRef = eyeDepth(0.5 * (c[2] / c[3]) + 0.5);
    const double dGpu = eyeDepth(depth[i]);
    const double rel = std::abs(dGpu - dRef) / dRef;
    // Bound: 8 steps of the 24-bit depth buffer at this distance (quantisation plus float32
    // evaluation of the projection on both sides: a step is 2^-24 d^2 (f - n) / (f n) for a
    // perspective camera, 2^-24 (f - n) for a parallel one), plus 1e-5 d for the residual of the
    // search (12 bisections and a secant step of a bracket at most a cell long).
    const double quantum = parallel ? std::ldexp(1.0, -24) * (f - n)
                                    : std::ldexp(1.0, -24) * dRef * dRef * (f - n) / (f * n);
    const double bound = (8.0 * quantum + 1e-5 * dRef) / dRef;
    if (rel > bound)
    {
      // Same horizon, another crossing (the linear search stepped over a double crossing):
      // a wrong pixel like a wrong id.
      r.DepthBoundViolations += 1;
      r.Mismatched += 1;
    }
    r.MaxRelDepthError = std::max(r.MaxRelDepthError, rel);
  }
  const std::string base = imageDirectory + "/" + name;
  WriteIdPNG(base + "-gpu.png", r.GpuIds, w, h);
  WriteIdPNG(base + "-ref.png", r.RefIds, w, h);
  return r;
}

bool CheckReference(const ReferenceResult& r, const std::string& name, long minCovered)
{
  std::cout << name << ": covered " << r.Covered << " px, mismatched " << r.Mismatched << " ("
            << 100.0 * r.MismatchFraction() << " %), wide region " << (r.WideRegion ? "yes" : "no")
            << ", max relative depth error " << r.MaxRelDepthError
            << ", of which depth outside its bound " << r.DepthBoundViolations << "\n";
  bool ok = true;
  if (r.Covered < minCovered)
  {
    std::cerr << name << ": FAILED: only " << r.Covered
              << " covered pixels, expected >= " << minCovered << "\n";
    ok = false;
  }
  // Edge pixels may land on either side on another rasteriser (StrataImagePolicy.h rule 4).
  if (r.MismatchFraction() > ImagePolicy::EdgePixelFraction)
  {
    std::cerr << name << ": FAILED: more than 0.5 % of covered pixels differ from the reference\n";
    ok = false;
  }
  if (r.WideRegion)
  {
    std::cerr << name << ": FAILED: a region of wrong ids wider than one pixel\n";
    ok = false;
  }
  return ok;
}

void MakeWindow(vtkSmartPointer<vtkRenderWindow>& win,
  vtkSmartPointer<vtkRenderer>& ren,
  int width,
  int height)
{
  win = vtkSmartPointer<vtkRenderWindow>::New();
  win->SetSize(width, height);
  win->SetMultiSamples(0);
  ren = vtkSmartPointer<vtkRenderer>::New();
  ren->SetBackground(0, 0, 0);
  win->AddRenderer(ren);
}
}
