// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataSubTests.h"

#include <cstdlib>
#include <iostream>

namespace strata_test
{
int RunSubTests(const std::vector<SubTest>& parts, const std::function<int()>& failures)
{
  for (const SubTest& part : parts)
  {
    const int before = failures();
    part.Run();
    const int failed = failures() - before;
    if (failed == 0)
    {
      std::cout << "sub-test " << part.Name << ": ok\n";
    }
    else
    {
      std::cout << "sub-test " << part.Name << ": FAILED, " << failed << " failed checks\n";
    }
  }
  return failures() == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
}
