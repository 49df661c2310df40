// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The image tests' baseline comparison: VTK's regression image test, then a pixel-by-pixel
// count that vtkImageDifference's forgiving neighbourhood match would miss.
#ifndef StrataRegressionImage_h
#define StrataRegressionImage_h

#include <string>

class vtkRenderWindow;

namespace strata_test
{
/// VTK's regression image test (vtkTesting, vtkImageDifference) of the window against
/// Testing/Data/Baseline/<name>.png. `threshold` is vtkTesting's: the smallest thresholded
/// image-difference error over the baseline and its alternatives (<name>_1.png, ...) must not
/// exceed it. Writes the test image (and the difference on failure) to OutputDirectory(); a
/// missing baseline fails, leaving the image there to be reviewed and copied in.
bool CompareWithBaseline(vtkRenderWindow* win, const std::string& name, double threshold);
}

#endif
