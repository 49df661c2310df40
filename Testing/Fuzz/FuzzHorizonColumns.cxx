// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// ASCII horizon columns through vtkHorizonColumnReader: detected, and as inline/crossline and
// as x/y/z columns.
#include "StrataFuzz.h"

#include "vtkHorizonColumnReader.h"
#include "vtkNew.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  const std::string path = strata_fuzz::WriteInput(data, size, ".txt");
  for (auto mode : { vtkHorizonColumnReader::ColumnMode::Auto,
         vtkHorizonColumnReader::ColumnMode::InlineCrossline,
         vtkHorizonColumnReader::ColumnMode::XYZ })
  {
    vtkNew<vtkHorizonColumnReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetMode(mode);
    reader->Update();
  }
  return 0;
}
