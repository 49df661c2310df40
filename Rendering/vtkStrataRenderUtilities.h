// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStrataRenderUtilities
 * @brief   What every Strata mapper reads off the renderer the same way: the camera as a cut
 *          sees it, the scene's lights as the shaders use them, matrices as GLSL takes them.
 *
 * One shared place (VTK's vtkOpenGLRenderUtilities plays this part for VTK's own mappers), so
 * that the height-field, multi-volume and hybrid mappers agree by construction rather than by
 * calling each other's statics.
 */
#ifndef vtkStrataRenderUtilities_h
#define vtkStrataRenderUtilities_h

#include "StrataRenderingModule.h" // For export macro
#include "vtkVolumeCut.h"          // For vtkVolumeCut::Camera

#include <type_traits> // For std::is_floating_point
#include <vector>      // For std::vector

class vtkActor;
class vtkFieldData;
class vtkOpenGLRenderPass;
class vtkRenderer;

class STRATARENDERING_EXPORT vtkStrataRenderUtilities
{
public:
  /**
   * The renderer's active camera as vtkVolumeCut sees it: eye, pixels per radian (or per
   * world unit in parallel projection) for the tiled viewport's height, and the frustum
   * planes.
   */
  static vtkVolumeCut::Camera GetCutCamera(vtkRenderer* ren);

  /**
   * The scene's lights as the ray casters shade with them: directions towards each switched-on
   * light (a positional light counts as directional from its position to its focal point) and
   * colour times intensity, 3 floats each, at most 8.
   */
  static void GetLights(vtkRenderer* ren,
    std::vector<float>& directions,
    std::vector<float>& colors);

  /// A row-major double matrix (vtkMatrix4x4::GetData()) as the column-major floats that
  /// vtkShaderProgram::SetUniformMatrix4x4 hands to glUniformMatrix4fv.
  static void ToColumnMajor(const double rowMajor[16], float columnMajor[16]);

  /**
   * A statistics struct (one with ForEachField, e.g. vtkVolumePager::Statistics) as field data
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

#endif
