// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Inputs that fuzzing (Testing/Fuzz) found to crash a reader or to reach undefined behaviour,
// each now a clean error that names what is wrong. The same inputs are in the fuzz corpus
// (Testing/Fuzz/corpus/<target>/crash-*), where the sanitized builds replay them; here each is
// written by the test itself and its error message checked, so that a plain build catches a
// reader that accepts it again.
#include "StrataErrorCounter.h"
#include "StrataSubTests.h"
#include "StrataTestHelpers.h"
#include "StrataTestPaths.h"

#include "vtkAlgorithm.h"
#include "vtkAsciiGridReader.h"
#include "vtkNew.h"
#include "vtkStreamingMetaImageReader.h"

#include <fstream>
#include <iostream>
#include <string>

namespace
{
using strata_test::Check;

void Spit(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// Runs `reader` on `bytes` written to `path`: it must fail with an error containing `expected`.
template<typename Reader>
void CheckRefused(const std::string& path,
  const std::string& bytes,
  const std::string& expected,
  const std::string& what)
{
  Spit(path, bytes);
  vtkNew<Reader> reader;
  vtkNew<strata_test::ErrorCounter> errors;
  errors->Watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  Check(errors->Errors > 0 && errors->First.find(expected) != std::string::npos,
    what + ": refused with \"" + expected + "\" (got \"" + errors->First + "\")");
}

void MetaImage(const std::string& dir)
{
  // Three DimSize of 2^31 - 1 doubles: their byte count overflowed a long long (UBSan,
  // signed-integer-overflow) before the file size was compared with it.
  CheckRefused<vtkStreamingMetaImageReader>(dir + "TestReaderFaults_dimsize.mha",
    "NDims = 3\nDimSize = 2147483647 2147483647 2147483647\nElementType = MET_DOUBLE\n"
    "ElementDataFile = LOCAL\nabc",
    "more than 2^62 bytes",
    "MetaImage DimSize overflow");
}

void AsciiGrid(const std::string& dir)
{
  // A line of separators only: format detection indexed its first token of none (a crash in
  // g++ builds, UBSan's null reference under the fuzzer).
  CheckRefused<vtkAsciiGridReader>(
    dir + "TestReaderFaults_separators.txt", ",", "not a text grid", "text grid of one comma");
  CheckRefused<vtkAsciiGridReader>(dir + "TestReaderFaults_separators2.txt",
    "\n ;, ,\n1 2 3\n",
    "not a text grid",
    "text grid whose first line is separators");
}
}

int TestReaderFaults(int argc, char* argv[])
{
  const strata_test::TestPaths paths = strata_test::TestPaths::FromArguments(argc, argv);
  const std::string dir = paths.Output + "/";
  strata_test::RunSubTests(
    {
      { "MetaImage", [&] { MetaImage(dir); } },
      { "AsciiGrid", [&] { AsciiGrid(dir); } },
    },
    strata_test::Failures);
  if (strata_test::Failures())
  {
    std::cerr << strata_test::Failures() << " check(s) failed\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
