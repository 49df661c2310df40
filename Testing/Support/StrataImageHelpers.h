// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Reading back colour, depth and per-pixel ids of a rendered frame, comparing ids with a
// reference, and writing images to look at (StrataTestingRendering).
#ifndef StrataImageHelpers_h
#define StrataImageHelpers_h

#include <string>
#include <vector>

class vtkRenderWindow;

namespace strata_test
{
/// RGB bytes of the last rendered frame, bottom row first, width*height*3.
std::vector<unsigned char> ReadRGB(vtkRenderWindow* win);
/// Window-space depth in [0,1] of the last rendered frame, bottom row first.
std::vector<float> ReadDepth(vtkRenderWindow* win);
/// Renders `win` and reads its RGBA back as floats in [0,1], bottom row first (premultiplied
/// over transparent black where the window has alpha planes and a background alpha of 0).
std::vector<float> RenderRGBA(vtkRenderWindow* win);

/// How far `front` blended over `back` (premultiplied RGBA, C = Cf + (1 - Af) Cb) is from
/// `whole`: the largest channel difference of any pixel, of 255, and the pixels off by more
/// than 1 of 255. Sort-last parallel rendering's check: two boxes' images against one.
struct OverDifference
{
  double Max = 0.0;
  long Off = 0;
};
OverDifference CompareOver(const std::vector<float>& front,
  const std::vector<float>& back,
  const std::vector<float>& whole);

/// Ids drawn as flat colours id+1 packed in 24-bit RGB (0 = background). See
/// vtkStackedHeightFieldMapper's HorizonId output.
std::vector<int> DecodeIds(const std::vector<unsigned char>& rgb);

/// Statistics of a per-pixel id comparison.
struct IdComparison
{
  long Covered = 0;        ///< pixels where either side has an id
  long Mismatched = 0;     ///< covered pixels whose ids differ
  bool WideRegion = false; ///< some 2x2 block of mismatches (a region wider than one pixel)
  int WideX = -1, WideY = -1;
  double MismatchFraction() const
  {
    return this->Covered ? double(this->Mismatched) / this->Covered : 0.0;
  }
};
/// Compares ids (-1 = none) pixel by pixel; width*height each.
IdComparison CompareIds(const std::vector<int>& test,
  const std::vector<int>& reference,
  int width,
  int height);

/// Writes an RGB image (bottom row first) as PNG, for looking at a failing case.
void WritePNG(const std::string& path,
  const std::vector<unsigned char>& rgb,
  int width,
  int height);
/// Writes a false-colour PNG of ids (-1 black) for the same reason.
void WriteIdPNG(const std::string& path, const std::vector<int>& ids, int width, int height);
}

#endif
