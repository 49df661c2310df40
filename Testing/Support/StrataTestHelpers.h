// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Helpers of Strata's C++ tests and benchmarks that need only the core (StrataTestingCore):
// catching every message VTK prints, counting failed checks, copying and corrupting files, and
// the benchmarks' small statistics.
#ifndef StrataTestHelpers_h
#define StrataTestHelpers_h

#include "vtkOutputWindow.h"

#include <cstdint>
#include <string>
#include <vector>

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

/// Records a failed check (printed at once); Failures() counts them for the test's exit code.
void Check(bool ok, const std::string& what);
int Failures();
/// Checks that VTK printed no error and no warning into `output` (saying how many it did).
void CheckNoVtkMessages(const CapturingOutputWindow* output);

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
