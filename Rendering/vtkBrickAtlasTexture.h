// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkBrickAtlasTexture
 * @brief   The GPU side of the multi-volume brick atlas: the shared 3-D atlas texture, one
 *          index texture per volume, and the GLSL lookup that reads them.
 *
 * vtkVolumePager decides which brick lives in which slot (vtkBrickAtlasAllocator) and writes
 * each volume's index table; this object holds the textures: the atlas (R32F, linear, bricks of
 * B^3 voxels sharing one voxel layer at their faces, so trilinear lookups are exact inside a
 * brick) and the index textures (RGBA16UI, one texel per level-0 brick: slot x, y, z and the
 * level of the cut node covering it, vtkVolumeCut::EmptyLevel and MissingLevel for transparent
 * and slotless bricks). Following Tuvok's rule, the object that owns the page table writes the
 * code that reads it: GetLookupFunction() is the only GLSL that knows where voxels live.
 *
 * The owner calls ReleaseGraphicsResources() from its own, with the context current.
 */
#ifndef vtkBrickAtlasTexture_h
#define vtkBrickAtlasTexture_h

#include "StrataRenderingModule.h" // For export macro
#include "vtkStrataGLObject.h"     // For vtkStrataGLObject

#include <array>   // For std::array
#include <cstdint> // For uint16_t
#include <map>     // For std::map
#include <string>  // For std::string
#include <vector>  // For std::vector

class STRATARENDERING_EXPORT vtkBrickAtlasTexture
{
public:
  /// The atlas's uniforms (uAtlas, uAtlasSize in texels, uBrickSize), declared once.
  static std::string GetShaderDeclarations();
  /**
   * `float strataScalarAt<n>(vec3 idx)`: volume n's scalar at index coordinates through its
   * index texture uIndex<n> (level-0 bricks uTableDims<n>) and the atlas; `feedbackCheck` is
   * inserted where the index entry e of level-0 brick b is known (empty: none).
   */
  static std::string GetLookupFunction(int n, const std::string& feedbackCheck);

  vtkBrickAtlasTexture() = default;
  vtkBrickAtlasTexture(const vtkBrickAtlasTexture&) = delete;
  vtkBrickAtlasTexture& operator=(const vtkBrickAtlasTexture&) = delete;

  /// (Re)defines the atlas texture of `size` texels, contents undefined.
  void Allocate(const std::array<int, 3>& size);
  bool IsAllocated() const { return static_cast<bool>(this->Atlas); }
  const std::array<int, 3>& GetSize() const { return this->Size; }

  /// Writes bricks of B^3 floats into the atlas, at slot positions (in bricks).
  void BeginUploads();
  void UploadBrick(const std::array<int, 3>& slot, int brickSize, const float* values);
  void EndUploads();

  /// Defines the index texture of `key` (the volume's input port) from its table.
  void SetIndex(int key, const int bricks[3], const std::vector<uint16_t>& table);

  unsigned int GetAtlasName() const { return this->Atlas.GetName(); }
  unsigned int GetIndexName(int key) const;

  void ReleaseGraphicsResources();

private:
  vtkStrataGLObject Atlas{ vtkStrataGLObject::Kinds::Texture };
  std::array<int, 3> Size = { 0, 0, 0 };
  std::map<int, vtkStrataGLObject> Index;
};

#endif
