// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::VolumeSkipGrid
 * @brief   Empty-space skipping finer than a brick: per-cell value ranges and, for the current
 *          transfer function, the Chebyshev distance of every cell to the nearest visible one.
 *
 * Bricks of 32^3 voxels are too coarse to skip the air inside a sparse volume (a tree, a
 * skull): most bricks hold a few visible voxels. This grid cuts the volume into cells of
 * CellSize voxels per axis. Cell c covers index coordinates [c C, (c + 1) C] per axis, and its
 * range is the min/max of the voxels c C .. (c + 1) C inclusive (clamped), which are all the
 * voxels trilinear or nearest interpolation reads for a sample inside the cell. Classify()
 * marks a cell visible when the opacity function's maximum over its range is positive, then
 * computes the chessboard distance D (in cells, capped at 255) from each cell to the nearest
 * visible cell. A ray at a cell with D > 0 may jump to where it leaves the box of cells
 * c - (D - 1) .. c + (D - 1) (all invisible): the jump is a single texel fetch, however far.
 *
 * Plain C++: the mapper uploads GetDistances() as an R8UI 3-D texture, tests inspect it.
 */
#ifndef StrataVolumeSkipGrid_h
#define StrataVolumeSkipGrid_h

#include "StrataCoreModule.h" // For export macro

#include <cstdint>    // For uint8_t
#include <functional> // For std::function
#include <vector>     // For std::vector

namespace strata
{
class STRATACORE_EXPORT VolumeSkipGrid
{
public:
  /// Maximum opacity of the transfer function over scalars [lo, hi].
  using OpacityRange = std::function<double(double lo, double hi)>;

  /**
   * Per-cell ranges of `scalars` (dims[0] * dims[1] * dims[2] floats, x fastest) for cells of
   * cellSize voxels (>= 1). NaN voxels are ignored; a cell of only NaN is invisible.
   */
  void Build(const float* scalars, const int dims[3], int cellSize);

  /**
   * Cells given by their ranges (cellDims cells of cellSize voxels, x fastest), for data that
   * is not in memory: a page pool's level-0 bricks of stride cellSize are exactly such cells.
   */
  void BuildFromRanges(const int cellDims[3],
    int cellSize,
    const float* minima,
    const float* maxima);

  /// Visibility and distances for this opacity function. Returns the number of visible cells.
  long long Classify(const OpacityRange& opacity);

  int GetCellSize() const { return this->CellSize; }
  /// Cells per axis: ceil((n - 1) / C), at least 1.
  const int* GetCellDimensions() const { return this->CellDims; }
  /// Min and max of cell (i, j, k), x fastest.
  const std::vector<float>& GetMinima() const { return this->Min; }
  const std::vector<float>& GetMaxima() const { return this->Max; }
  /// Chebyshev distance in cells to the nearest visible cell, 0 for visible ones, 255 at most
  /// (also when no cell is visible).
  const std::vector<uint8_t>& GetDistances() const { return this->Distance; }

private:
  int CellSize = 8;
  int CellDims[3] = { 0, 0, 0 };
  std::vector<float> Min;
  std::vector<float> Max;
  std::vector<uint8_t> Distance;
};
}

#endif
