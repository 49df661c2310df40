// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The main of a fuzz target built without libFuzzer (g++, or any build without
// STRATA_BUILD_FUZZERS): runs the target once on every file named, or in a folder named, on the
// command line, as `fuzz-<target> corpus/` does with libFuzzer. The corpus replay tests use it,
// so the checked-in inputs are regression tests in every build, sanitized or not.
#include "StrataFuzz.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  std::vector<std::filesystem::path> inputs;
  for (int a = 1; a < argc; ++a)
  {
    const std::filesystem::path p(argv[a]);
    if (std::filesystem::is_directory(p))
    {
      for (const auto& entry : std::filesystem::directory_iterator(p))
      {
        if (entry.is_regular_file())
        {
          inputs.push_back(entry.path());
        }
      }
    }
    else if (std::filesystem::is_regular_file(p))
    {
      inputs.push_back(p);
    }
    else
    {
      std::fprintf(stderr, "replay: no file or folder %s\n", argv[a]);
      return 1;
    }
  }
  std::sort(inputs.begin(), inputs.end());
  for (const auto& p : inputs)
  {
    std::ifstream in(p, std::ios::binary);
    const std::vector<char> bytes(
      (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("replay: %zu inputs ran\n", inputs.size());
  return inputs.empty() ? 1 : 0;
}
