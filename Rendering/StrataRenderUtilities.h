// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::RenderUtilities
 * @brief   What every Strata mapper reads off the renderer the same way: the camera as a cut
 *          sees it, the scene's lights as the shaders use them, matrices as GLSL takes them.
 *
 * One shared place (VTK's vtkOpenGLRenderUtilities plays this part for VTK's own mappers), so
 * that the height-field, multi-volume and hybrid mappers agree by construction rather than by
 * calling each other's statics.
 */
#ifndef StrataRenderUtilities_h
#define StrataRenderUtilities_h

#include "StrataRenderingModule.h" // For export macro
#include "StrataVolumeCut.h"       // For strata::VolumeCut::Camera

#include <type_traits> // For std::is_floating_point
#include <vector>      // For std::vector

class vtkActor;
class vtkFieldData;
class vtkOpenGLRenderPass;
class vtkOpenGLState;
class vtkRenderer;

namespace strata
{
class STRATARENDERING_EXPORT RenderUtilities
{
public:
  /**
   * The renderer's active camera as strata::VolumeCut sees it: eye, pixels per radian (or per
   * world unit in parallel projection) for the tiled viewport's height, and the frustum
   * planes.
   */
  static strata::VolumeCut::Camera GetCutCamera(vtkRenderer* ren);

  /**
   * The scene's lights as the ray casters shade with them: directions towards each switched-on
   * light (a positional light counts as directional from its position to its focal point) and
   * colour times intensity, 3 floats each, at most 8.
   */
  static void GetLights(vtkRenderer* ren,
    std::vector<float>& directions,
    std::vector<float>& colors);

  /**
   * Makes what earlier draws and clears wrote into textures attached to the bound framebuffer
   * visible to texture reads of later draws while the textures stay attached (GL 4.5 section
   * 9.3.1; ARB_texture_barrier, or NV_texture_barrier before it). Without it such a read is
   * undefined: llvmpipe happens to run clears and draws in order, NVIDIA read stale texels
   * (a blob's core missing where the previous frame had terminated its rays). The only place
   * Strata issues the barrier; a pass that reads back what it draws calls it after each draw.
   */
  static void TextureBarrier();
  /// Whether the context has texture barriers (GL 4.5, ARB or NV_texture_barrier): a pass may
  /// read back what it draws only then.
  static bool HasTextureBarrier();

  /**
   * Clears the colour attachments of the bound draw framebuffer to (0, 0, 0, 0) for a pass that
   * reads them back as textures, and puts the texture barrier in: a clear is a write. Every
   * clear of such a pass goes through here.
   */
  static void ClearForReadBack(vtkOpenGLState* state);

  /**
   * Sets a pixel-store alignment (GL_UNPACK_ALIGNMENT or GL_PACK_ALIGNMENT) for its lifetime and
   * then puts back the value it found. vtkOpenGLState caches these and skips setting a value its
   * cache already holds, so a raw glPixelStorei left behind desynchronises VTK: its later
   * uploads of rows that are not a multiple of 4 bytes came out sheared (an 8-bit volume of odd
   * width after a skip-grid upload), and its RGB read-backs overran their buffers.
   */
  class STRATARENDERING_EXPORT ScopedPixelStore
  {
  public:
    ScopedPixelStore(unsigned int name, int value);
    ~ScopedPixelStore();
    ScopedPixelStore(const ScopedPixelStore&) = delete;
    ScopedPixelStore& operator=(const ScopedPixelStore&) = delete;

  private:
    unsigned int Name;
    int Saved = 4;
  };

  /**
   * Enables a capability VTK's state cache does not track (GL_DEPTH_CLAMP,
   * GL_PROGRAM_POINT_SIZE) for its lifetime, then leaves it as it found it, not forced off.
   */
  class STRATARENDERING_EXPORT ScopedEnable
  {
  public:
    explicit ScopedEnable(unsigned int capability);
    ~ScopedEnable();
    ScopedEnable(const ScopedEnable&) = delete;
    ScopedEnable& operator=(const ScopedEnable&) = delete;

  private:
    unsigned int Capability;
    bool WasEnabled = false;
  };

  /// A row-major double matrix (vtkMatrix4x4::GetData()) as the column-major floats that
  /// vtkShaderProgram::SetUniformMatrix4x4 hands to glUniformMatrix4fv.
  static void ToColumnMajor(const double rowMajor[16], float columnMajor[16]);

  /**
   * A statistics struct (one with ForEachField, e.g. strata::VolumePager::Statistics) as field data
   * the wrappers can take: one one-component, one-tuple array per field, named as the field;
   * floating-point fields as vtkDoubleArray, integers and flags (0 or 1) as vtkTypeInt64Array.
   * Arrays of those names already in `out` are replaced; others are kept.
   */
  template<typename Statistics>
  static void ToFieldData(const Statistics& statistics, vtkFieldData* out)
  {
    statistics.ForEachField(
      [out](const char* name, auto value)
      {
        if (std::is_floating_point<decltype(value)>::value)
        {
          SetField(out, name, static_cast<double>(value));
        }
        else
        {
          SetField(out, name, static_cast<long long>(value));
        }
      });
  }

  ///@{
  /// One named one-value array in `out` (replacing an array of that name).
  /// The first render pass on `actor`'s keys (vtkOpenGLRenderPass::RenderPasses()) that is a
  /// `Pass`, or null.
  template<typename Pass>
  static Pass* FindRenderPass(vtkActor* actor)
  {
    for (vtkOpenGLRenderPass* pass : GetRenderPasses(actor))
      if (auto* found = Pass::SafeDownCast(pass))
        return found;
    return nullptr;
  }
  /// The render passes on `actor`'s keys, in order.
  static std::vector<vtkOpenGLRenderPass*> GetRenderPasses(vtkActor* actor);

  static void SetField(vtkFieldData* out, const char* name, double value);
  static void SetField(vtkFieldData* out, const char* name, long long value);
  ///@}
};
}

#endif
