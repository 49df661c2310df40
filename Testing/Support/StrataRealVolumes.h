// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The real volumes of ../shared/data/volumes (bucky, tooth, engine, bonsai) as the demo and the
// benchmarks show them: one reader, one hand-tuned transfer function and one view per data set.
#ifndef StrataRealVolumes_h
#define StrataRealVolumes_h

#include "StrataTestPaths.h" // For TestPaths

#include "vtkSmartPointer.h"

#include <string>
#include <utility>
#include <vector>

class vtkImageData;
class vtkRenderer;
class vtkVolume;
class vtkVolumeProperty;

namespace strata_test
{
/// Reads a data set by name (bucky and tooth first from paths.Data, all from paths.SharedData,
/// ../shared/data when that is not given); on failure returns nullptr and says why in `why`.
/// The origin is set to 0.
vtkSmartPointer<vtkImageData> LoadRealVolume(const std::string& name,
  const TestPaths& paths,
  std::string& why);

/// Hand-tuned transfer functions over the full 8-bit range of each data set, opacity per voxel,
/// trilinear interpolation.
vtkSmartPointer<vtkVolumeProperty> MakeRealVolumeProperty(const std::string& name);

/// Camera from direction `dir` at the centre of the world bounds of the (image, volume) pairs,
/// at `distanceFactor` times the distance from which their bounding sphere just fills the view.
void FrameVolumes(vtkRenderer* ren,
  const std::vector<std::pair<vtkImageData*, vtkVolume*>>& volumes,
  const double dir[3],
  const double up[3],
  double distanceFactor);

/// Each data set's view: direction from the focal point towards the eye, and up.
void RealVolumeView(const std::string& name, double dir[3], double up[3]);
}

#endif
