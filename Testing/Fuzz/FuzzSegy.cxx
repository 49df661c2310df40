// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// SEG-Y post-stack volumes through vtkSegyVolumeReader (segyio underneath), with the line
// numbers at the standard trace header bytes (189, 193) or at the older ones (9, 21).
#include "StrataFuzz.h"

#include "vtkNew.h"
#include "vtkSegyVolumeReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  // One read per input, the byte positions chosen by the input's size (two reads halved the
  // rate).
  const bool standard = size % 2 == 0;
  vtkNew<vtkSegyVolumeReader> reader;
  reader->SetFileName(strata_fuzz::WriteInput(data, size, ".sgy").c_str());
  reader->SetInlineByte(standard ? 189 : 9);
  reader->SetCrosslineByte(standard ? 193 : 21);
  reader->Update();
  return 0;
}
