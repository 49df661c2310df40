// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::PagePoolFormat
 * @brief   The versioned on-disk layout of Strata page pools (brick pools and tile pools).
 *
 * A page pool holds every level of a multi-resolution data set cut into fixed-size pages, the
 * unit the page cache reads and the GPU atlas stores (Lux and Froehlich, multi-volume ray
 * casting 3.1 and stacked height-field ray casting 3.3): bricks of B^3 voxels for volumes
 * (the octree of strata::VolumeBrickTree, exactly) and tiles of B^2 points times all layers for
 * height-field stacks (the quadtree of strata::MinMaxQuadtree). One format serves both, told apart
 * by the Kind field, so one reader, one cache and one set of fault checks serve both.
 *
 * Geometry (shared with strata::VolumeBrickTree): pages share one layer with their neighbours
 * (stride S = B - 1); page (l, i, j, k) covers level-l points [i S, i S + B - 1] (clamped to
 * the level: points beyond it repeat its last point) per axis. Level l+1 keeps every second
 * point of level l, filtered by [1 2 1]/4 per filtered axis with clamping at the border,
 * computed in double and rounded half up to integer types (cast for float); n > 1 points
 * become n/2 + 1, 1 stays 1. Levels stop at the first level that fits in one page.
 * At most 2^31 - 1 pages in all (page ids are 32-bit).
 * - BrickPool: dims (nx, ny, nz) voxels; all three axes filtered; page = B*B*B values.
 * - TilePool: dims (nx, ny, L): L height-field layers on one (nx, ny) grid, stored together
 *   because the ray caster tests all layers of a tile at once; only x and y are filtered and
 *   paged (L stays L at every level); page = B*B*L values, x fastest, then y, then layer.
 *   One height field is simply L = 1.
 * Pages are numbered as strata::VolumeBrickTree's nodes: level by level from level 0, within a
 * level x fastest (tiles: index = ty * tilesX + tx); the root is the last page.
 *
 * Components. A volume of n > 1 components (RGBA colour, independent channels) is n brick
 * pools, one per component, each a complete pool of one scalar (so every component pages,
 * caches and enters the atlas like any volume): component 0 in the file the user names,
 * component c in GetComponentFileName(name, c) ("x.spp" -> "x.c1.spp"). Such files are
 * version 2: the header adds the number of components, the file's component and a tag that
 * one write gives all its files, so that a set mixed from two writes is refused
 * (CheckComponent). One-component pools stay version 1 (an old reader cannot read only the
 * first component of a set and take it for the volume).
 *
 * Byte layout, version 1 (2: the fields at 228, 236 and 240). Everything little-endian; every
 * offset and every page start is a multiple of 8.
 * @verbatim
 * Header, 256 bytes at offset 0:
 *   0  char[8]  magic "STRATAPP"
 *   8  u32      version (1)
 *  12  u32      header size in bytes (256)
 *  16  u32      kind: 0 BrickPool, 1 TilePool
 *  20  u32      scalar type: 0 uint8, 1 uint16, 2 int16, 3 float32 (IEEE 754)
 *  24  i32[3]   dimensions of level 0 (see Kind); each in [1, 2^20]
 *  36  u32      page size B, in [8, 512]
 *  40  u32      number of levels (must equal the count implied by dims and B)
 *  44  u32      compression: 0 none, 1 zstd allowed (each page says whether it used it)
 *  48  u64      number of pages (must equal the count implied by dims and B)
 *  56  u64      page table offset (= header size)
 *  64  u64      data offset (= table offset + 40 * pages): first page byte
 *  72  u64      total file size in bytes (detects truncation)
 *  80  f64[3]   spacing (> 0)
 * 104  f64[3]   origin
 * 128  f64[9]   direction matrix, row-major (columns are the index axes in world space)
 * 200  f64[2]   value range of level 0 (NaN and no-data values excluded; min > max if none)
 * 216  f64      no-data value (meaningful only if the flag below is 1)
 * 224  u32      has no-data value: 0 or 1
 * 228  u32      version 2: number of components n, in [2, 4] (version 1: reserved, 0)
 * 232  u32      CRC-32 of the page table bytes
 * 236  u32      version 2: this file's component, in [0, n) (version 1: reserved, 0)
 * 240  u32      version 2: the write's tag, the same in every file of the set
 * 244  u8[8]    reserved, 0
 * 252  u32      CRC-32 of header bytes [0, 252)
 * Page table, 40 bytes per page, in page-number order, at the table offset:
 *   0  u32      level
 *   4  u32      index within the level (x fastest)
 *   8  u64      file offset of the stored page (multiple of 8, >= data offset)
 *  16  u64      stored size in bytes (raw size if not compressed)
 *  24  f32      min of the page's values (NaN and no-data excluded; +inf if none)
 *  28  f32      max of the page's values (-inf if none)
 *  32  u32      CRC-32 of the stored bytes
 *  36  u32      encoding: 0 raw, 1 one zstd frame of the raw page
 * Pages: raw = B*B*B (or B*B*L) little-endian values of the scalar type, x fastest; zero
 * padding up to the next multiple of 8 between pages.
 * @endverbatim
 * CRC-32 is the IEEE 802.3 polynomial (0xEDB88320 reflected, init and final xor 0xFFFFFFFF),
 * the one of zlib and PNG. Per-page min/max lets the cut skip pages without reading them.
 *
 * The class is a namespace of static functions: encoding, decoding and validation of the
 * header and the table, and the level geometry. Validation returns false with a message
 * that names the offending field, so a broken or hostile file never reaches an allocation
 * or a read that it sizes.
 *
 * @sa strata::PagePoolWriter strata::PagePoolFile strata::VolumeBrickTree strata::MinMaxQuadtree
 */
#ifndef StrataPagePoolFormat_h
#define StrataPagePoolFormat_h

#include "StrataCoreModule.h" // For export macro

#include <cstddef> // For size_t
#include <cstdint> // For fixed-width types
#include <string>  // For std::string
#include <vector>  // For std::vector

namespace strata
{
class STRATACORE_EXPORT PagePoolFormat
{
public:
  static constexpr uint32_t Version = 1;           ///< one component
  static constexpr uint32_t ComponentsVersion = 2; ///< a file of a set of components
  static constexpr int MaxComponents = 4;
  static constexpr size_t HeaderSize = 256;
  static constexpr size_t EntrySize = 40;
  static constexpr int MaxDimension = 1 << 20;
  static constexpr int MinPageSize = 8;
  static constexpr int MaxPageSize = 512;
  /// Largest raw page accepted (tile pools with many layers): 1 GiB.
  static constexpr uint64_t MaxPageBytes = uint64_t(1) << 30;

  enum class Kind : uint32_t
  {
    BrickPool = 0,
    TilePool = 1
  };
  enum class ScalarType : uint32_t
  {
    UInt8 = 0,
    UInt16 = 1,
    Int16 = 2,
    Float32 = 3
  };
  enum class Compression : uint32_t
  {
    None = 0,
    Zstd = 1
  };
  enum class Encoding : uint32_t
  {
    Raw = 0,
    Zstd = 1
  };

  struct Header
  {
    uint32_t Version = PagePoolFormat::Version;
    Kind PoolKind = Kind::BrickPool;
    ScalarType Type = ScalarType::UInt8;
    int Dimensions[3] = { 1, 1, 1 };
    int PageSize = 32;
    int NumberOfLevels = 0;
    Compression PageCompression = Compression::None;
    uint64_t NumberOfPages = 0;
    uint64_t TableOffset = HeaderSize;
    uint64_t DataOffset = 0;
    uint64_t FileSize = 0;
    double Spacing[3] = { 1, 1, 1 };
    double Origin[3] = { 0, 0, 0 };
    double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    double ValueRange[2] = { 0, 0 };
    double NoDataValue = 0;
    bool HasNoDataValue = false;
    uint32_t TableChecksum = 0;
    int Components = 1; ///< the set's (version 2 when > 1)
    int Component = 0;  ///< this file's
    uint32_t ComponentsTag = 0;
  };

  struct PageEntry
  {
    uint32_t Level = 0;
    uint32_t Index = 0;
    uint64_t Offset = 0;
    uint64_t StoredSize = 0;
    float Min = 0;
    float Max = 0;
    uint32_t Checksum = 0;
    Encoding PageEncoding = Encoding::Raw;
  };

  /// Level geometry implied by kind, dims and page size: points and pages per axis.
  struct Level
  {
    int Dimensions[3];
    int Pages[3];
    uint64_t FirstPage; ///< page number of the level's first page
  };

  /// Bytes per value of a scalar type (0 for an unknown one).
  static int GetScalarSize(ScalarType type);
  static const char* GetScalarTypeName(ScalarType type);

  /**
   * Levels of a pool, finest first, as strata::VolumeBrickTree builds them. Returns false (with
   * `error`) on dimensions or a page size outside the limits above.
   */
  static bool ComputeLevels(Kind kind,
    const int dims[3],
    int pageSize,
    std::vector<Level>& levels,
    std::string& error);
  /// Values per page: B^3 for bricks, B^2 * layers for tiles.
  static uint64_t GetPageValues(Kind kind, const int dims[3], int pageSize);
  /// Total page count of a level list.
  static uint64_t GetNumberOfPages(const std::vector<Level>& levels);

  /// The file of component `c` of the set whose component 0 is `name` (see the class doc).
  static std::string GetComponentFileName(const std::string& name, int c);
  /**
   * Whether `other` is component `c` of the set `first` (component 0) heads: the same number
   * of components and tag, kind, scalar type, dimensions, page size, levels and geometry.
   * False with `error` naming what differs.
   */
  static bool CheckComponent(const Header& first, const Header& other, int c, std::string& error);

  /// CRC-32 (IEEE), continuing from `crc` (start with 0).
  static uint32_t Crc32(const void* data, size_t size, uint32_t crc = 0);

  ///@{
  /**
   * Fixed-size little-endian encodings. EncodeHeader fills HeaderSize bytes and computes the
   * header CRC; DecodeHeader reads them without validating (see ValidateHeader).
   */
  static void EncodeHeader(const Header& header, unsigned char out[HeaderSize]);
  static void DecodeHeader(const unsigned char in[HeaderSize], Header& header);
  static void EncodeEntry(const PageEntry& entry, unsigned char out[EntrySize]);
  static void DecodeEntry(const unsigned char in[EntrySize], PageEntry& entry);
  ///@}

  /**
   * Checks raw header bytes: magic, version, header checksum, then every field (see
   * ValidateHeader). `fileSize` is the actual size of the file.
   */
  static bool ValidateHeaderBytes(const unsigned char in[HeaderSize],
    uint64_t fileSize,
    Header& header,
    std::string& error);
  /**
   * Checks a decoded header for absurd or inconsistent values: kind and scalar type known,
   * dims in [1, 2^20], page size in [8, 512], level and page counts equal to those implied by
   * dims, offsets consistent, file size equal to `fileSize` (truncation), finite geometry.
   */
  static bool ValidateHeader(const Header& header, uint64_t fileSize, std::string& error);
  /**
   * Checks a decoded page table against its header: numbering, offsets and sizes inside the
   * data area, raw pages of the raw size, known encodings.
   */
  static bool ValidateTable(const Header& header,
    const std::vector<PageEntry>& table,
    std::string& error);
};
}

#endif
