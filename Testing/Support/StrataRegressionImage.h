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
/// VTK's regression image test (vtkRegressionTestImageThreshold: vtkTesting, vtkImageDifference)
/// of the window against the baseline on the test's command line (`argc`, `argv` as the test
/// driver passes them: -V <baseline>, relative to -D <data> unless absolute; -T <output>).
/// `threshold` is vtkTesting's: the smallest thresholded image-difference error over the
/// baseline and its alternatives (<name>_1.png, ...) must not exceed it. Writes the test image
/// (and the difference on failure) to the -T folder; a missing baseline fails, leaving the image
/// there to be reviewed and copied into Testing/Data/Baseline/. Then counts, pixel by pixel, the
/// pixels off by more than 24/255 from the baseline: more than 0.2 % of the image fails. `name`
/// prefixes what it prints.
bool CompareWithBaseline(int argc,
  char* argv[],
  vtkRenderWindow* win,
  const std::string& name,
  double threshold);
}

#endif
