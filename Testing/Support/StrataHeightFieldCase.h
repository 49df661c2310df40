// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// What the hard cases of the stacked height-field ray caster
// (Testing/Cxx/TestHeightField<Case>.cxx) share: a scene of one mapper over a stack of horizons
// with tiles of 16, its camera, and the comparison of ids and depth, pixel by pixel, with the
// double-precision reference (StrataHeightFieldScenes: CompareWithReference and CheckReference
// state the bounds).
#ifndef StrataHeightFieldCase_h
#define StrataHeightFieldCase_h

#include "vtkActor.h" // For vtkNew<vtkActor>
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkStackedHeightFieldMapper.h" // For vtkNew<vtkStackedHeightFieldMapper>

#include <string>
#include <vector>

class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;

namespace strata_test
{
/// The horizons `images` on one vtkStackedHeightFieldMapper (tile size 16) in a w x h window;
/// its comparisons write their images to `ImageDirectory`.
struct HeightFieldScene
{
  vtkSmartPointer<vtkRenderWindow> Win;
  vtkSmartPointer<vtkRenderer> Ren;
  vtkNew<vtkStackedHeightFieldMapper> Mapper;
  vtkNew<vtkActor> Actor;
  std::vector<vtkSmartPointer<vtkImageData>> Images;
  std::string ImageDirectory;
  HeightFieldScene(const std::string& imageDirectory,
    const std::vector<vtkSmartPointer<vtkImageData>>& images,
    int w = 200,
    int h = 160);
  void Camera(const double pos[3], const double focal[3], const double up[3]);
  /// CompareWithReference, then CheckReference with at least `minCovered` covered pixels.
  bool Check(const std::string& name, long minCovered);
};

/// An nx x ny field of heights base + amp * FractalNoise (5 octaves from `seed`, 0.07 per cell).
std::vector<float> Field(int nx, int ny, int seed, double base, double amp);

/// The centre of `image`'s bounds in x and y, at z = 0.
void Center(vtkImageData* image, double c[3]);
}

#endif
