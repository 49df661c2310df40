// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataMemory.h"

#include <cstddef>
#include <fstream>
#include <malloc.h>
#include <string>

#if defined(__SANITIZE_ADDRESS__)
#define STRATA_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define STRATA_TEST_ASAN 1
#endif
#endif
#ifdef STRATA_TEST_ASAN
// The sanitizer runtime's own count (sanitizer/allocator_interface.h, which gcc does not ship).
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#endif

namespace strata_test
{
double ResidentKiB()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0)
      return std::stod(line.substr(6));
  return -1.0;
}

double HeapInUseKiB()
{
#ifdef STRATA_TEST_ASAN
  return static_cast<double>(__sanitizer_get_current_allocated_bytes()) / 1024.0;
#else
  const struct mallinfo2 m = mallinfo2();
  return (static_cast<double>(m.uordblks) + static_cast<double>(m.hblkhd)) / 1024.0;
#endif
}

bool UnderAddressSanitizer()
{
#ifdef STRATA_TEST_ASAN
  return true;
#else
  return false;
#endif
}
}
