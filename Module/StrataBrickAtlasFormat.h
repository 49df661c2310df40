// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::BrickAtlasFormat
 * @brief   How bricks are stored in the atlas texture: the texel type a scene's volumes share,
 *          the encoding of each volume's values into it and the affine decode back.
 *
 * The lean atlas of issue 16: a brick costs B^3 texels of the atlas's type, not always B^3
 * floats, so one budget holds 4x (8-bit) or 2x (16-bit) the bricks. All volumes of a frame
 * share one atlas, so its texel type is the widest any of them needs and the storage allows
 * (Choose):
 * - UInt8 (GL R8, normalised): Native storage, every volume 8-bit unsigned;
 * - UInt16 (GL R16, normalised): every volume 8- or 16-bit (Normalized16, or Native with one
 *   16-bit volume); int16 values are stored offset by 32768, 8-bit ones times 257 (filling the
 *   16 bits: R16 filtered the 8-bit blob exactly here without it too, the factor is margin for
 *   filtering of 16-bit precision);
 * - Float32 (GL R32F): any float volume, or Float32 storage; values as they are.
 * The shader reads t in [0, 1] from a normalised texture and decodes value = t Scale + Offset
 * (GetDecode). Filtering is linear, so the decode commutes with the trilinear interpolation and
 * level 0 stays exact. Coarser levels of in-core volumes are float averages; their texels are
 * rounded to the nearest integer (as page pools store them), at most half a unit off.
 *
 * Plain C++ (no OpenGL): strata::VolumePager sizes the atlas with it and strata::BrickAtlasTexture
 * uploads what Encode wrote.
 *
 * @sa strata::BrickAtlasAllocator strata::VolumePager strata::BrickAtlasTexture
 */
#ifndef StrataBrickAtlasFormat_h
#define StrataBrickAtlasFormat_h

#include "StrataCoreModule.h"      // For export macro
#include "StrataVolumeBrickTree.h" // For strata::VolumeBrickTree::ScalarType

#include <cstddef> // For size_t
#include <vector>  // For std::vector

namespace strata
{
class STRATACORE_EXPORT BrickAtlasFormat
{
public:
  using ScalarType = strata::VolumeBrickTree::ScalarType;

  /// How 8- and 16-bit volumes are stored (float volumes always as Float32).
  enum class Storage
  {
    Float32,      ///< as float, 4 bytes a voxel
    Normalized16, ///< R16, 2 bytes a voxel (8-bit data too)
    Native        ///< R8 when every volume is 8-bit, else R16
  };

  /**
   * The texel type of an atlas holding volumes of `types` under `storage`: UInt8, UInt16 or
   * Float32 (never Int16, stored as offset UInt16).
   */
  static ScalarType Choose(const std::vector<ScalarType>& types, Storage storage);
  /// Bytes per texel of an atlas type.
  static int GetTexelSize(ScalarType atlas)
  {
    return strata::VolumeBrickTree::GetScalarSize(atlas);
  }
  /// The type a VTK scalar type (VTK_UNSIGNED_CHAR, ...) is stored as: 8-bit unsigned
  /// UInt8, signed 8-bit and int16 Int16, uint16 UInt16, anything else Float32.
  static ScalarType FromVTKType(int vtkType);
  /// Whether the shader decodes texels (a normalised atlas type).
  static bool IsNormalized(ScalarType atlas) { return atlas != ScalarType::Float32; }
  /// value = texel * scale + offset for a volume of `volume` values in an atlas of `atlas`.
  static void GetDecode(ScalarType atlas, ScalarType volume, double& scale, double& offset);
  /**
   * Writes n values of a volume of type `volume` as texels of `atlas` into `out`
   * (n * GetTexelSize(atlas) bytes): rounded to the nearest integer, offset and clamped to
   * the type's range for integer atlases, copied for Float32.
   */
  static void Encode(const float* values, size_t n, ScalarType atlas, ScalarType volume, void* out);
  /// Short names: "uint8", "uint16", "int16", "float32".
  static const char* GetName(ScalarType type);
};
}

#endif
