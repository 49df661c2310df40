// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataFeedbackBuffer.h"

#include "StrataRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureUnitManager.h"
#include "vtk_glew.h"

namespace strata
{

namespace
{
// Runs `use` with a texture unit of the window's manager active, so that the binds made in it
// disturb no unit someone else holds. (A window that counts no units, its resources released,
// counts them again in strata::GraphicsResources::Register, before any mapper draws.)
template<typename Use>
void OnFreeUnit(vtkOpenGLRenderWindow* window, Use&& use)
{
  vtkTextureUnitManager* units = window->GetTextureUnitManager();
  const int unit = units->Allocate();
  window->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
  use();
  glBindTexture(GL_TEXTURE_2D, 0);
  units->Free(unit);
}

void Define(GLuint texture, GLint format, GLenum pixels, GLenum type, int width, int height)
{
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexImage2D(GL_TEXTURE_2D, 0, format, width, height, 0, pixels, type, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}
}

FeedbackBuffer::FeedbackBuffer(bool scored)
  : Scored(scored)
{
}

bool FeedbackBuffer::Allocate(vtkOpenGLRenderWindow* window, int width, int height, int scale)
{
  const int w = (width + scale - 1) / scale;
  const int h = (height + scale - 1) / scale;
  if (this->Ids && w == this->Size[0] && h == this->Size[1])
  {
    return false;
  }
  OnFreeUnit(window,
    [&]
    {
      Define(this->Ids.Get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, w, h);
      if (this->Scored)
        Define(this->Scores.Get(), GL_R32F, GL_RED, GL_FLOAT, w, h);
    });
  glBindBuffer(GL_PIXEL_PACK_BUFFER, this->PixelBuffer.Get());
  glBufferData(GL_PIXEL_PACK_BUFFER,
    static_cast<GLsizeiptr>(size_t(w) * h * sizeof(uint32_t)),
    nullptr,
    GL_STREAM_READ);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  this->Size[0] = w;
  this->Size[1] = h;
  this->Pending = false;
  return true;
}

void FeedbackBuffer::Clear(vtkOpenGLRenderWindow* window)
{
  const GLuint zero = 0;
  const GLfloat zeroScore = 0.f;
  if (GLEW_VERSION_4_4 || GLEW_ARB_clear_texture)
  {
    // No barrier needed: image units, not attachments; a clear is an ordinary GL command, which
    // later image loads see in order (glMemoryBarrier orders shader writes only; Queue has it).
    glClearTexImage(this->Ids.GetName(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    if (this->Scored)
      // No barrier needed: as above.
      glClearTexImage(this->Scores.GetName(), 0, GL_RED, GL_FLOAT, &zeroScore);
    return;
  }
  // All-zero bits are 0u and 0.0f alike.
  const std::vector<GLuint> zeros(static_cast<size_t>(this->Size[0]) * this->Size[1], 0u);
  OnFreeUnit(window,
    [&]
    {
      const strata::RenderUtilities::ScopedPixelStore alignment(GL_UNPACK_ALIGNMENT, 4);
      glBindTexture(GL_TEXTURE_2D, this->Ids.GetName());
      glTexSubImage2D(GL_TEXTURE_2D,
        0,
        0,
        0,
        this->Size[0],
        this->Size[1],
        GL_RED_INTEGER,
        GL_UNSIGNED_INT,
        zeros.data());
      if (this->Scored)
      {
        glBindTexture(GL_TEXTURE_2D, this->Scores.GetName());
        glTexSubImage2D(
          GL_TEXTURE_2D, 0, 0, 0, this->Size[0], this->Size[1], GL_RED, GL_FLOAT, zeros.data());
      }
    });
}

void FeedbackBuffer::BindImages(bool readWrite)
{
  const GLenum access = readWrite ? GL_READ_WRITE : GL_WRITE_ONLY;
  glBindImageTexture(0, this->Ids.GetName(), 0, GL_FALSE, 0, access, GL_R32UI);
  if (this->Scored)
    glBindImageTexture(1, this->Scores.GetName(), 0, GL_FALSE, 0, access, GL_R32F);
}

void FeedbackBuffer::UnbindImages()
{
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  if (this->Scored)
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
}

void FeedbackBuffer::Queue(vtkOpenGLRenderWindow* window)
{
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
  OnFreeUnit(window,
    [&]
    {
      glBindTexture(GL_TEXTURE_2D, this->Ids.GetName());
      glBindBuffer(GL_PIXEL_PACK_BUFFER, this->PixelBuffer.GetName());
      const strata::RenderUtilities::ScopedPixelStore alignment(GL_PACK_ALIGNMENT, 4);
      glGetTexImage(GL_TEXTURE_2D, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
      glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    });
  this->Pending = true;
}

bool FeedbackBuffer::Read(std::vector<strata::FeedbackReduction::Entry>& list)
{
  list.clear();
  if (!this->Pending || !this->PixelBuffer)
    return false;
  this->Pending = false;
  const size_t count = static_cast<size_t>(this->Size[0]) * this->Size[1];
  glBindBuffer(GL_PIXEL_PACK_BUFFER, this->PixelBuffer.GetName());
  const auto* ids = static_cast<const uint32_t*>(glMapBufferRange(
    GL_PIXEL_PACK_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(uint32_t)), GL_MAP_READ_BIT));
  if (ids)
  {
    this->LastOpenCL = this->UseOpenCL && this->Reduction.ReduceOpenCL(ids, count, list);
    if (!this->LastOpenCL)
      this->Reduction.ReduceCPU(ids, count, list);
    glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  return ids != nullptr;
}

void FeedbackBuffer::ReleaseGraphicsResources()
{
  this->Ids.Release();
  this->Scores.Release();
  this->PixelBuffer.Release();
  this->Size[0] = this->Size[1] = 0;
  this->Pending = false;
}
}
