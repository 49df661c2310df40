// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::GLObject
 * @brief   One OpenGL texture, buffer or vertex array name, owned.
 *
 * For the GL objects VTK has no class for in the form the mappers need (integer and array
 * textures of a given internal format, pixel-pack buffers, plain vertex arrays). The name is
 * created on first Get() in the current context and deleted by Release(), which the owner
 * calls from its ReleaseGraphicsResources, where VTK guarantees a current context (the
 * owner's strata::GraphicsResources makes it current when the owner dies first). The
 * destructor deletes nothing: without its context a GL name cannot be deleted, so an owner
 * that forgot Release() leaks it, which the GL lifetime test catches.
 */
#ifndef StrataGLObject_h
#define StrataGLObject_h

#include "StrataRenderingModule.h" // For export macro

namespace strata
{
class STRATARENDERING_EXPORT GLObject
{
public:
  enum class Kinds
  {
    Texture,
    Buffer,
    VertexArray,
  };

  explicit GLObject(Kinds kind)
    : Kind(kind)
  {
  }
  GLObject(const GLObject&) = delete;
  GLObject& operator=(const GLObject&) = delete;

  /// The name, generated in the current context if there is none yet.
  unsigned int Get();
  /// The name, 0 if none.
  unsigned int GetName() const { return this->Name; }
  explicit operator bool() const { return this->Name != 0; }
  /// Deletes the name (the owner's context must be current); then Get() makes a new one.
  void Release();

private:
  Kinds Kind;
  unsigned int Name = 0;
};
}

#endif
