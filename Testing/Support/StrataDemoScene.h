// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The demo's first scene, shared by Examples/StrataDemo and TestHeightFieldDemo so that the test
// checks exactly what the demo shows, and the camera of its Reek scene (TestHeightFieldPaging).
#ifndef StrataDemoScene_h
#define StrataDemoScene_h

#include "vtkSmartPointer.h"

#include <vector>

class vtkActor;
class vtkImageData;
class vtkRenderer;
class vtkStackedHeightFieldMapper;

namespace strata_test
{
struct DemoScene
{
  std::vector<vtkSmartPointer<vtkImageData>> Horizons;
  vtkSmartPointer<vtkStackedHeightFieldMapper> Mapper;
  vtkSmartPointer<vtkActor> Stack;  ///< the three horizons, z exaggerated 1.5x
  vtkSmartPointer<vtkActor> Well;   ///< a deviated well path as a tube through all three
  vtkSmartPointer<vtkActor> Target; ///< a sphere around the well's target, cut by the top horizon
};

/// Adds the synthetic stack (MakeDemoHorizons at UTM coordinates, 321 x 241, 6.25 m), the well
/// and the target to `ren`, with the demo's background and camera.
DemoScene AddDemoScene(vtkRenderer* ren);

/// The demo's camera on its Reek scene (the four horizons of `actor`, scaled 8x in z): from the
/// south-west, above, zoomed by `zoom` (the demo uses 1.3).
void FrameReekScene(vtkRenderer* ren, vtkActor* actor, double zoom);
}

#endif
