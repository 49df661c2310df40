// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataPagePoolFile.h"

#include <zstd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <map>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace strata
{

namespace
{
using Format = strata::PagePoolFormat;

// Reads exactly `size` bytes at `offset`; short reads mean the file changed under us.
bool ReadAll(int fd, void* data, size_t size, uint64_t offset, std::string& error)
{
  char* p = static_cast<char*>(data);
  while (size > 0)
  {
    const ssize_t n = ::pread(fd, p, size, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n < 0)
    {
      error = std::string("read error: ") + std::strerror(errno);
      return false;
    }
    if (n == 0)
    {
      error = "unexpected end of file at byte " + std::to_string(offset);
      return false;
    }
    p += n;
    size -= static_cast<size_t>(n);
    offset += static_cast<uint64_t>(n);
  }
  return true;
}

// The signature OpenShared compares: a file replaced on disk (rewritten, renamed over) differs.
bool ReadSignature(const struct stat& info, uint64_t out[4])
{
  out[0] = static_cast<uint64_t>(info.st_dev);
  out[1] = static_cast<uint64_t>(info.st_ino);
  out[2] = static_cast<uint64_t>(info.st_size);
  out[3] = static_cast<uint64_t>(info.st_mtim.tv_sec) * 1000000000ull +
           static_cast<uint64_t>(info.st_mtim.tv_nsec);
  return true;
}

std::atomic<long long> Opens{ 0 };

struct SharedFiles
{
  std::mutex Mutex;
  std::map<std::string, std::weak_ptr<PagePoolFile>> Files;
};

SharedFiles& Shared()
{
  static SharedFiles* files = new SharedFiles; // never destroyed: used from static destructors
  return *files;
}

template<typename T>
void ToFloat(const unsigned char* raw, uint64_t count, float* out)
{
  for (uint64_t i = 0; i < count; ++i)
  {
    T v;
    std::memcpy(&v, raw + i * sizeof(T), sizeof(T));
    out[i] = static_cast<float>(v);
  }
}
}

PagePoolFile::~PagePoolFile()
{
  this->Close();
}

void PagePoolFile::Close()
{
  if (this->Fd >= 0)
  {
    ::close(this->Fd);
  }
  this->Fd = -1;
  std::fill(this->Signature, this->Signature + 4, 0);
  this->Levels.clear();
  this->Table.clear();
  this->PageValues = 0;
  this->PoolHeader = Header();
}

std::shared_ptr<PagePoolFile> PagePoolFile::OpenShared(const std::string& path, std::string& error)
{
  SharedFiles& shared = Shared();
  std::lock_guard<std::mutex> lock(shared.Mutex);
  std::shared_ptr<PagePoolFile> file = shared.Files[path].lock();
  struct stat info;
  uint64_t now[4] = { 0, 0, 0, 0 };
  if (file && ::stat(path.c_str(), &info) == 0 && ReadSignature(info, now) &&
      std::equal(now, now + 4, file->Signature))
  {
    return file;
  }
  file = std::make_shared<PagePoolFile>();
  if (!file->Open(path))
  {
    error = file->GetErrorMessage();
    shared.Files.erase(path);
    return nullptr;
  }
  shared.Files[path] = file;
  // Entries of files nobody holds any more go, so the table stays as small as what is open.
  for (auto it = shared.Files.begin(); it != shared.Files.end();)
    it = it->second.expired() ? shared.Files.erase(it) : std::next(it);
  return file;
}

std::shared_ptr<PagePoolFile> PagePoolFile::OpenSharedComponent(const PagePoolFile& first,
  int c,
  std::string& error)
{
  const std::string path = strata::PagePoolFormat::GetComponentFileName(first.Path, c);
  std::shared_ptr<PagePoolFile> file = OpenShared(path, error);
  if (file && !strata::PagePoolFormat::CheckComponent(first.PoolHeader, file->PoolHeader, c, error))
  {
    error = "page pool '" + path + "': " + error;
    return nullptr;
  }
  return file;
}

long long PagePoolFile::GetNumberOfOpens()
{
  return Opens.load();
}

bool PagePoolFile::Open(const std::string& path)
{
  this->Close();
  this->Path = path;
  this->ErrorMessage.clear();
  auto fail = [&](const std::string& why)
  {
    this->ErrorMessage = "page pool '" + path + "': " + why;
    this->Close();
    return false;
  };
  const uint16_t probe = 1;
  unsigned char first;
  std::memcpy(&first, &probe, 1);
  if (first != 1)
  {
    return fail("big-endian hosts are not supported");
  }
  this->Fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (this->Fd < 0)
  {
    return fail(std::string("cannot open: ") + std::strerror(errno));
  }
  ++Opens;
  struct stat info;
  if (::fstat(this->Fd, &info) != 0)
  {
    return fail(std::string("cannot stat: ") + std::strerror(errno));
  }
  ReadSignature(info, this->Signature);
  if (!S_ISREG(info.st_mode))
  {
    return fail("not a regular file");
  }
  const uint64_t fileSize = static_cast<uint64_t>(info.st_size);
  if (fileSize < Format::HeaderSize)
  {
    return fail("truncated file: " + std::to_string(fileSize) + " bytes, the header alone needs " +
                std::to_string(Format::HeaderSize));
  }
  unsigned char head[Format::HeaderSize];
  std::string why;
  if (!ReadAll(this->Fd, head, sizeof(head), 0, why))
  {
    return fail(why);
  }
  Header header;
  if (!Format::ValidateHeaderBytes(head, fileSize, header, why))
  {
    return fail(why);
  }
  // The header is consistent with the file size, so the table size is bounded by it.
  std::vector<unsigned char> table(header.NumberOfPages * Format::EntrySize);
  if (!ReadAll(this->Fd, table.data(), table.size(), header.TableOffset, why))
  {
    return fail(why);
  }
  if (Format::Crc32(table.data(), table.size()) != header.TableChecksum)
  {
    return fail("page table checksum mismatch: the page table is corrupt");
  }
  std::vector<PageEntry> entries(header.NumberOfPages);
  for (size_t id = 0; id < entries.size(); ++id)
  {
    Format::DecodeEntry(table.data() + id * Format::EntrySize, entries[id]);
  }
  if (!Format::ValidateTable(header, entries, why))
  {
    return fail(why);
  }
  std::vector<Level> levels;
  if (!Format::ComputeLevels(header.PoolKind, header.Dimensions, header.PageSize, levels, why))
  {
    return fail(why);
  }
  this->PoolHeader = header;
  this->Levels = std::move(levels);
  this->Table = std::move(entries);
  this->PageValues = Format::GetPageValues(header.PoolKind, header.Dimensions, header.PageSize);
  return true;
}

uint64_t PagePoolFile::GetPageBytes() const
{
  return this->PageValues * Format::GetScalarSize(this->PoolHeader.Type);
}

int64_t PagePoolFile::GetPageId(int level, uint64_t index) const
{
  if (level < 0 || level >= this->GetNumberOfLevels())
  {
    return -1;
  }
  const Level& l = this->Levels[level];
  const uint64_t count = static_cast<uint64_t>(l.Pages[0]) * l.Pages[1] * l.Pages[2];
  return index < count ? static_cast<int64_t>(l.FirstPage + index) : -1;
}

float PagePoolFile::GetPageMin(int level, uint64_t index) const
{
  const int64_t id = this->GetPageId(level, index);
  return id < 0 ? 0.0f : this->Table[id].Min;
}

float PagePoolFile::GetPageMax(int level, uint64_t index) const
{
  const int64_t id = this->GetPageId(level, index);
  return id < 0 ? 0.0f : this->Table[id].Max;
}

std::string PagePoolFile::GetLastPageError() const
{
  std::lock_guard<std::mutex> lock(this->ErrorMutex);
  return this->LastPageError;
}

bool PagePoolFile::Fail(std::string* out, const std::string& message) const
{
  const std::string error = "page pool '" + this->Path + "': " + message;
  if (out)
  {
    *out = error;
  }
  std::lock_guard<std::mutex> lock(this->ErrorMutex);
  this->LastPageError = error;
  return false;
}

bool PagePoolFile::ReadStored(int level,
  uint64_t index,
  std::vector<unsigned char>& raw,
  std::string& error) const
{
  if (this->Fd < 0)
  {
    error = "not open";
    return false;
  }
  const int64_t id = this->GetPageId(level, index);
  if (id < 0)
  {
    error = "no page " + std::to_string(index) + " in level " + std::to_string(level);
    return false;
  }
  const PageEntry& e = this->Table[id];
  const std::string name =
    "page (level " + std::to_string(level) + ", index " + std::to_string(index) + ")";
  std::vector<unsigned char> stored(e.StoredSize);
  std::string why;
  if (!ReadAll(this->Fd, stored.data(), stored.size(), e.Offset, why))
  {
    error = name + ": " + why;
    return false;
  }
  const uint32_t crc = Format::Crc32(stored.data(), stored.size());
  if (crc != e.Checksum)
  {
    char text[96];
    std::snprintf(text,
      sizeof(text),
      ": checksum mismatch (stored %08x, computed %08x), corrupt",
      e.Checksum,
      crc);
    error = name + text;
    return false;
  }
  const uint64_t bytes = this->GetPageBytes();
  if (e.PageEncoding == Format::Encoding::Raw)
  {
    raw = std::move(stored);
    return true;
  }
  raw.resize(bytes);
  const size_t n = ZSTD_decompress(raw.data(), raw.size(), stored.data(), stored.size());
  if (ZSTD_isError(n) || n != bytes)
  {
    error = name + ": bad zstd frame (" +
            (ZSTD_isError(n) ? std::string(ZSTD_getErrorName(n)) : "wrong size") + ")";
    return false;
  }
  return true;
}

bool PagePoolFile::ReadPageNative(int level, uint64_t index, void* out, std::string* error) const
{
  std::vector<unsigned char> raw;
  std::string why;
  if (!this->ReadStored(level, index, raw, why))
  {
    return this->Fail(error, why);
  }
  std::memcpy(out, raw.data(), raw.size());
  return true;
}

bool PagePoolFile::ReadPage(int level, uint64_t index, float* out, std::string* error) const
{
  std::vector<unsigned char> raw;
  std::string why;
  if (!this->ReadStored(level, index, raw, why))
  {
    return this->Fail(error, why);
  }
  switch (this->PoolHeader.Type)
  {
    case Format::ScalarType::UInt8:
      ToFloat<uint8_t>(raw.data(), this->PageValues, out);
      break;
    case Format::ScalarType::UInt16:
      ToFloat<uint16_t>(raw.data(), this->PageValues, out);
      break;
    case Format::ScalarType::Int16:
      ToFloat<int16_t>(raw.data(), this->PageValues, out);
      break;
    case Format::ScalarType::Float32:
      ToFloat<float>(raw.data(), this->PageValues, out);
      break;
  }
  return true;
}
}
