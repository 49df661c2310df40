// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// NumPy arrays (.npy) through vtkNumpyGridReader, in both axis orders.
#include "StrataFuzz.h"

#include "vtkNew.h"
#include "vtkNumpyGridReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  const std::string path = strata_fuzz::WriteInput(data, size, ".npy");
  for (bool swap : { false, true })
  {
    vtkNew<vtkNumpyGridReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetSwapAxes(swap);
    reader->SetNullValue(0.0);
    reader->Update();
  }
  return 0;
}
