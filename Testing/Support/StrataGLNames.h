// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Counting the GL objects alive in a window's context (TestGraphicsResources, TestPagingSoak):
// textures, buffers, vertex arrays and framebuffers, by asking glIs* for every name in the
// range GL hands out.
#ifndef StrataGLNames_h
#define StrataGLNames_h

#include <string>

class vtkRenderWindow;

namespace strata_test
{
/// Live GL names of each kind in one context.
struct GLNames
{
  int Textures = 0, Buffers = 0, Arrays = 0, Framebuffers = 0;
  bool operator==(const GLNames& o) const
  {
    return this->Textures == o.Textures && this->Buffers == o.Buffers && this->Arrays == o.Arrays &&
           this->Framebuffers == o.Framebuffers;
  }
  int Total() const { return this->Textures + this->Buffers + this->Arrays + this->Framebuffers; }
  std::string Text() const;
};

/// Makes `win` current and counts its context's live names. Names are small integers handed
/// out from 1 up; 16384 is far beyond what one window of the tests' scenes makes.
GLNames CountGLNames(vtkRenderWindow* win);
}

#endif
