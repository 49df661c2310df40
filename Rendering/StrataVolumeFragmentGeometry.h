// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::VolumeFragmentGeometry
 * @brief   The multi-volume ray caster's fragments: the BSP tree over the volumes' boxes and
 *          the faces of its convex fragments on the GPU.
 *
 * The volumes' boxes (index range [0, n-1] per axis, or one spacing thick for n == 1, placed
 * by each volume's index-to-world matrix) go into a strata::VolumeBSPTree, rebuilt only when a box
 * moves. The faces of all fragments are kept in one vertex buffer of outward triangles in the
 * tree's local frame (world minus a double-precision origin near the data), with, per
 * fragment, its first vertex and count, its centroid (for the outline dilation of several
 * rays per pixel) and its planes (the shader clips each ray to them).
 *
 * The owner calls ReleaseGraphicsResources() from its own, with the context current.
 */
#ifndef StrataVolumeFragmentGeometry_h
#define StrataVolumeFragmentGeometry_h

#include "StrataGLObject.h"        // For strata::GLObject
#include "StrataRenderingModule.h" // For export macro
#include "StrataVolumeBSPTree.h"   // For strata::VolumeBSPTree

#include <array>  // For std::array
#include <vector> // For std::vector

class vtkMatrix4x4;
class vtkShaderProgram;

namespace strata
{
class STRATARENDERING_EXPORT VolumeFragmentGeometry
{
public:
  /**
   * Sets the box of each volume from its index-to-world matrix and dimensions, rebuilds the
   * tree if a box changed and uploads the fragments' faces if they changed.
   */
  void Update(const std::vector<vtkMatrix4x4*>& indexToWorld, const std::vector<const int*>& dims);

  const strata::VolumeBSPTree& GetTree() const { return this->Tree; }
  const strata::VolumeBSPTree::Vector3& GetOrigin() const { return this->Tree.GetOrigin(); }

  /// Fragment f's draw: its vertices, centroid and planes (4 floats each, local frame).
  int GetVertexCount(int f) const { return this->Count[f]; }
  const std::array<float, 3>& GetCentroid(int f) const { return this->Centroid[f]; }
  const std::vector<float>& GetPlanes(int f) const { return this->Planes[f]; }

  /// Binds the vertex array, its attribute set up for `program` (attribute vertexLocal).
  void Bind(vtkShaderProgram* program);
  /// Draws fragment f's faces (the vertex array bound).
  void Draw(int f) const;
  void Unbind() const;

  void ReleaseGraphicsResources();

private:
  void Upload();

  strata::VolumeBSPTree Tree;
  bool Valid = false; ///< the vertex buffer holds the tree's fragments
  strata::GLObject Vertices{ strata::GLObject::Kinds::Buffer };
  strata::GLObject VertexArray{ strata::GLObject::Kinds::VertexArray };
  vtkShaderProgram* ArrayProgram = nullptr; ///< the program the attribute was set up for
  std::vector<int> First, Count;
  std::vector<std::array<float, 3>> Centroid;
  std::vector<std::vector<float>> Planes;
};
}

#endif
