// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// CompareWithBaseline: VTK::TestingRendering's regression image test, then a pixel-by-pixel
// count.
#include "StrataRegressionImage.h"

#include "StrataImageHelpers.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPointData.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkTesting.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>

namespace strata_test
{
bool CompareWithBaseline(int argc,
  char* argv[],
  vtkRenderWindow* win,
  const std::string& name,
  double threshold)
{
  // The baseline as vtkTesting finds it on the command line: -V, relative to -D unless absolute.
  vtkNew<vtkTesting> arguments;
  for (int i = 0; i < argc; ++i)
  {
    arguments->AddArgument(argv[i]);
  }
  if (!arguments->IsValidImageSpecified())
  {
    std::cout << name << ": no baseline image given (-V)\n";
    return false;
  }
  const std::string baseline = arguments->GetValidImageFileName();
  const bool vtkPassed = vtkRegressionTestImageThreshold(win, threshold) == vtkTesting::PASSED;
  std::cout << name << ": vtkTesting regression image against " << baseline << " (threshold "
            << threshold << "): " << (vtkPassed ? "passed" : "FAILED") << "\n";
  if (!vtkPassed)
  {
    return false;
  }

  // vtkImageDifference forgives a shift of a pixel or two anywhere (it matches each pixel in a
  // 3 x 3 neighbourhood and averages): a sphere moved by two pixels scores 0. So also count, pixel
  // by pixel, the pixels whose colour differs by more than 24 of 255 in a channel (more than
  // shading rounds to across Mesa versions); more than 0.2 % of the image fails.
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baseline.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  const int* size = win->GetSize();
  int dims[3];
  image->GetDimensions(dims);
  auto* pixels = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  if (!pixels || dims[0] != size[0] || dims[1] != size[1])
  {
    std::cout << name << ": baseline size differs from the window's\n";
    return false;
  }
  const int comps = pixels->GetNumberOfComponents();
  const auto rgb = ReadRGB(win);
  long differing = 0;
  for (vtkIdType i = 0; i < vtkIdType(size[0]) * size[1]; ++i)
  {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
    {
      worst = std::max(worst,
        std::abs(int(rgb[3 * i + c]) - int(pixels->GetValue(i * comps + std::min(c, comps - 1)))));
    }
    differing += worst > 24;
  }
  const long allowed = static_cast<long>(0.002 * size[0] * size[1]);
  std::cout << name << ": " << differing << " pixels differ from the baseline by more than 24/255"
            << " (at most " << allowed << " allowed)\n";
  return differing <= allowed;
}
}
