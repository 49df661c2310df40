// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::VolumeBrickTree
 * @brief   Multi-resolution octree of fixed-size bricks over one scalar volume.
 *
 * The volume representation of Lux and Froehlich (multi-volume multi-resolution ray casting,
 * section 3.1): every level is cut into bricks of B^3 voxels, the unit of paging and of the
 * atlas texture, so bricks of any level are interchangeable in memory. Neighbouring bricks
 * share one voxel layer (brick stride S = B - 1): trilinear interpolation anywhere inside a
 * brick reads only that brick, so the ray caster never needs a neighbour. Voxels beyond the
 * level are clamped copies of its last layer.
 *
 * Index space is VTK's: point (voxel) v of level 0 sits at index coordinate v, the volume
 * spans [0, n-1] per axis. Level l+1 keeps every second point of level l, at level-l index
 * 2v, valued by the [1 2 1]/4 filter per axis: the average of the trilinear field over the
 * coarse voxel's footprint [2v-1, 2v+1] (a box filter of the reconstructed field), clamped at
 * the border. A level of n > 1 points has n/2 + 1 (integer division); 1 stays 1. Keeping
 * points on even positions, rather than averaging pairs (which moves them half a voxel),
 * nests the bricks exactly: brick (l, I) covers level-0 index [I S 2^l, (I+1) S 2^l] per
 * axis, precisely the union of its children, so one index-table fetch per sample is exact
 * and coarse bricks show no seams against fine ones.
 *
 * Levels stop at the first that fits one brick (the root). A node is (level, i, j, k); its
 * children are the up to 8 bricks (2i + a, 2j + b, 2k + c) of level l-1. Each node stores the
 * range of its own voxels (shared layer and clamped padding included) and the range of its
 * whole subtree: a node may be skipped as empty only when nothing below it is visible either.
 *
 * Level 0 is borrowed from the caller (it must outlive the tree); coarser levels are owned,
 * in the input type, at about 1/7 of the input size. Plain C++: no VTK data types.
 *
 * @sa strata::BrickAtlasAllocator strata::VolumeCut
 */
#ifndef StrataVolumeBrickTree_h
#define StrataVolumeBrickTree_h

#include "StrataCoreModule.h" // For export macro

#include <cstddef> // For size_t
#include <cstdint> // For fixed-width scalar types
#include <string>  // For std::string
#include <vector>  // For std::vector

namespace strata
{
class STRATACORE_EXPORT VolumeBrickTree
{
public:
  enum class ScalarType
  {
    UInt8,
    UInt16,
    Int16,
    Float32
  };
  /// Bytes per voxel of a scalar type.
  static int GetScalarSize(ScalarType type);

  /**
   * One axis of the [1 2 1] filter every coarse level is built with (here and in
   * strata::PagePoolWriter): the weighted sum of row[2v - 1], row[2v], row[2v + 1] (clamped to the
   * row's n values) over the taps that hold data (`skip(value)` false), their weight in
   * `weight`. Holes take no part, so a coarse value is a hole only where every tap is.
   */
  template<typename T, typename Skip>
  static double FilterTaps(const T* row, int v, int n, Skip skip, double& weight)
  {
    double sum = 0.0;
    weight = 0.0;
    for (int d = -1; d <= 1; ++d)
    {
      const int i = 2 * v + d < 0 ? 0 : (2 * v + d > n - 1 ? n - 1 : 2 * v + d);
      if (!skip(row[i]))
      {
        const double w = d == 0 ? 2.0 : 1.0;
        sum += w * static_cast<double>(row[i]);
        weight += w;
      }
    }
    return sum;
  }

  struct Node
  {
    int Level;
    int Index[3]; ///< brick position in its level
    float Min;    ///< range of the brick's own B^3 voxels (NaN ignored; Min > Max if all NaN)
    float Max;
    float SubtreeMin; ///< range of this brick and every descendant
    float SubtreeMax;
  };

  ///@{
  /**
   * Builds the tree over nx*ny*nz scalars, x fastest, with bricks of brickSize^3 voxels
   * (brickSize >= 2). The scalars are borrowed. Returns false, with GetErrorMessage() saying
   * why, on a null pointer, empty or absurd dimensions or a brick size below 2.
   */
  bool Build(const void* scalars, ScalarType type, const int dims[3], int brickSize);
  bool Build(const uint8_t* scalars, const int dims[3], int brickSize);
  bool Build(const uint16_t* scalars, const int dims[3], int brickSize);
  bool Build(const int16_t* scalars, const int dims[3], int brickSize);
  bool Build(const float* scalars, const int dims[3], int brickSize);
  ///@}

  /**
   * The structure alone, for a volume that stays on disk (a page pool, whose pages are this
   * tree's bricks in node order): levels, nodes and ranges from `minima`/`maxima` per node
   * id, no voxels; `type`, that of its voxels on disk (GetScalarType). GetLevelData, GetVoxel
   * and ExtractBrick must not be called on it.
   */
  bool BuildStructure(const int dims[3],
    int brickSize,
    const float* minima,
    const float* maxima,
    ScalarType type = ScalarType::Float32);
  /// False for a structure-only tree.
  bool HasData() const { return this->Input != nullptr; }

  ScalarType GetScalarType() const { return this->Type; }
  int GetBrickSize() const { return this->BrickSize; }
  /// Distance between the first voxels of neighbouring bricks: brick size - 1.
  int GetBrickStride() const { return this->BrickSize - 1; }
  int GetNumberOfLevels() const { return static_cast<int>(this->Levels.size()); }
  /// Points of level l per axis.
  const int* GetLevelDimensions(int l) const { return this->Levels[l].Dims; }
  /// Bricks of level l per axis.
  const int* GetLevelBricks(int l) const { return this->Levels[l].Bricks; }
  /// Voxels of level l, x fastest, in GetScalarType().
  const void* GetLevelData(int l) const;
  /// Value of voxel (i, j, k) of level l; indices are clamped to the level.
  double GetVoxel(int l, int i, int j, int k) const;

  ///@{
  /**
   * Nodes are numbered level by level from level 0; within a level x fastest. The root is the
   * last node. The brick index within its level, GetNodeId(...) - GetLevelOffset(l), is what
   * keys it in the atlas.
   */
  int GetNumberOfNodes() const { return static_cast<int>(this->Nodes.size()); }
  int GetLevelOffset(int l) const { return this->Levels[l].Offset; }
  int GetNodeId(int l, int i, int j, int k) const
  {
    const int* b = this->Levels[l].Bricks;
    return this->Levels[l].Offset + (k * b[1] + j) * b[0] + i;
  }
  int GetRootId() const { return static_cast<int>(this->Nodes.size()) - 1; }
  const Node& GetNode(int id) const { return this->Nodes[id]; }
  /// Parent node id, -1 for the root.
  int GetParent(int id) const;
  /// Writes the ids of the children (none for level 0, at most 8) and returns their number.
  int GetChildren(int id, int children[8]) const;
  ///@}

  /**
   * Level-0 index-space box the node stands for, clipped to the volume:
   * [I S 2^l, (I+1) S 2^l] per axis. Boxes of one level tile [0, n-1] and share faces.
   */
  void GetNodeBounds(int id, double bounds[6]) const;

  ///@{
  /**
   * Writes the node's B^3 voxels, x fastest, for upload into an atlas slot: as float, or in
   * the native type (B^3 * GetScalarSize() bytes).
   */
  void ExtractBrick(int id, float* out) const;
  void ExtractBrickNative(int id, void* out) const;
  ///@}

  /// Bytes owned by the tree (coarse levels and nodes; level 0 is borrowed).
  size_t GetMemorySize() const;
  const std::string& GetErrorMessage() const { return this->ErrorMessage; }

private:
  struct Level
  {
    int Dims[3];
    int Bricks[3];
    int Offset;
    std::vector<unsigned char> Storage; ///< empty for level 0, which is borrowed
  };

  bool BuildLevels(const int dims[3], int brickSize);
  template<typename T>
  void Downsample(int l);
  template<typename T>
  void ComputeRanges(int l);
  template<typename T, typename O>
  void Extract(int id, O* out) const;

  ScalarType Type = ScalarType::UInt8;
  const void* Input = nullptr;
  int BrickSize = 0;
  std::vector<Level> Levels;
  std::vector<Node> Nodes;
  std::string ErrorMessage;
};
}

#endif
