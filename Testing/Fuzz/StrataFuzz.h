// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// What every fuzz target shares. Strata's readers take file names, so each input is written to
// a file in memory (/dev/shm when it exists, else the temporary folder) with the extension the
// reader expects, and VTK's output window is silenced: a reader's error on garbage is the
// expected outcome, only a sanitizer report, a crash, a leak or a hang is a finding.
#ifndef StrataFuzz_h
#define StrataFuzz_h

#include <cstddef>
#include <cstdint>
#include <string>

namespace strata_fuzz
{
/// Silences VTK's errors and warnings (once per process), unless STRATA_FUZZ_VERBOSE is set.
void SilenceVTK();

/// Writes `data` to this process's input file with extension `extension` (".gri", ...) and
/// returns its path; the same path for every input of a run.
std::string WriteInput(const uint8_t* data, size_t size, const std::string& extension);
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

#endif
