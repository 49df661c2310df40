// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::PagePoolFile
 * @brief   Thread-safe reader of a page pool file: validated header and table, checked pages.
 *
 * The disk end of the paging pipeline (Lux and Froehlich, 3.3): the page cache's worker
 * threads call ReadPage concurrently, so reads use pread on one descriptor (no shared file
 * position) and per-call buffers; after Open the object is read-only and every const method
 * may be called from any number of threads. Open validates the header and the whole page
 * table against the real file size, so a truncated or hostile file is refused before any
 * page is touched; ReadPage verifies the page's CRC-32 (and the zstd frame's size) so a
 * corrupt page is refused with a message and never returned as data. Per-page min/max come
 * from the table, letting the cut skip empty pages without any I/O.
 *
 * @sa strata::PagePoolFormat strata::PagePoolWriter
 */
#ifndef StrataPagePoolFile_h
#define StrataPagePoolFile_h

#include "StrataCoreModule.h"     // For export macro
#include "StrataPagePoolFormat.h" // For the header and table types

#include <cstdint> // For fixed-width types
#include <memory>  // For std::shared_ptr
#include <mutex>   // For std::mutex
#include <string>  // For std::string
#include <vector>  // For std::vector

namespace strata
{
class STRATACORE_EXPORT PagePoolFile
{
public:
  using Header = strata::PagePoolFormat::Header;
  using PageEntry = strata::PagePoolFormat::PageEntry;
  using Level = strata::PagePoolFormat::Level;

  PagePoolFile() = default;
  ~PagePoolFile();
  PagePoolFile(const PagePoolFile&) = delete;
  PagePoolFile& operator=(const PagePoolFile&) = delete;

  /**
   * Opens and validates `path`. Returns false, with GetErrorMessage() naming the file and the
   * fault (missing, unreadable, truncated, bad magic/version, corrupt header or table, absurd
   * values), leaving the object closed. Not to be called concurrently with reads.
   */
  bool Open(const std::string& path);
  void Close();

  ///@{
  /**
   * The pool at `path` opened once per process: the file some reader, pager or picker holds
   * open already, while the file on disk is that file still (same device, inode, size and
   * modification time), else a newly opened one. Null, with `error` naming the file and the
   * fault, when it cannot be opened. A shared file is read-only: never Open or Close it.
   * (A process-wide table, not a member: the point is that a reader and the mappers paging
   * its output, which know nothing of each other, hold one descriptor and one page table.)
   */
  static std::shared_ptr<PagePoolFile> OpenShared(const std::string& path, std::string& error);
  /**
   * OpenShared of component `c` of the set of components `first` heads (its component 0;
   * strata::PagePoolFormat, Components), checked to belong to it (CheckComponent); null, with
   * `error` naming the file and what differs, otherwise.
   */
  static std::shared_ptr<PagePoolFile> OpenSharedComponent(const PagePoolFile& first,
    int c,
    std::string& error);
  /// Files this process has opened (Open calls that reached the disk), for tests of sharing.
  static long long GetNumberOfOpens();
  ///@}
  const std::string& GetPath() const { return this->Path; }
  bool IsOpen() const { return this->Fd >= 0; }

  const Header& GetHeader() const { return this->PoolHeader; }
  strata::PagePoolFormat::Kind GetKind() const { return this->PoolHeader.PoolKind; }
  strata::PagePoolFormat::ScalarType GetScalarType() const { return this->PoolHeader.Type; }
  const int* GetDimensions() const { return this->PoolHeader.Dimensions; }
  int GetPageSize() const { return this->PoolHeader.PageSize; }
  int GetNumberOfLevels() const { return static_cast<int>(this->Levels.size()); }
  const Level& GetLevel(int l) const { return this->Levels[l]; }
  uint64_t GetNumberOfPages() const { return this->Table.size(); }
  /// Values per page (B^3, or B^2 * layers) and its raw size in bytes.
  uint64_t GetPageValues() const { return this->PageValues; }
  uint64_t GetPageBytes() const;
  /// Page number of page `index` of level `l` (as strata::VolumeBrickTree's node ids); -1 if none.
  int64_t GetPageId(int level, uint64_t index) const;

  ///@{
  /// Table entry and the page's value range, without reading it; id as GetPageId.
  const PageEntry& GetPageEntry(uint64_t id) const { return this->Table[id]; }
  float GetPageMin(int level, uint64_t index) const;
  float GetPageMax(int level, uint64_t index) const;
  ///@}

  ///@{
  /**
   * Reads and checks one page: GetPageValues() values, converted to float or in the native
   * type (GetPageBytes() bytes). Thread-safe. Returns false on a bad page address, a read
   * error, a checksum mismatch or a bad zstd frame, with the reason in `error` (if given) and
   * in GetLastPageError(); `out` is then unspecified but never holds unchecked file bytes
   * presented as valid.
   */
  bool ReadPage(int level, uint64_t index, float* out, std::string* error = nullptr) const;
  bool ReadPageNative(int level, uint64_t index, void* out, std::string* error = nullptr) const;
  ///@}

  /// Why Open failed.
  const std::string& GetErrorMessage() const { return this->ErrorMessage; }
  /// The most recent page error from any thread (a copy, safely taken).
  std::string GetLastPageError() const;

private:
  bool ReadStored(int level,
    uint64_t index,
    std::vector<unsigned char>& raw,
    std::string& error) const;
  bool Fail(std::string* out, const std::string& message) const;

  std::string Path;
  int Fd = -1;
  /// What the file was when opened (device, inode, size, modification time in ns).
  uint64_t Signature[4] = { 0, 0, 0, 0 };
  Header PoolHeader;
  std::vector<Level> Levels;
  std::vector<PageEntry> Table;
  uint64_t PageValues = 0;
  std::string ErrorMessage;
  mutable std::mutex ErrorMutex;
  mutable std::string LastPageError;
};
}

#endif
