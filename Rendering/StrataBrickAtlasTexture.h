// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::BrickAtlasTexture
 * @brief   The GPU side of the multi-volume brick atlas: the shared 3-D atlas texture, one
 *          index texture per volume, and the GLSL lookup that reads them.
 *
 * strata::VolumePager decides which brick lives in which slot (strata::BrickAtlasAllocator) and
 * writes each volume's index table; this object holds the textures: the atlas (R8, R16 or R32F by
 * strata::BrickAtlasFormat, linear, bricks of B^3 voxels sharing one voxel layer at their faces, so
 * trilinear lookups are exact inside a brick) and the index textures. The pager's table
 * (slot x, y, z and the level of the cut node covering each level-0 brick,
 * strata::VolumeCut::EmptyLevel and MissingLevel for transparent and slotless bricks) is stored
 * resolved, as RGBA32F: the atlas texel of the brick's index-space origin (xyz) and the
 * node's scale 2^-level (w; -1 transparent, -2 slotless), so that a sample costs one nearest
 * fetch and one multiply-add before the atlas lookup. Following Tuvok's rule, the object that
 * owns the page table writes the code that reads it: GetLookupFunction() is the only GLSL that
 * knows where voxels live.
 *
 * The owner calls ReleaseGraphicsResources() from its own, with the context current.
 */
#ifndef StrataBrickAtlasTexture_h
#define StrataBrickAtlasTexture_h

#include "StrataGLObject.h"        // For strata::GLObject
#include "StrataRenderingModule.h" // For export macro
#include "StrataVolumeBrickTree.h" // For strata::VolumeBrickTree::ScalarType

#include <array>   // For std::array
#include <cstdint> // For uint16_t
#include <map>     // For std::map
#include <string>  // For std::string
#include <vector>  // For std::vector

namespace strata
{
class STRATARENDERING_EXPORT BrickAtlasTexture
{
public:
  /// The atlas's uniforms (uAtlas, uAtlasSize in texels, uBrickSize), declared once.
  static std::string GetShaderDeclarations();
  /**
   * `float strataScalarAt<n>(vec3 idx)`: volume n's scalar at index coordinates through its
   * index texture uIndex<n> (level-0 bricks uTableDims<n>) and the atlas; `feedbackCheck` is
   * inserted where the level-0 brick b and `coarse`, 2^level of the node covering it, are known
   * (empty: none, and neither is computed). `normalized`: the atlas's texels are decoded,
   * value = t uDecode<n>.x + uDecode<n>.y (strata::BrickAtlasFormat::GetDecode).
   */
  static std::string GetLookupFunction(int n, const std::string& feedbackCheck, bool normalized);
  /// The same for the volume named `n` (component c > 0 of volume v is "<v>c<c>").
  static std::string GetLookupFunction(const std::string& n,
    const std::string& feedbackCheck,
    bool normalized);

  BrickAtlasTexture() = default;
  BrickAtlasTexture(const BrickAtlasTexture&) = delete;
  BrickAtlasTexture& operator=(const BrickAtlasTexture&) = delete;

  /// (Re)defines the atlas texture of `size` texels of `type`, contents undefined.
  void Allocate(const std::array<int, 3>& size, strata::VolumeBrickTree::ScalarType type);
  bool IsAllocated() const { return static_cast<bool>(this->Atlas); }
  const std::array<int, 3>& GetSize() const { return this->Size; }

  /// Writes bricks of B^3 texels of the atlas's type (strata::BrickAtlasFormat::Encode) into the
  /// atlas, at slot positions (in bricks).
  void BeginUploads();
  void UploadBrick(const std::array<int, 3>& slot, int brickSize, const void* texels);
  void EndUploads();

  /**
   * Defines the index texture of `key` (the volume's input port) from the pager's table of
   * `bricks` level-0 bricks of `brickSize` voxels (strata::VolumePager::BuildIndexTable), resolved
   * against this atlas's size (Allocate first).
   */
  void SetIndex(int key, const int bricks[3], int brickSize, const std::vector<uint16_t>& table);

  unsigned int GetAtlasName() const { return this->Atlas.GetName(); }
  unsigned int GetIndexName(int key) const;

  void ReleaseGraphicsResources();

private:
  strata::GLObject Atlas{ strata::GLObject::Kinds::Texture };
  std::array<int, 3> Size = { 0, 0, 0 };
  strata::VolumeBrickTree::ScalarType Type = strata::VolumeBrickTree::ScalarType::Float32;
  std::map<int, strata::GLObject> Index;
  int SavedAlignment = 4; ///< GL_UNPACK_ALIGNMENT before BeginUploads, put back by EndUploads
};
}

#endif
