// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::MinMaxQuadtree
 * @brief   Global min-max quadtree over tiles of a height-field stack, with sorted interval lists.
 *
 * The two-level acceleration structure of Lux and Froehlich (stacked height-field ray casting,
 * section 4, Fig. 4). Level 0 holds tiles of TileSize x TileSize cells; each coarser level
 * merges 2 x 2 nodes until one node covers the grid. Every node stores the union [min, max] of
 * the heights of all layers inside it (empty-space skipping) and a sorted list of disjoint
 * depth intervals, each naming the layers whose range covers it. A ray that reaches a node
 * walks that list front-to-back or back-to-front by the sign of its vertical direction and
 * stops at the first interval that yields a hit: intervals are disjoint, so nothing in a later
 * one can be nearer.
 *
 * Tile (a, b) of level l covers grid x in [a S, (a+1) S] and y in [b S, (b+1) S] with
 * S = TileSize * 2^l, clipped to the grid; its boundary points are shared with neighbours, so
 * the bilinear surface inside a tile lies within the min/max of the tile's points. Every
 * interval list is built (not only the leaves'): under paging, any node of a cut can be a leaf.
 *
 * Plain C++: the mapper serialises it into buffer textures, tests inspect it directly.
 */
#ifndef StrataMinMaxQuadtree_h
#define StrataMinMaxQuadtree_h

#include "StrataCoreModule.h" // For export macro

#include <array>   // For std::array
#include <cstddef> // For size_t
#include <vector>  // For std::vector

namespace strata
{
class HeightFieldStack;
}

namespace strata
{
class STRATACORE_EXPORT MinMaxQuadtree
{
public:
  struct Node
  {
    float Min;          ///< lowest valid height in the node (Min > Max when empty)
    float Max;          ///< highest valid height in the node
    int IntervalOffset; ///< first interval of this node in GetIntervals()
    int IntervalCount;  ///< number of intervals, sorted by increasing z
  };
  struct Interval
  {
    float ZMin;
    float ZMax;
    int LayerOffset; ///< first layer id of this interval in GetLayerLists()
    int LayerCount;
  };

  /**
   * Builds the tree for `stack` with tiles of tileSize x tileSize cells (tileSize >= 1).
   */
  void Build(const strata::HeightFieldStack& stack, int tileSize);

  /**
   * Builds the tree from given leaf ranges instead of heights: `leafMin`/`leafMax` hold, per
   * level-0 tile (x fastest, GetLeafCount() of them) and layer (layer fastest within a tile),
   * a bound of that layer's heights over the tile (min > max: no data there). A paging
   * renderer passes the ranges of the data it actually samples under the current cut, so
   * coarse pages get coarse but valid bounds; ranges computed from full-resolution heights
   * give exactly the tree Build() makes.
   */
  void BuildFromLeafRanges(int nx,
    int ny,
    int layers,
    int tileSize,
    const std::vector<float>& leafMin,
    const std::vector<float>& leafMax);

  /// Level-0 tiles (leaves) in x and y of a grid of nx x ny points with the given tile size.
  static std::array<int, 2> GetLeafCount(int nx, int ny, int tileSize);

  int GetTileSize() const { return this->TileSize; }
  int GetNumberOfLevels() const { return static_cast<int>(this->LevelDims.size()); }
  /// Nodes of level l in x and y; level 0 are the tiles, the last level is the single root.
  int GetLevelNX(int l) const { return this->LevelDims[l][0]; }
  int GetLevelNY(int l) const { return this->LevelDims[l][1]; }
  /// Index of the first node of level l in GetNodes(); nodes of a level go x fastest.
  int GetLevelOffset(int l) const { return this->LevelOffsets[l]; }
  const Node& GetNode(int l, int a, int b) const
  {
    return this->Nodes[this->LevelOffsets[l] + b * this->LevelDims[l][0] + a];
  }
  const std::vector<Node>& GetNodes() const { return this->Nodes; }
  const std::vector<Interval>& GetIntervals() const { return this->Intervals; }
  const std::vector<int>& GetLayerLists() const { return this->LayerLists; }
  /// Bytes the serialised tree occupies on the GPU.
  size_t GetMemorySize() const;

private:
  void BuildLevels(int nx, int ny, int tileSize);
  void BuildUpperLevels(int layers, std::vector<float>& lmin, std::vector<float>& lmax);
  void BuildIntervals(const std::vector<float>& layerMin,
    const std::vector<float>& layerMax,
    int layers,
    Node& node);

  int TileSize = 0;
  std::vector<std::array<int, 2>> LevelDims;
  std::vector<int> LevelOffsets;
  std::vector<Node> Nodes;
  std::vector<Interval> Intervals;
  std::vector<int> LayerLists;
};
}

#endif
