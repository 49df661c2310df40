// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataTestPaths.h"

#include <cstring>

namespace strata_test
{
namespace
{
/// The member of `paths` that `option` sets, or null when it is not a path option.
std::string* PathOf(TestPaths& paths, const char* option)
{
  if (std::strcmp(option, "-D") == 0)
    return &paths.Data;
  if (std::strcmp(option, "-T") == 0)
    return &paths.Output;
  if (std::strcmp(option, "--shared-data") == 0)
    return &paths.SharedData;
  return nullptr;
}

/// An empty value leaves the default.
void Set(std::string& path, const char* value)
{
  if (*value)
  {
    path = value;
  }
}
}

TestPaths TestPaths::FromArguments(int argc, char* argv[])
{
  TestPaths paths;
  for (int i = 0; i + 1 < argc; ++i)
  {
    if (std::string* path = PathOf(paths, argv[i]))
    {
      Set(*path, argv[++i]);
    }
  }
  return paths;
}

TestPaths TestPaths::TakeFromArguments(int& argc, char* argv[])
{
  TestPaths paths;
  int kept = 0;
  for (int i = 0; i < argc; ++i)
  {
    std::string* path = i + 1 < argc ? PathOf(paths, argv[i]) : nullptr;
    if (path)
    {
      Set(*path, argv[++i]);
    }
    else
    {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  return paths;
}
}
