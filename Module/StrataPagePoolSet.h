// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::PagePoolSet
 * @brief   One page pool as a set of files (a file per component), opened once per process,
 *          and the image of a level-0 extent at any level, read page by page.
 *
 * What the pool reader (IO) and the picker (Rendering) both need, so that neither module
 * depends on the other: the files come from strata::PagePoolFile::OpenShared, so a reader, the
 * pagers of the mappers and the picker hold one descriptor and one page table per file.
 *
 * Geometry of a coarse level. Level l has n_l points per axis (n -> n/2 + 1 per level). Its
 * image keeps the origin and the direction, and its spacing is s * (n_0 - 1) / (n_l - 1) per
 * axis (s when n_l = 1), so that the coarse image covers exactly the physical region of the
 * full one. A level-0 extent [a, b] maps to the smallest level-l extent covering it:
 * [floor(a / r), ceil(b / r)] with r = (n_0 - 1) / (n_l - 1).
 *
 * @sa strata::PagePoolFile strata::PagePoolFormat vtkPagePoolProtocol
 */
#ifndef StrataPagePoolSet_h
#define StrataPagePoolSet_h

#include "StrataCoreModule.h" // For export macro
#include "vtkSmartPointer.h"  // For the image returned

#include <functional> // For std::function
#include <memory>     // For std::shared_ptr
#include <string>     // For std::string
#include <vector>     // For std::vector

class vtkImageData;
namespace strata
{
class PagePoolFile;
}

namespace strata
{
class STRATACORE_EXPORT PagePoolSet
{
public:
  /**
   * Opens the set whose component 0 is `name` (one file for a pool of one component). False,
   * with `error`, when a file is missing or foreign, or `name` is another component's file.
   */
  bool Open(const std::string& name, std::string& error);
  void Close() { this->Files.clear(); }
  bool IsOpen() const { return !this->Files.empty(); }
  int GetNumberOfComponents() const { return static_cast<int>(this->Files.size()); }
  const strata::PagePoolFile& GetFile(int component = 0) const { return *this->Files[component]; }
  /// Whether this is a tile pool (nx x ny tiles of L layers) rather than a brick pool.
  bool IsTilePool() const;
  /// The VTK scalar type of the values.
  int GetVTKScalarType() const;

  /**
   * The level-`level` extent covering the level-0 `updateExtent` (clamped to the pool), and
   * the level's spacing. False when the clamped request is empty.
   */
  bool LevelExtent(int level, const int updateExtent[6], int extent[6], double spacing[3]) const;

  /// What ReadImage reports and accepts.
  struct Read
  {
    double MemoryLimitMB = 0.0;           ///< the most the image may take; 0: no limit
    std::string LimitName = "limit";      ///< how the error names the limit
    std::string LimitAdvice;              ///< what the error adds after the limit
    int Layer = 0;                        ///< the layer of a tile pool
    std::string ArrayName;                ///< the scalars' name
    long long PagesRead = 0;              ///< out: pages read (a page per component)
    std::function<void(double)> Progress; ///< called with the fraction read, if set
  };
  /**
   * The image of level `level` over the level-0 `updateExtent`: extent, spacing, the pool's
   * origin and direction, scalars in the pool's type (components interleaved). An empty
   * image for an empty request. Null, with `error`, when the image would pass the memory
   * limit (checked before anything is allocated), the layer is out of range, or a page
   * cannot be read.
   */
  vtkSmartPointer<vtkImageData> ReadImage(int level,
    const int updateExtent[6],
    Read& read,
    std::string& error) const;
  /// As ReadImage, for `extent` given in level `level`'s own indices (clamped to the level).
  vtkSmartPointer<vtkImageData> ReadLevelImage(int level,
    const int extent[6],
    Read& read,
    std::string& error) const;
  /// Level `level`'s whole extent (a tile pool's: one layer) and spacing.
  void GetLevelGeometry(int level, int extent[6], double spacing[3]) const;
  /**
   * The level-0 extent under level `level`'s `extent` (its own indices): the level-0 points
   * from the first to the last one it covers, widened to whole points.
   */
  void LevelToFinest(int level, const int extent[6], int finest[6]) const;

private:
  bool ReadPages(int level, const int extent[6], Read& read, void* dst, std::string& error) const;

  std::vector<std::shared_ptr<strata::PagePoolFile>> Files;
};
}

#endif
