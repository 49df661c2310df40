// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// Hybrid point/volume files (.shv) through vtkHybridVolumeReader. The file's checksum is made
// to match the fuzzed bytes before they are written, so that mutations reach the checks behind
// it (sizes, points) instead of stopping at the checksum.
#include "StrataFuzz.h"

#include "StrataHybridVolumeFile.h"
#include "vtkHybridVolumeReader.h"
#include "vtkNew.h"

#include <cstring>
#include <vector>

namespace
{
// strata::HybridVolumeFile's FNV-1a over the header before the checksum field and all that follows
// the header.
constexpr size_t ChecksumOffset = 152;

uint64_t Fnv(const uint8_t* data, size_t n, uint64_t hash)
{
  for (size_t i = 0; i < n; ++i)
  {
    hash = (hash ^ data[i]) * 1099511628211ull;
  }
  return hash;
}
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  std::vector<uint8_t> bytes(data, data + size);
  const size_t header = strata::HybridVolumeFile::HeaderSize;
  if (size >= header)
  {
    uint64_t hash = Fnv(bytes.data(), ChecksumOffset, 1469598103934665603ull);
    hash = Fnv(bytes.data() + header, size - header, hash);
    std::memcpy(bytes.data() + ChecksumOffset, &hash, sizeof(hash));
  }
  vtkNew<vtkHybridVolumeReader> reader;
  reader->SetFileName(strata_fuzz::WriteInput(bytes.data(), bytes.size(), ".shv").c_str());
  reader->Update();
  return 0;
}
