// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// A test as a sequence of named parts: each part is a small function whose checks count their
// failures in the test's own counter; the runner runs the parts in order, says after each
// whether it passed ("sub-test <name>: ok" or "sub-test <name>: FAILED, <n> failed checks") and
// returns the test's exit code.
#ifndef StrataSubTests_h
#define StrataSubTests_h

#include <functional>
#include <string>
#include <vector>

namespace strata_test
{
struct SubTest
{
  std::string Name;
  std::function<void()> Run;
};

/// Runs `parts` in order; a part fails when `failures()` (the test's count of failed checks)
/// grew while it ran. Returns EXIT_SUCCESS when no check failed, else EXIT_FAILURE.
int RunSubTests(const std::vector<SubTest>& parts, const std::function<int()>& failures);
}

#endif
