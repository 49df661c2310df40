// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStrataComputeProgram
 * @brief   A compute program that the ray casters' parts bind their textures and uniforms to as
 *          to any vtkShaderProgram.
 *
 * VTK 9.1's shader program compiles vertex, fragment and geometry shaders only. The ray casters
 * set their uniforms through vtkShaderProgram (its SetUniform calls and cached locations), in the
 * parts shared by both stages (strata::MultiVolumeInput, strata::VolumeSurfaceLayers, the atlases);
 * this program is one of those, built from one compute source. It is not in the window's shader
 * cache: Use() binds it and tells that cache that none of its own programs is bound, so that VTK
 * binds its next program again. A built program is not rebuilt; its owner makes a new one after
 * ReleaseGraphicsResources (the uniform locations cached by vtkShaderProgram belong to one link).
 *
 * @sa strata::ComputeStage
 */
#ifndef vtkStrataComputeProgram_h
#define vtkStrataComputeProgram_h

#include "StrataRenderingModule.h" // For export macro
#include "vtkShaderProgram.h"

#include <string> // For std::string

class vtkOpenGLRenderWindow;
class vtkWindow;

class STRATARENDERING_EXPORT vtkStrataComputeProgram : public vtkShaderProgram
{
public:
  static vtkStrataComputeProgram* New();
  vtkTypeMacro(vtkStrataComputeProgram, vtkShaderProgram);

  /// Compiles and links `source` (the context current); false with the log in GetError().
  bool Build(const std::string& source);
  /// The source of the last Build.
  const std::string& GetComputeSource() const { return this->ComputeSource; }
  /// Whether Build succeeded and nothing was released since.
  bool IsBuilt() const { return this->Handle != 0 && this->Linked; }

  /// Binds the program; the window's shader cache then holds no bound program.
  void Use(vtkOpenGLRenderWindow* window);

  /// Deletes the program (its window's context current).
  void ReleaseComputeProgram(vtkWindow* window);

protected:
  vtkStrataComputeProgram() = default;
  ~vtkStrataComputeProgram() override = default;

private:
  vtkStrataComputeProgram(const vtkStrataComputeProgram&) = delete;
  void operator=(const vtkStrataComputeProgram&) = delete;

  std::string ComputeSource;
};

#endif
