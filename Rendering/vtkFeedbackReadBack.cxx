// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkFeedbackReadBack.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

void vtkFeedbackReadBack::Allocate(unsigned int& buffer, size_t count)
{
  if (!buffer)
    glGenBuffers(1, &buffer);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
  glBufferData(GL_PIXEL_PACK_BUFFER,
    static_cast<GLsizeiptr>(count * sizeof(uint32_t)),
    nullptr,
    GL_STREAM_READ);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

void vtkFeedbackReadBack::Queue(vtkOpenGLRenderWindow* renWin,
  unsigned int texture,
  unsigned int buffer)
{
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
  vtkTextureUnitManager* units = renWin->GetTextureUnitManager();
  const int unit = units->Allocate();
  renWin->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, texture);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindTexture(GL_TEXTURE_2D, 0);
  units->Free(unit);
}

bool vtkFeedbackReadBack::Map(unsigned int buffer,
  size_t count,
  const std::function<void(const uint32_t* ids)>& use)
{
  glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
  const auto* ids = static_cast<const uint32_t*>(glMapBufferRange(
    GL_PIXEL_PACK_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(uint32_t)), GL_MAP_READ_BIT));
  if (ids)
  {
    use(ids);
    glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  return ids != nullptr;
}
