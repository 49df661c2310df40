// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// Irap binary horizon grids (.gri) through vtkIrapBinaryGridReader.
#include "StrataFuzz.h"

#include "vtkIrapBinaryGridReader.h"
#include "vtkNew.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  vtkNew<vtkIrapBinaryGridReader> reader;
  reader->SetFileName(strata_fuzz::WriteInput(data, size, ".gri").c_str());
  reader->Update();
  return 0;
}
