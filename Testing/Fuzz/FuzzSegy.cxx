// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// SEG-Y post-stack volumes through vtkSegyVolumeReader (segyio underneath), with the line
// numbers at the standard trace header bytes (189, 193) and at the older ones (9, 21).
#include "StrataFuzz.h"

#include "vtkNew.h"
#include "vtkSegyVolumeReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  const std::string path = strata_fuzz::WriteInput(data, size, ".sgy");
  for (bool standard : { true, false })
  {
    vtkNew<vtkSegyVolumeReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetInlineByte(standard ? 189 : 9);
    reader->SetCrosslineByte(standard ? 193 : 21);
    reader->Update();
  }
  return 0;
}
