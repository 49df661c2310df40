// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::PagePoolWriter
 * @brief   Streams a volume or a height-field stack into a page pool file with bounded memory.
 *
 * Conversion of data larger than memory (Lux and Froehlich, 3.3: out-of-core preprocessing).
 * The source is a callback that fills a block of consecutive slabs on request: z slices of
 * nx*ny voxels for a BrickPool, rows of a TilePool (all layers: block layout x fastest, then
 * row, then layer, i.e. count*nx values per layer). The writer never holds the data set.
 *
 * How all levels are produced in one pass: every level keeps a sliding window of its most
 * recent slices, no more than the B slices a row of pages spans plus the 3 the [1 2 1] filter
 * reads. A slice arriving at level l (from the source for l = 0, from the filter otherwise)
 * completes (a) the row of pages whose last slice it is, which are cut, summarised (min/max,
 * CRC), optionally compressed and appended to the file at once, and (b) the coarse slices of
 * level l+1 whose three taps are now present, which are computed with exactly the arithmetic
 * of strata::VolumeBrickTree (double sums, one rounding) and pushed into level l+1 recursively.
 * Slices no longer needed by either are dropped. Memory is therefore about (B + 3) slices of
 * level 0 plus 1/4 of that per coarser level (1/2 for tile pools) plus one source block; the
 * memory limit only sets how many slices one source call fills, so the file is identical
 * byte for byte whatever the limit. A limit below the minimum fails before anything is read.
 *
 * The header and page table are written last (they hold the value range and the offsets) at
 * the front of the file, whose size is known in advance. Output goes to `<name>.tmp-<pid>`,
 * is flushed with fdatasync and renamed over `<name>` only when complete; on any failure the
 * temporary file is removed and `<name>` is left untouched.
 *
 * Plain C++ (no vtkObject) so a VTK algorithm, a ParaView plugin and the strata-convert CLI
 * can all drive it; progress is reported through a callback as a fraction of pages written.
 *
 * @sa strata::PagePoolFormat strata::PagePoolFile strata::VolumeBrickTree
 */
#ifndef StrataPagePoolWriter_h
#define StrataPagePoolWriter_h

#include "StrataCoreModule.h"     // For export macro
#include "StrataPagePoolFormat.h" // For the format's enums and header

#include <cstdint>    // For fixed-width types
#include <functional> // For std::function
#include <string>     // For std::string
#include <vector>     // For std::vector

namespace strata
{
class STRATACORE_EXPORT PagePoolWriter
{
public:
  using Kind = strata::PagePoolFormat::Kind;
  using ScalarType = strata::PagePoolFormat::ScalarType;
  /**
   * Fills `buffer` with `count` slabs starting at `first` along the streaming axis (z for
   * bricks, y for tiles) in the pool's scalar type. Returns false to abort the conversion.
   */
  using SourceCallback = std::function<bool(int first, int count, void* buffer)>;
  /// Receives the fraction of pages written, in [0, 1], non-decreasing.
  using ProgressCallback = std::function<void(double fraction)>;

  /// What one Write() did, for reports and benchmarks.
  struct Statistics
  {
    uint64_t NumberOfPages = 0;
    uint64_t CompressedPages = 0; ///< pages stored as zstd frames
    uint64_t RawBytes = 0;        ///< sum of raw page sizes
    uint64_t StoredBytes = 0;     ///< sum of stored page sizes
    uint64_t FileSize = 0;
    uint64_t SourceCalls = 0;
    int SlabsPerCall = 0;
    uint64_t EstimatedPeakBytes = 0;    ///< the writer's own buffers, as budgeted
    uint64_t MeasuredPeakSlabBytes = 0; ///< largest sum of all levels' slice windows seen
  };

  ///@{
  /// Output file name (no default).
  void SetFileName(const std::string& name) { this->FileName = name; }
  const std::string& GetFileName() const { return this->FileName; }
  ///@}
  ///@{
  /// Pool kind, default BrickPool.
  void SetKind(Kind kind) { this->PoolKind = kind; }
  Kind GetKind() const { return this->PoolKind; }
  ///@}
  ///@{
  /// Scalar type of the source and of the pages, default UInt8.
  void SetScalarType(ScalarType type) { this->Type = type; }
  ScalarType GetScalarType() const { return this->Type; }
  ///@}
  ///@{
  /// Level-0 dimensions: (nx, ny, nz) voxels, or (nx, ny, layers) for tiles. Default 1 1 1.
  void SetDimensions(int nx, int ny, int nz);
  const int* GetDimensions() const { return this->Dimensions; }
  ///@}
  ///@{
  /// Geometry copied into the header: spacing (1 1 1), origin (0 0 0), row-major direction (I).
  void SetSpacing(double x, double y, double z);
  void SetOrigin(double x, double y, double z);
  void SetDirection(const double direction[9]);
  ///@}
  ///@{
  /// Page size B (values per axis, shared layer included), in [8, 512]; default 32.
  void SetPageSize(int size) { this->PageSize = size; }
  int GetPageSize() const { return this->PageSize; }
  ///@}
  ///@{
  /**
   * Per-page zstd compression, default off. A page is stored compressed only when that makes
   * it smaller. Level is zstd's (default 3).
   */
  void SetCompression(bool on) { this->Compress = on; }
  bool GetCompression() const { return this->Compress; }
  void SetCompressionLevel(int level) { this->CompressionLevel = level; }
  int GetCompressionLevel() const { return this->CompressionLevel; }
  ///@}
  ///@{
  /// Memory the writer may use for its buffers, in MB (2^20 bytes); default 512.
  void SetMemoryLimit(double megabytes) { this->MemoryLimitMB = megabytes; }
  double GetMemoryLimit() const { return this->MemoryLimitMB; }
  ///@}
  ///@{
  /**
   * Value that marks missing data (default: none). It is recorded in the header and left out
   * of page and global min/max; NaN is always left out. The down-sampling filter does not
   * treat it specially (as strata::VolumeBrickTree), so pick NaN for float height fields.
   */
  void SetNoDataValue(double value);
  void ClearNoDataValue() { this->HasNoData = false; }
  ///@}
  /**
   * The file written is component `component` of a set of `components` brick pools, all
   * written with the same `tag` (strata::PagePoolFormat, Components); default: one component.
   */
  void SetComponent(int component, int components, uint32_t tag)
  {
    this->Component = component;
    this->Components = components;
    this->ComponentsTag = tag;
  }
  void SetSource(SourceCallback source) { this->Source = std::move(source); }
  void SetProgressCallback(ProgressCallback progress) { this->Progress = std::move(progress); }

  /// Converts. Returns false, with GetErrorMessage() saying why, leaving no file behind.
  bool Write();

  const std::string& GetErrorMessage() const { return this->ErrorMessage; }
  const Statistics& GetStatistics() const { return this->Stats; }

private:
  template<typename T>
  bool WriteTyped();
  bool MakeHeader(strata::PagePoolFormat::Header& header,
    std::vector<strata::PagePoolFormat::Level>& levels);

  std::string FileName;
  Kind PoolKind = Kind::BrickPool;
  ScalarType Type = ScalarType::UInt8;
  int Dimensions[3] = { 1, 1, 1 };
  double Spacing[3] = { 1, 1, 1 };
  double Origin[3] = { 0, 0, 0 };
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  int PageSize = 32;
  bool Compress = false;
  int CompressionLevel = 3;
  double MemoryLimitMB = 512;
  bool HasNoData = false;
  double NoDataValue = 0;
  int Component = 0;
  int Components = 1;
  uint32_t ComponentsTag = 0;
  SourceCallback Source;
  ProgressCallback Progress;
  std::string ErrorMessage;
  Statistics Stats;
};
}

#endif
