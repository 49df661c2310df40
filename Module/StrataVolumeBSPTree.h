// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::VolumeBSPTree
 * @brief   Solid-leaf BSP tree that cuts overlapping oriented volume boxes into convex fragments,
 *          each covered by a fixed set of volumes, and sorts them front to back.
 *
 * The volume decomposition of Lux and Froehlich (GPU-based ray casting of multiple
 * multi-resolution volume datasets, section 3.4, Fig. 5). Only the bounding boxes of the volumes
 * enter the tree, so it is rebuilt only when a volume moves, never when the view or the resident
 * bricks change. The tree is auto-partitioning: every split plane is a face plane of a box. A
 * cell is split until every box either contains it or misses it; each leaf is then a convex
 * fragment covered by a fixed set of volumes, which a ray caster casts in one pass with a shader
 * instantiated for that many volumes. Leaves covered by no box are dropped (solid-leaf tree).
 * Visiting the eye's side of every split plane first lists the fragments front to back, for any
 * perspective or parallel view, without sorting.
 *
 * Split choice, deterministic: among the face planes that cut the current cell, the one that cuts
 * the fewest other boxes inside the cell; ties go to planes with nothing outside them (they trim
 * empty space for free), then to input order. This reaches the minimal fragment counts of simple
 * configurations: 7 for two boxes overlapping at a corner or one box inside another, 2k - 1 for k
 * boxes in a row each overlapping the next, 1 for coincident boxes.
 *
 * Geometry is kept relative to a local origin (the centre of the first box) so UTM-sized
 * coordinates keep their precision: fragment planes and vertices are local, add GetOrigin() for
 * world coordinates. Distances below the tolerance (RelativeTolerance times the diagonal of the
 * boxes' bounding box) count as zero: coplanar or nearly coplanar faces create no slivers, and a
 * plane leaving less than that on one side of a cell does not split it.
 *
 * Plain C++: the multi-volume mapper draws the fragments, tests inspect them directly.
 *
 * @sa strata::MinMaxQuadtree
 */
#ifndef StrataVolumeBSPTree_h
#define StrataVolumeBSPTree_h

#include "StrataCoreModule.h" // For export macro

#include <array>  // For std::array
#include <vector> // For std::vector

namespace strata
{
class STRATACORE_EXPORT VolumeBSPTree
{
public:
  using Vector3 = std::array<double, 3>;
  /// Plane (nx, ny, nz, d) with unit outward normal: n.x + d <= 0 inside.
  using Plane = std::array<double, 4>;

  struct Box
  {
    /// Row-major 4x4 matrix mapping the unit cube [0,1]^3 to world coordinates (any rotation,
    /// non-uniform scale, shear, mirroring and translation; the last row is taken as 0 0 0 1).
    std::array<double, 16> Matrix;
    int VolumeId;
    bool operator==(const Box& other) const
    {
      return this->Matrix == other.Matrix && this->VolumeId == other.VolumeId;
    }
    bool operator!=(const Box& other) const { return !(*this == other); }
  };

  /// A convex leaf cell covered by a fixed set of boxes. Coordinates are local (see GetOrigin()).
  struct Fragment
  {
    std::vector<int> VolumeIds;  ///< ids of the covering boxes, ascending
    std::vector<int> BoxIndices; ///< the same boxes as indices into GetBoxes(), same order
    std::vector<Plane> Planes;   ///< one per face, outward
    std::vector<Vector3> Vertices;
    std::vector<std::vector<int>> Faces; ///< counter-clockwise seen from outside, one per plane
    std::vector<int> Triangles;          ///< fan triangulation of Faces, 3 indices each, outward
    double Volume = 0.0;
  };

  /// Inner node (Fragment < 0) with a split plane, or leaf (Fragment >= 0).
  struct Node
  {
    Plane Split;      ///< local coordinates
    int Inside = -1;  ///< child on the n.x + d <= 0 side; -1: empty space
    int Outside = -1; ///< child on the other side; -1: empty space
    int Fragment = -1;
  };

  /**
   * Sets the boxes; returns true (and marks the tree for rebuilding) only when they differ from
   * the current ones, so a caller can pass its volumes every frame and rebuild on change. Boxes
   * thinner than the tolerance in some direction cover no volume and are ignored.
   */
  bool SetBoxes(const std::vector<Box>& boxes);
  const std::vector<Box>& GetBoxes() const { return this->Boxes; }

  ///@{
  /// Distances below RelativeTolerance times the diagonal of the boxes' bounding box count as zero.
  /// Default 1e-7: double rounding of UTM coordinates (about 1e-9 m at 7e6 m) stays two orders
  /// below it for scenes of 1 m and more, and 1e-7 of a scene (1 mm in 10 km) is below any pixel.
  void SetRelativeTolerance(double tolerance);
  double GetRelativeTolerance() const { return this->RelativeTolerance; }
  ///@}
  /// Absolute tolerance of the last Build(), in world units.
  double GetTolerance() const { return this->Tolerance; }

  /// Builds the tree from the current boxes (always; see Update()).
  void Build();
  /// Builds the tree if the boxes or the tolerance changed since the last build; returns whether
  /// it did.
  bool Update();
  bool GetNeedsBuild() const { return this->NeedsBuild; }

  /// World position of the local origin of planes and vertices (centre of the first box).
  const Vector3& GetOrigin() const { return this->Origin; }

  int GetNumberOfFragments() const { return static_cast<int>(this->Fragments.size()); }
  const Fragment& GetFragment(int i) const { return this->Fragments[i]; }
  const std::vector<Fragment>& GetFragments() const { return this->Fragments; }
  /// Largest number of volumes covering one fragment (shader instances needed: 1 to this).
  int GetMaximumOverlap() const;

  const std::vector<Node>& GetNodes() const { return this->Nodes; }
  /// Root node index, -1 when no box covers any volume.
  int GetRoot() const { return this->Root; }
  /// Depth of the deepest leaf (root alone: 0).
  int GetDepth() const { return this->Depth; }

  /// Fragment containing a world point by descending the tree; -1 outside all boxes. Points on
  /// a face go to the inside of its plane.
  int FindFragment(const Vector3& worldPoint) const;
  /// Whether a world point lies in fragment i (on the inside of all its planes, boundary included).
  bool FragmentContainsPoint(int i, const Vector3& worldPoint) const;

  /**
   * Fragment indices in the order rays meet them. Perspective: rays start at `eye` (world).
   * Parallel: rays travel along `direction` and `eye` is ignored. Fragments on the far side of
   * every plane are never in front of nearer ones, so compositing in this order is exact.
   */
  void SortFrontToBack(const Vector3& eye,
    bool parallel,
    const Vector3& direction,
    std::vector<int>& order) const;
  /// The reverse of SortFrontToBack(), for back-to-front compositing.
  void SortBackToFront(const Vector3& eye,
    bool parallel,
    const Vector3& direction,
    std::vector<int>& order) const;

private:
  void Collect(int node,
    const Vector3& localEye,
    bool parallel,
    const Vector3& direction,
    std::vector<int>& order) const;

  std::vector<Box> Boxes;
  double RelativeTolerance = 1e-7;
  double Tolerance = 0.0;
  bool NeedsBuild = true;
  Vector3 Origin = { { 0.0, 0.0, 0.0 } };
  std::vector<Node> Nodes;
  std::vector<Fragment> Fragments;
  int Root = -1;
  int Depth = 0;
};
}

#endif
