// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataVolumeIntegrationBuffers.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <string>

namespace strata
{

VolumeIntegrationBuffers::VolumeIntegrationBuffers() = default;
VolumeIntegrationBuffers::~VolumeIntegrationBuffers() = default;

void VolumeIntegrationBuffers::Prepare(vtkOpenGLRenderWindow* window,
  const int viewport[4],
  int rays)
{
  const int width = viewport[2], height = viewport[3];
  if (!this->Framebuffer)
  {
    this->Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    this->SceneDepth = vtkSmartPointer<vtkTextureObject>::New();
  }
  this->Framebuffer->SetContext(window);
  this->SceneDepth->SetContext(window);
  if (int(this->SceneDepth->GetWidth()) != width || int(this->SceneDepth->GetHeight()) != height)
  {
    this->SceneDepth->ReleaseGraphicsResources(window);
    this->SceneDepth->SetContext(window);
    this->SceneDepth->AllocateDepth(width, height, vtkTextureObject::Float32);
  }
  while (static_cast<int>(this->Accumulation.size()) < rays)
  {
    this->Accumulation.push_back(vtkSmartPointer<vtkTextureObject>::New());
  }
  for (int r = 0; r < rays; ++r)
  {
    vtkTextureObject* acc = this->Accumulation[r];
    acc->SetContext(window);
    if (int(acc->GetWidth()) != width || int(acc->GetHeight()) != height || !acc->GetHandle())
    {
      acc->ReleaseGraphicsResources(window);
      acc->SetContext(window);
      acc->Allocate2D(width, height, 4, VTK_FLOAT);
    }
  }
  this->SceneDepth->Activate();
  this->SceneDepth->CopyFromFrameBuffer(viewport[0], viewport[1], 0, 0, width, height);
  this->SceneDepth->Deactivate();
}

void VolumeIntegrationBuffers::Bind(vtkOpenGLRenderWindow* window,
  int rays,
  vtkTextureObject* extra)
{
  window->GetState()->PushFramebufferBindings();
  this->Framebuffer->Bind();
  // Detach first: VTK's framebuffer keeps an attachment whose vtkTextureObject it already holds
  // even when Prepare reallocated that texture under a new GL name (a resize), and a framebuffer
  // that is not bound keeps a deleted texture attached. Without this every draw after a resize
  // went into the old, deleted textures and the composite read new, never written ones.
  this->Framebuffer->RemoveColorAttachments(static_cast<unsigned int>(this->Attached));
  for (int r = 0; r < rays; ++r)
  {
    this->Framebuffer->AddColorAttachment(r, this->Accumulation[r]);
  }
  if (extra)
    this->Framebuffer->AddColorAttachment(rays, extra);
  this->Attached = rays + (extra ? 1 : 0);
  this->Framebuffer->ActivateDrawBuffers(this->Attached);
}

void VolumeIntegrationBuffers::Unbind(vtkOpenGLRenderWindow* window)
{
  window->GetState()->PopFramebufferBindings();
}

vtkTextureObject* VolumeIntegrationBuffers::GetAccumulation(int ray) const
{
  return this->Accumulation[ray];
}

vtkTextureObject* VolumeIntegrationBuffers::GetSceneDepth() const
{
  return this->SceneDepth;
}

void VolumeIntegrationBuffers::Composite(vtkShaderProgram* program, const int viewport[4], int rays)
{
  for (int r = 0; r < rays; ++r)
  {
    this->Accumulation[r]->Activate();
    program->SetUniformi(
      ("uAccumulation" + std::to_string(r)).c_str(), this->Accumulation[r]->GetTextureUnit());
  }
  const float origin[2] = { float(viewport[0]), float(viewport[1]) };
  program->SetUniform2f("uViewportOrigin", origin);
  glBindVertexArray(this->EmptyArray.Get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  for (int r = 0; r < rays; ++r)
  {
    this->Accumulation[r]->Deactivate();
  }
}

void VolumeIntegrationBuffers::ReleaseGraphicsResources(vtkWindow* window)
{
  for (auto& a : this->Accumulation)
    a->ReleaseGraphicsResources(window);
  if (this->SceneDepth)
    this->SceneDepth->ReleaseGraphicsResources(window);
  if (this->Framebuffer)
    this->Framebuffer->ReleaseGraphicsResources(window);
  this->Accumulation.clear();
  this->Attached = 0;
  this->SceneDepth = nullptr;
  this->Framebuffer = nullptr;
  this->EmptyArray.Release();
}
}
