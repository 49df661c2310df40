// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Shared helpers of Strata's C++ tests: reading back colour, depth and per-pixel ids, comparing
// them with reference arrays, and catching every message VTK prints.
#ifndef StrataTestHelpers_h
#define StrataTestHelpers_h

#include "vtkCommand.h"
#include "vtkOutputWindow.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkRenderWindow;

namespace strata_test
{
/// Captures everything VTK writes (errors, warnings, text) so a test can assert it printed none.
class CapturingOutputWindow : public vtkOutputWindow
{
public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override;
  void DisplayErrorText(const char* text) override;
  void DisplayWarningText(const char* text) override;
  void DisplayGenericWarningText(const char* text) override;
  void DisplayDebugText(const char* text) override;
  std::vector<std::string> Messages;
  int Errors = 0;
  int Warnings = 0;
  /// Install as VTK's output window; returns the instance (owned by VTK).
  static CapturingOutputWindow* Install();
};

/// Counts ErrorEvent and WarningEvent of an algorithm and its executive, so that expected errors
/// neither print nor go unnoticed; keeps the first message without VTK's file/line prefix.
class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long event, void* data) override;
  void Watch(vtkAlgorithm* algorithm);
  void Reset();
  int Errors = 0;
  int Warnings = 0;
  std::string First;
};

/// Records a failed check (printed at once); Failures() counts them for the test's exit code.
void Check(bool ok, const std::string& what);
int Failures();

/// VTK's regression image test (vtkTesting, vtkImageDifference) of the window against
/// Testing/Data/Baseline/<name>.png. `threshold` is vtkTesting's: the smallest thresholded
/// image-difference error over the baseline and its alternatives (<name>_1.png, ...) must not
/// exceed it. Writes the test image (and the difference on failure) to OutputDirectory(); a
/// missing baseline fails, leaving the image there to be reviewed and copied in.
bool CompareWithBaseline(vtkRenderWindow* win, const std::string& name, double threshold);

/// RGB bytes of the last rendered frame, bottom row first, width*height*3.
std::vector<unsigned char> ReadRGB(vtkRenderWindow* win);
/// Window-space depth in [0,1] of the last rendered frame, bottom row first.
std::vector<float> ReadDepth(vtkRenderWindow* win);

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

/// Where tests may write files: $STRATA_TEST_OUTPUT or the current directory.
std::string OutputDirectory();
/// Testing/Data in the source tree ($STRATA_TEST_DATA).
std::string TestDataDirectory();
/// ../shared/data ($STRATA_SHARED_DATA); empty when not set.
std::string SharedDataDirectory();

/// Copies a file; with `fraction` < 1 only its first fraction of bytes (a truncated file).
bool CopyFile(const std::string& from, const std::string& to, double fraction = 1.0);
/// Flips the bits of the stored byte `offset` bytes into page `page` of a page pool (a
/// corrupt page, which its checksum must catch).
bool CorruptPage(const std::string& pool, uint64_t page, int offset);

/// Benchmarks: peak resident set of this process in MB, file existence, the q-quantile.
double PeakRssMB();
bool FileExists(const std::string& path);
double Percentile(std::vector<double> values, double q);
}

#endif
