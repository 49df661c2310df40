// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The subsurface scene of the demo (scripts/demo) and of TestSubsurfaceDemo: two synthetic
// surveys written from the four Reek horizons (vtkSyntheticSurveyWriter, SEG-Y with rotated UTM
// trace coordinates): survey A on every 8th node of the horizons' grid, converted to a page pool
// and paged; survey B, 2x finer laterally and 2x in depth, rotated 15 degrees more, over the
// middle, in core. Both drawn by one vtkMultiVolumeRayCastMapper in world coordinates (survey A
// cropped to the last third of its first axis, so that the horizons show beside it); the
// second horizon draped with survey A's amplitude (vtkHorizonVolumeSampler through the pool),
// the base horizon coloured by depth, the top horizon translucent (opacity 0.45, composited
// inside the volumes by the ray caster's surface layers); a deviated well through them. 8x vertical
// exaggeration.
#ifndef StrataSubsurfaceDemo_h
#define StrataSubsurfaceDemo_h

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkActor;
class vtkAlgorithm;
class vtkHorizonVolumeSampler;
class vtkMultiVolume;
class vtkMultiVolumeRayCastMapper;
class vtkRenderer;
class vtkStackedHeightFieldMapper;

namespace strata_test
{
struct SubsurfaceDemo
{
  vtkSmartPointer<vtkMultiVolumeRayCastMapper> VolumeMapper;
  vtkSmartPointer<vtkMultiVolume> Volumes;
  vtkSmartPointer<vtkStackedHeightFieldMapper> HorizonMapper;
  vtkSmartPointer<vtkActor> Horizons, Well;
  vtkSmartPointer<vtkHorizonVolumeSampler> Drape;
  std::vector<vtkSmartPointer<vtkAlgorithm>> Sources; ///< keeps the pipeline alive
  std::vector<std::string> Files;                     ///< written to the work folder
};

/// Builds the scene in `ren` from the Reek horizons in `horizonDir`, writing its SEG-Y files
/// and pool to `work`; false (with a message on stderr) if a file cannot be read or written.
bool AddSubsurfaceDemo(vtkRenderer* ren,
  const std::string& horizonDir,
  const std::string& work,
  SubsurfaceDemo& scene);

/// Removes the scene's files.
void RemoveSubsurfaceDemoFiles(const SubsurfaceDemo& scene);
}

#endif
