// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkStrataComputeProgram.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtk_glew.h"

#include <vector>

vtkStandardNewMacro(vtkStrataComputeProgram);

namespace
{
std::string InfoLog(GLuint object, bool program)
{
  GLint length = 0;
  if (program)
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  else
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
  if (program)
    glGetProgramInfoLog(object, length, nullptr, log.data());
  else
    glGetShaderInfoLog(object, length, nullptr, log.data());
  return std::string(log.data());
}
}

bool vtkStrataComputeProgram::Build(const std::string& source)
{
  this->ComputeSource = source;
  if (this->Handle != 0)
  {
    this->Error = "vtkStrataComputeProgram: already built";
    return false;
  }
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok)
  {
    this->Error = "compute shader: " + InfoLog(shader, false);
    glDeleteShader(shader);
    return false;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDetachShader(program, shader);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok)
  {
    this->Error = "compute program: " + InfoLog(program, true);
    glDeleteProgram(program);
    return false;
  }
  this->Handle = static_cast<int>(program);
  this->Linked = true;
  this->Error.clear();
  return true;
}

void vtkStrataComputeProgram::Use(vtkOpenGLRenderWindow* window)
{
  // VTK's cache binds a program only when it is not the one it bound last: forget that one.
  window->GetShaderCache()->ReleaseCurrentShader();
  glUseProgram(static_cast<GLuint>(this->Handle));
  this->Bound = true;
}

void vtkStrataComputeProgram::ReleaseComputeProgram(vtkWindow*)
{
  if (this->Handle != 0)
    glDeleteProgram(static_cast<GLuint>(this->Handle));
  this->Handle = 0;
  this->Linked = false;
  this->Bound = false;
}
