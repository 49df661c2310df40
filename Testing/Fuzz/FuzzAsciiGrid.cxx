// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// Text horizon grids (Irap classic ASCII, ZMAP+, ESRI ASCII, whitespace matrices) through
// vtkAsciiGridReader: the format detected from the input (Auto) for most inputs, and named for
// the rest (by the input's size, so one reader run per input covers every parser).
#include "StrataFuzz.h"

#include "vtkAsciiGridReader.h"
#include "vtkNew.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  vtkNew<vtkAsciiGridReader> reader;
  reader->SetFileName(strata_fuzz::WriteInput(data, size, ".asc").c_str());
  using Format = vtkAsciiGridReader::GridFormat;
  const Format named[] = {
    Format::Auto, Format::Auto, Format::IrapClassic, Format::Zmap, Format::EsriAscii, Format::Matrix
  };
  reader->SetFormat(named[size % 6]);
  reader->Update();
  return 0;
}
