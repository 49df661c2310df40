// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// Page pools (.spp, brick and tile pools): the header and page table through strata::PagePoolFile,
// every page of every level read (as float and native), then vtkPagePoolReader at full or at
// the coarsest resolution. The checksums of the pages, the table and the header are made to
// match the fuzzed bytes before they are written, so that mutations reach the checks behind
// them (levels, offsets, sizes, zstd frames) instead of stopping at a checksum.
#include "StrataFuzz.h"

#include "StrataPagePoolFile.h"
#include "StrataPagePoolFormat.h"
#include "vtkNew.h"
#include "vtkPagePoolReader.h"

#include <vector>

namespace
{
using Format = strata::PagePoolFormat;

// Where the encodings keep their checksums (StrataPagePoolFormat.cxx).
constexpr size_t TableChecksumOffset = 232;
constexpr size_t HeaderChecksumOffset = 252;
constexpr size_t EntryChecksumOffset = 32;

void PutU32(uint8_t* p, uint32_t v)
{
  for (int b = 0; b < 4; ++b)
  {
    p[b] = static_cast<uint8_t>(v >> (8 * b));
  }
}

/// Recomputes each checksum whose bytes lie inside the file, innermost first.
void FixChecksums(std::vector<uint8_t>& bytes)
{
  const size_t size = bytes.size();
  if (size < Format::HeaderSize)
  {
    return;
  }
  Format::Header header;
  Format::DecodeHeader(bytes.data(), header);
  const uint64_t offset = header.TableOffset;
  if (offset <= size && header.NumberOfPages <= (size - offset) / Format::EntrySize)
  {
    for (uint64_t id = 0; id < header.NumberOfPages; ++id)
    {
      uint8_t* entry = bytes.data() + offset + id * Format::EntrySize;
      Format::PageEntry e;
      Format::DecodeEntry(entry, e);
      if (e.Offset <= size && e.StoredSize <= size - e.Offset)
      {
        PutU32(entry + EntryChecksumOffset,
          Format::Crc32(bytes.data() + e.Offset, static_cast<size_t>(e.StoredSize)));
      }
    }
    const size_t tableBytes = static_cast<size_t>(header.NumberOfPages) * Format::EntrySize;
    PutU32(bytes.data() + TableChecksumOffset, Format::Crc32(bytes.data() + offset, tableBytes));
  }
  PutU32(bytes.data() + HeaderChecksumOffset, Format::Crc32(bytes.data(), HeaderChecksumOffset));
}

/// Every page of every level through the file interface, both conversions.
void ReadAllPages(const std::string& path)
{
  strata::PagePoolFile file;
  if (!file.Open(path))
  {
    return;
  }
  // The format allows pages of up to 1 GB (strata::PagePoolFormat::MaxPageBytes), and a compressed
  // page of a few bytes may declare one (found: a 400-byte tile pool of 6 x 5 nodes and 24577
  // layers, one 567 MB page). Reading it is correct and costs its size; this pass, which holds two
  // copies beside the file's own buffer, leaves such pools to the reader below.
  constexpr uint64_t MaxPassBytes = uint64_t(64) << 20;
  if (file.GetPageBytes() > MaxPassBytes)
  {
    return;
  }
  std::vector<float> values(file.GetPageValues());
  std::vector<unsigned char> native(file.GetPageBytes());
  for (int l = 0; l < file.GetNumberOfLevels(); ++l)
  {
    const Format::Level& level = file.GetLevel(l);
    const uint64_t pages = static_cast<uint64_t>(level.Pages[0]) * level.Pages[1] * level.Pages[2];
    for (uint64_t index = 0; index < pages; ++index)
    {
      file.GetPageMin(l, index);
      file.GetPageMax(l, index);
      file.ReadPage(l, index, values.data());
      file.ReadPageNative(l, index, native.data());
    }
  }
}
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  strata_fuzz::SilenceVTK();
  std::vector<uint8_t> bytes(data, data + size);
  FixChecksums(bytes);
  const std::string path = strata_fuzz::WriteInput(bytes.data(), bytes.size(), ".spp");
  ReadAllPages(path);
  // Then the reader: full resolution of the first layer, or (odd sizes) the coarsest level of
  // the second, a tile pool's; one read per input.
  const bool full = size % 2 == 0;
  vtkNew<vtkPagePoolReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetResolution(full ? 1.0 : 0.0);
  reader->SetLayer(full ? 0 : 1);
  reader->Update();
  return 0;
}
