// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataVolumeSurfaceLayers.h"

#include "StrataRenderUtilities.h"

#include "vtkActor.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkRenderState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <algorithm>
#include <string>

namespace strata
{

VolumeSurfaceLayers::VolumeSurfaceLayers()
  : Pass(vtkSmartPointer<vtkVolumeSurfacePeelPass>::New())
{
}

VolumeSurfaceLayers::~VolumeSurfaceLayers()
{
  this->RemoveAllActors(); // no actor keeps a peel that nothing sets up
}

void VolumeSurfaceLayers::Allocate(vtkOpenGLRenderWindow* window, int width, int height, int layers)
{
  auto sized = [&](vtkSmartPointer<vtkTextureObject>& t, bool depth, int components)
  {
    if (!t)
      t = vtkSmartPointer<vtkTextureObject>::New();
    t->SetContext(window);
    if (int(t->GetWidth()) == width && int(t->GetHeight()) == height && t->GetHandle())
      return;
    t->ReleaseGraphicsResources(window);
    t->SetContext(window);
    if (depth)
      t->AllocateDepth(width, height, vtkTextureObject::Float32);
    else
      t->Allocate2D(width, height, components, VTK_FLOAT);
  };
  this->Colors.resize(std::max<size_t>(this->Colors.size(), layers));
  this->Depths.resize(std::max<size_t>(this->Depths.size(), layers));
  for (int k = 0; k < layers; ++k)
  {
    sized(this->Colors[k], false, 4);
    sized(this->Depths[k], true, 1);
  }
  // RGBA, alpha kept 0: the integration blend scales the source by 1 - destination alpha, and a
  // one-channel texture would read alpha 1.
  sized(this->Progress, false, 4);
  if (!this->Framebuffer)
    this->Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
  this->Framebuffer->SetContext(window);
  this->Layers = layers;
}

void VolumeSurfaceLayers::Attach(vtkActor* actor) const
{
  vtkInformation* keys = actor->GetPropertyKeys();
  if (!keys)
  {
    vtkNew<vtkInformation> info;
    actor->SetPropertyKeys(info);
    keys = info;
  }
  if (!keys->Has(vtkOpenGLRenderPass::RenderPasses()) ||
      keys->Length(vtkOpenGLRenderPass::RenderPasses()) == 0)
    keys->Append(vtkOpenGLRenderPass::RenderPasses(), this->Pass);
}

void VolumeSurfaceLayers::AddActor(vtkActor* actor)
{
  if (!actor)
    return;
  this->Actors.emplace_back(actor);
  // At once: a height-field actor in the renderer too knows from its first frame that its
  // translucent horizons are peeled here (the translucent pass comes before the volumes').
  this->Attach(actor);
}

void VolumeSurfaceLayers::RemoveAllActors()
{
  for (vtkActor* actor : this->Actors)
  {
    vtkInformation* keys = actor->GetPropertyKeys();
    if (keys && keys->Has(vtkOpenGLRenderPass::RenderPasses()))
      keys->Remove(vtkOpenGLRenderPass::RenderPasses(), this->Pass);
  }
  this->Actors.clear();
}

bool VolumeSurfaceLayers::HasVisibleActors() const
{
  return std::any_of(this->Actors.begin(),
    this->Actors.end(),
    [](vtkActor* a) { return a->GetVisibility() && a->GetMapper(); });
}

int VolumeSurfaceLayers::Peel(vtkRenderer* ren,
  vtkOpenGLRenderWindow* window,
  vtkTextureObject* sceneDepth,
  const int viewport[4],
  int layers,
  int rays,
  bool acrossFragments)
{
  this->Layers = 0;
  std::vector<vtkActor*> actors;
  for (vtkActor* actor : this->Actors)
    if (actor->GetVisibility() && actor->GetMapper())
      actors.push_back(actor);
  if (actors.empty() || layers <= 0)
    return 0;
  if (!acrossFragments || rays >= 8)
  {
    if (!this->UnsupportedWarned)
      vtkGenericWarningMacro("Translucent actors among volumes need the front-to-back order, "
                             "texture barriers and at most 7 rays per pixel: not drawn.");
    this->UnsupportedWarned = true;
    return 0;
  }
  const int width = viewport[2], height = viewport[3];
  this->Allocate(window, width, height, layers);
  vtkOpenGLState* state = window->GetState();
  state->PushFramebufferBindings();
  {
    vtkOpenGLState::ScopedglViewport viewportSaver(state);
    vtkOpenGLState::ScopedglClearColor clearSaver(state);
    vtkOpenGLState::ScopedglEnableDisable blendEnable(state, GL_BLEND);
    vtkOpenGLState::ScopedglEnableDisable depthEnable(state, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
    vtkOpenGLState::ScopedglDepthFunc depthFuncSaver(state);
    // VTK leaves its scissor on the renderer's window rectangle: off for the layers, which sit at
    // (0, 0) of their own textures (a renderer off the window's origin lost its layers).
    vtkOpenGLState::ScopedglEnableDisable scissorEnable(state, GL_SCISSOR_TEST);
    this->Framebuffer->Bind();
    state->vtkglViewport(0, 0, width, height);
    state->vtkglDisable(GL_SCISSOR_TEST);
    state->vtkglDisable(GL_BLEND);
    state->vtkglEnable(GL_DEPTH_TEST);
    state->vtkglDepthFunc(GL_LESS);
    state->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
    state->vtkglClearDepth(1.0);
    this->Pass->Active = true; // the actors carry the pass since AddActor
    for (int k = 0; k < layers; ++k)
    {
      this->Framebuffer->AddColorAttachment(0, this->Colors[k]);
      this->Framebuffer->AddDepthAttachment(this->Depths[k]);
      this->Framebuffer->ActivateDrawBuffers(1);
      state->vtkglDepthMask(GL_TRUE);
      // No barrier needed: layer k is read only once detached (the peel of layer k + 1 reads
      // its depth with layer k + 1 attached; the integration reads the layers after the peel).
      state->vtkglClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      this->Pass->Layer = k;
      this->Pass->Scene = sceneDepth;
      this->Pass->Previous = k > 0 ? this->Depths[k - 1].Get() : sceneDepth;
      sceneDepth->Activate();
      this->Pass->Previous->Activate();
      // vtkActor::Render directly, not RenderTranslucentPolygonalGeometry: outside the
      // translucent pass the actor writes depth, which the peel needs.
      for (vtkActor* actor : actors)
        actor->Render(ren, actor->GetMapper());
      this->Pass->Previous->Deactivate();
      sceneDepth->Deactivate();
    }
    this->Pass->Active = false;
    this->Pass->Scene = nullptr; // freed with the buffers; not to be named after the peel
    this->Pass->Previous = nullptr;
    this->Framebuffer->RemoveDepthAttachment();
    this->Framebuffer->RemoveColorAttachment(0);
  }
  state->PopFramebufferBindings();
  return this->Layers;
}

vtkTextureObject* VolumeSurfaceLayers::GetColor(int layer) const
{
  return this->Colors[layer];
}

vtkTextureObject* VolumeSurfaceLayers::GetDepth(int layer) const
{
  return this->Depths[layer];
}

vtkTextureObject* VolumeSurfaceLayers::GetProgress() const
{
  return this->Layers > 0 ? this->Progress.Get() : nullptr;
}

void VolumeSurfaceLayers::SetUniforms(vtkShaderProgram* program) const
{
  if (this->Layers == 0)
    return;
  for (int k = 0; k < this->Layers; ++k)
  {
    const std::string K = std::to_string(k);
    this->Colors[k]->Activate();
    program->SetUniformi(("uSurfaceColor" + K).c_str(), this->Colors[k]->GetTextureUnit());
    this->Depths[k]->Activate();
    program->SetUniformi(("uSurfaceDepth" + K).c_str(), this->Depths[k]->GetTextureUnit());
  }
  this->Progress->Activate();
  program->SetUniformi("uSurfaceProgress", this->Progress->GetTextureUnit());
}

void VolumeSurfaceLayers::Deactivate() const
{
  if (this->Layers == 0)
    return;
  for (int k = 0; k < this->Layers; ++k)
  {
    this->Colors[k]->Deactivate();
    this->Depths[k]->Deactivate();
  }
  this->Progress->Deactivate();
}

void VolumeSurfaceLayers::ReleaseGraphicsResources(vtkWindow* window)
{
  for (auto& t : this->Colors)
    t->ReleaseGraphicsResources(window);
  for (auto& t : this->Depths)
    t->ReleaseGraphicsResources(window);
  if (this->Progress)
    this->Progress->ReleaseGraphicsResources(window);
  if (this->Framebuffer)
    this->Framebuffer->ReleaseGraphicsResources(window);
  this->Colors.clear();
  this->Depths.clear();
  this->Progress = nullptr;
  this->Framebuffer = nullptr;
  this->Layers = 0;
}
}
