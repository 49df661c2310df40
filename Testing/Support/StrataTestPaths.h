// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Where a test, a benchmark or the demo reads and writes, from its command line: vtkTesting's
// `-D <dir>` (the data folder, Testing/Data of the source tree) and `-T <dir>` (the output
// folder), and `--shared-data <dir>` (../shared/data, the larger real data sets, which may be
// missing: what needs them says so and skips that part). Testing/Cxx/CMakeLists.txt passes all
// three to every test; scripts/bench and scripts/demo pass them to the programs.
#ifndef StrataTestPaths_h
#define StrataTestPaths_h

#include <string>

namespace strata_test
{
struct TestPaths
{
  std::string Data = "Testing/Data"; ///< -D; "Testing/Data" (from the source tree) when not given
  std::string SharedData;            ///< --shared-data; empty when not given
  std::string Output = ".";          ///< -T; the current directory when not given

  /// The paths on a test's command line (argv as the test driver passes it); other arguments,
  /// such as vtkTesting's -V, are left to their readers.
  static TestPaths FromArguments(int argc, char* argv[]);
  /// For programs with positional arguments (the benchmarks, the demo): the paths, removed from
  /// argv; `argc` becomes the count of what is left.
  static TestPaths TakeFromArguments(int& argc, char* argv[]);
};
}

#endif
