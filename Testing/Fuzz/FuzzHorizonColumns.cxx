// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// ASCII horizon columns through vtkHorizonColumnReader: detected, or read as inline/crossline
// or as x/y/z columns, the mode chosen by the input's size (one read per input: a small file may
// legitimately span a grid of 2^24 nodes, 64 MB to fill, so each read counts).
#include "StrataFuzz.h"

#include "vtkHorizonColumnReader.h"
#include "vtkNew.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  const std::string path = strata_fuzz::WriteInput(data, size, ".txt");
  using Mode = vtkHorizonColumnReader::ColumnMode;
  const Mode modes[3] = { Mode::Auto, Mode::InlineCrossline, Mode::XYZ };
  vtkNew<vtkHorizonColumnReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetMode(modes[size % 3]);
  reader->Update();
  return 0;
}
