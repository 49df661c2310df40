// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Scenes and the GPU-versus-reference comparison shared by the height-field tests, the demo
// test and the benchmark.
#ifndef StrataHeightFieldScenes_h
#define StrataHeightFieldScenes_h

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;
class vtkActor;
class vtkStackedHeightFieldMapper;

namespace strata_test
{
/// Deterministic fractal (value) noise in [-1, 1]: `octaves` octaves from `seed`.
double FractalNoise(double x, double y, int seed, int octaves);

/// An nx x ny height field with origin, spacing and rotation (degrees, about z), float heights.
vtkSmartPointer<vtkImageData> MakeHorizon(int nx,
  int ny,
  double ox,
  double oy,
  double sx,
  double sy,
  double rotationDeg,
  const std::vector<float>& heights);

/// Three crossing fractal horizons with NaN holes on a 161 x 121 grid (the demo's stack).
std::vector<vtkSmartPointer<vtkImageData>> MakeDemoHorizons(int nx = 161,
  int ny = 121,
  double ox = 0,
  double oy = 0,
  double spacing = 12.5,
  double rot = 0);

struct ReferenceResult
{
  long Covered = 0;
  long Mismatched = 0;
  bool WideRegion = false;
  double MaxRelDepthError = 0.0; ///< max |d_gpu - d_ref| / d_ref over pixels with equal ids
  double DepthBoundViolations = 0;
  std::vector<int> GpuIds, RefIds;
  std::vector<double> RefDepth;  ///< window depth [0, 1] of the reference's hits, 1 where none
  std::vector<double> RefPoints; ///< grid-space hit points of the reference, 3 per pixel
  double MismatchFraction() const
  {
    return this->Covered ? double(this->Mismatched) / this->Covered : 0.0;
  }
};

/// Renders `mapper` (switched to HorizonId output) in `win`/`ren` and compares ids and depth,
/// pixel by pixel, with strata::HeightFieldReferenceCaster on rays built from VTK's camera in
/// double precision. `images` are the mapper's inputs (for the grid geometry). Writes both id
/// images as <imageDirectory>/<name>-gpu.png and -ref.png.
ReferenceResult CompareWithReference(vtkRenderWindow* win,
  vtkRenderer* ren,
  vtkActor* actor,
  vtkStackedHeightFieldMapper* mapper,
  const std::vector<vtkSmartPointer<vtkImageData>>& images,
  const std::string& name,
  const std::string& imageDirectory);

/// Asserts the bounds on a comparison, printing the numbers: mismatches <= 0.5 % of
/// covered pixels (ImagePolicy::EdgePixelFraction, StrataImagePolicy.h rule 4), no mismatched
/// region wider than one pixel, depth within its bound, and at
/// least `minCovered` covered pixels (so that an empty image cannot pass).
bool CheckReference(const ReferenceResult& r, const std::string& name, long minCovered);

/// A 200 x 160 EGL window with one renderer, multisampling off.
void MakeWindow(vtkSmartPointer<vtkRenderWindow>& win,
  vtkSmartPointer<vtkRenderer>& ren,
  int width = 200,
  int height = 160);
}

#endif
