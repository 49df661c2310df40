// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// MetaImage headers with their data (.mha, ElementDataFile LOCAL, or a data file that is not
// there) through vtkStreamingMetaImageReader: the whole extent, then one slab.
#include "StrataFuzz.h"

#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStreamingMetaImageReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  const std::string path = strata_fuzz::WriteInput(data, size, ".mha");
  vtkStreamingMetaImageReader::IsStreamable(path.c_str());
  vtkNew<vtkStreamingMetaImageReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  reader->UpdateInformation();
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  if (extent[5] > extent[4])
  {
    extent[4] = extent[5] = (extent[4] + extent[5]) / 2;
    reader->UpdateExtent(extent);
  }
  return 0;
}
