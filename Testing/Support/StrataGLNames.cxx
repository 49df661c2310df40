// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataGLNames.h"

#include "vtkRenderWindow.h"
#include "vtk_glew.h"

namespace strata_test
{
std::string GLNames::Text() const
{
  return std::to_string(this->Textures) + " textures, " + std::to_string(this->Buffers) +
         " buffers, " + std::to_string(this->Arrays) + " vertex arrays, " +
         std::to_string(this->Framebuffers) + " framebuffers";
}

GLNames CountGLNames(vtkRenderWindow* win)
{
  win->MakeCurrent();
  GLNames n;
  for (GLuint name = 1; name < 16384; ++name)
  {
    n.Textures += glIsTexture(name) ? 1 : 0;
    n.Buffers += glIsBuffer(name) ? 1 : 0;
    n.Arrays += glIsVertexArray(name) ? 1 : 0;
    n.Framebuffers += glIsFramebuffer(name) ? 1 : 0;
  }
  return n;
}
}
