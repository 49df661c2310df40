// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// NumPy arrays (.npy) through vtkNumpyGridReader, in either axis order.
#include "StrataFuzz.h"

#include "vtkNew.h"
#include "vtkNumpyGridReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  // One read per input, the axis order chosen by the input's size (two reads halved the rate).
  vtkNew<vtkNumpyGridReader> reader;
  reader->SetFileName(strata_fuzz::WriteInput(data, size, ".npy").c_str());
  reader->SetSwapAxes(size % 2 == 1);
  reader->SetNullValue(0.0);
  reader->Update();
  return 0;
}
