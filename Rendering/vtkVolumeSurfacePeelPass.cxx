// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkVolumeSurfacePeelPass.h"

#include "StrataRenderUtilities.h"

#include "vtkActor.h"
#include "vtkObjectFactory.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include <string>

vtkStandardNewMacro(vtkVolumeSurfacePeelPass);

//------------------------------------------------------------------------------
void vtkVolumeSurfacePeelPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Scene: " << this->Scene << "\n";
  os << indent << "Previous: " << this->Previous << "\n";
  os << indent << "Layer: " << this->Layer << "\n";
  os << indent << "Active: " << this->Active << "\n";
}

bool vtkVolumeSurfacePeelPass::PreReplaceShaderValues(std::string&,
  std::string&,
  std::string& fragmentShader,
  vtkAbstractMapper*,
  vtkProp*)
{
  vtkShaderProgram::Substitute(fragmentShader,
    "//VTK::DepthPeeling::Dec",
    "uniform sampler2D strataPeelScene;\nuniform sampler2D strataPeelPrevious;\n"
    "uniform int strataPeelLayer;\nuniform int strataPeelActive;\n//VTK::DepthPeeling::Dec");
  vtkShaderProgram::Substitute(fragmentShader,
    "//VTK::DepthPeeling::PreColor",
    "{\n    ivec2 strataPixel = ivec2(gl_FragCoord.xy);\n"
    "    if (strataPeelActive != 0 &&\n"
    "      (gl_FragCoord.z >= texelFetch(strataPeelScene, strataPixel, 0).r ||\n"
    "      (strataPeelLayer > 0 &&\n"
    "        gl_FragCoord.z <= texelFetch(strataPeelPrevious, strataPixel, 0).r)))\n"
    "    {\n      discard;\n    }\n  }\n  //VTK::DepthPeeling::PreColor");
  return true;
}

bool vtkVolumeSurfacePeelPass::SetShaderParameters(vtkShaderProgram* program,
  vtkAbstractMapper*,
  vtkProp*,
  vtkOpenGLVertexArrayObject*)
{
  // Drawn outside a peel (an actor also in the renderer), the test is off: its samplers would
  // name whatever is bound on the last peel's units.
  program->SetUniformi("strataPeelActive", this->Active ? 1 : 0);
  if (!this->Active)
    return true;
  program->SetUniformi("strataPeelScene", this->Scene->GetTextureUnit());
  program->SetUniformi("strataPeelPrevious", this->Previous->GetTextureUnit());
  program->SetUniformi("strataPeelLayer", this->Layer);
  return true;
}

vtkVolumeSurfacePeelPass* vtkVolumeSurfacePeelPass::Find(vtkActor* actor)
{
  return strata::RenderUtilities::FindRenderPass<vtkVolumeSurfacePeelPass>(actor);
}
