// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataComputeStaging.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <string>

namespace strata
{
namespace
{
const char* ResolveVertex = "//VTK::System::Dec\n"
                            "// One triangle over the viewport, which is the staged rectangle.\n"
                            "void main()\n{\n"
                            "  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, "
                            "float((gl_VertexID & 2) << 1) - 1.0);\n"
                            "  gl_Position = vec4(p, 0.0, 1.0);\n}\n";

std::string ResolveFragment(int outputs)
{
  std::string fs =
    "//VTK::System::Dec\n"
    "//VTK::Output::Dec\n"
    "// The compute stage's staged pixels (strata::ComputeStaging): depth and colours "
    "where a ray hit.\n"
    "uniform ivec2 uOrigin;\n"
    "uniform sampler2D uStagedDepth;\n";
  for (int i = 0; i < outputs; ++i)
    fs += "uniform sampler2D uStaged" + std::to_string(i) + ";\n";
  fs += "void main()\n{\n"
        "  ivec2 texel = ivec2(gl_FragCoord.xy) - uOrigin;\n"
        "  vec2 staged = texelFetch(uStagedDepth, texel, 0).rg;\n"
        "  if (staged.y < 0.5)\n  {\n    discard;\n  }\n"
        "  gl_FragDepth = staged.x;\n";
  for (int i = 0; i < outputs; ++i)
    fs += "  gl_FragData[" + std::to_string(i) + "] = texelFetch(uStaged" + std::to_string(i) +
          ", texel, 0);\n";
  return fs + "}\n";
}

// (Re)allocates `t` as width x height of `components` floats; true if it holds that now.
void Size(vtkSmartPointer<vtkTextureObject>& t,
  vtkOpenGLRenderWindow* window,
  int width,
  int height,
  int components)
{
  if (!t)
    t = vtkSmartPointer<vtkTextureObject>::New();
  t->SetContext(window);
  if (int(t->GetWidth()) == width && int(t->GetHeight()) == height &&
      int(t->GetComponents()) == components && t->GetHandle())
    return;
  t->ReleaseGraphicsResources(window);
  t->SetContext(window);
  t->Allocate2D(width, height, components, VTK_FLOAT);
}
}

ComputeStaging::ComputeStaging() = default;
ComputeStaging::~ComputeStaging() = default;

void ComputeStaging::Bind(vtkOpenGLRenderWindow* window,
  int width,
  int height,
  const ComputeStage::Outputs& outputs)
{
  for (int i = 0; i < outputs.Count && i < 2; ++i)
  {
    Size(this->Colors[i], window, width, height, 4);
    glBindImageTexture(ComputeStage::FirstImageUnit + i,
      this->Colors[i]->GetHandle(),
      0,
      GL_FALSE,
      0,
      GL_WRITE_ONLY,
      GL_RGBA32F);
  }
  Size(this->Depth, window, width, height, 2);
  glBindImageTexture(ComputeStage::DepthImageUnit(outputs),
    this->Depth->GetHandle(),
    0,
    GL_FALSE,
    0,
    GL_WRITE_ONLY,
    GL_RG32F);
  this->Bound = outputs;
}

void ComputeStaging::Unbind()
{
  for (int i = 0; i <= this->Bound.Count; ++i)
    glBindImageTexture(
      ComputeStage::FirstImageUnit + i, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
}

bool ComputeStaging::Resolve(vtkOpenGLRenderWindow* window, const int rect[4], const int origin[2])
{
  const int outputs = this->Bound.Count;
  const std::string fs = ResolveFragment(outputs);
  vtkShaderProgram* program =
    window->GetShaderCache()->ReadyShaderProgram(ResolveVertex, fs.c_str(), "");
  if (!program)
    return false;
  // The dispatch's image stores, read here as textures.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglViewport viewportSaver(state);
  state->vtkglViewport(origin[0] + rect[0], origin[1] + rect[1], rect[2], rect[3]);
  program->SetUniform2i("uOrigin", origin);
  this->Depth->Activate();
  program->SetUniformi("uStagedDepth", this->Depth->GetTextureUnit());
  for (int i = 0; i < outputs; ++i)
  {
    this->Colors[i]->Activate();
    program->SetUniformi(
      ("uStaged" + std::to_string(i)).c_str(), this->Colors[i]->GetTextureUnit());
  }
  glBindVertexArray(this->EmptyArray.Get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  for (int i = 0; i < outputs; ++i)
    this->Colors[i]->Deactivate();
  this->Depth->Deactivate();
  return true;
}

void ComputeStaging::ReleaseGraphicsResources(vtkWindow* window)
{
  for (auto& c : this->Colors)
    if (c)
      c->ReleaseGraphicsResources(window);
  if (this->Depth)
    this->Depth->ReleaseGraphicsResources(window);
  this->Colors = {};
  this->Depth = nullptr;
  this->EmptyArray.Release();
}
}
