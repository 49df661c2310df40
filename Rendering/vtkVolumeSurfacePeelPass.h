// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkVolumeSurfacePeelPass
 * @brief   The depth peel's hook into vtkOpenGLPolyDataMapper's fragment shader.
 *
 * Set on an actor's vtkOpenGLRenderPass::RenderPasses() key: a fragment survives pass k only in
 * front of the opaque scene and, for k > 0, behind layer k - 1; the depth test keeps the nearest
 * survivor. Mappers with their own shaders (vtkStackedHeightFieldMapper) find it on their actor and
 * read the same textures. strata::VolumeSurfaceLayers owns one and sets it up in Peel.
 *
 * @sa strata::VolumeSurfaceLayers
 */
#ifndef vtkVolumeSurfacePeelPass_h
#define vtkVolumeSurfacePeelPass_h

#include "StrataRenderingModule.h" // For export macro
#include "vtkOpenGLRenderPass.h"

#include <string> // For std::string

class vtkActor;
class vtkShaderProgram;
class vtkTextureObject;

class STRATARENDERING_EXPORT vtkVolumeSurfacePeelPass : public vtkOpenGLRenderPass
{
public:
  static vtkVolumeSurfacePeelPass* New();
  vtkTypeMacro(vtkVolumeSurfacePeelPass, vtkOpenGLRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The peel on `actor`'s keys, or null.
  static vtkVolumeSurfacePeelPass* Find(vtkActor* actor);

  void Render(const vtkRenderState*) override {}
  bool PreReplaceShaderValues(std::string& vertexShader,
    std::string& geometryShader,
    std::string& fragmentShader,
    vtkAbstractMapper* mapper,
    vtkProp* prop) override;
  bool SetShaderParameters(vtkShaderProgram* program,
    vtkAbstractMapper* mapper,
    vtkProp* prop,
    vtkOpenGLVertexArrayObject* vao) override;

  vtkTextureObject* Scene = nullptr;    ///< the opaque scene's depth, activated by Peel
  vtkTextureObject* Previous = nullptr; ///< layer k - 1's depth (k > 0), activated by Peel
  int Layer = 0;                        ///< k
  bool Active = false;                  ///< Peel is drawing (else attached between frames)

protected:
  vtkVolumeSurfacePeelPass() = default;
  ~vtkVolumeSurfacePeelPass() override = default;

private:
  vtkVolumeSurfacePeelPass(const vtkVolumeSurfacePeelPass&) = delete;
  void operator=(const vtkVolumeSurfacePeelPass&) = delete;
};

#endif
