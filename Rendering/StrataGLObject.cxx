// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataGLObject.h"

#include "vtk_glew.h"

namespace strata
{

unsigned int GLObject::Get()
{
  if (!this->Name)
  {
    GLuint name = 0;
    switch (this->Kind)
    {
      case Kinds::Texture:
        glGenTextures(1, &name);
        break;
      case Kinds::Buffer:
        glGenBuffers(1, &name);
        break;
      case Kinds::VertexArray:
        glGenVertexArrays(1, &name);
        break;
    }
    this->Name = name;
  }
  return this->Name;
}

void GLObject::Release()
{
  if (!this->Name)
    return;
  GLuint name = this->Name;
  switch (this->Kind)
  {
    case Kinds::Texture:
      glDeleteTextures(1, &name);
      break;
    case Kinds::Buffer:
      glDeleteBuffers(1, &name);
      break;
    case Kinds::VertexArray:
      glDeleteVertexArrays(1, &name);
      break;
  }
  this->Name = 0;
}
}
