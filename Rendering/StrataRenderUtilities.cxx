// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataRenderUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkTypeInt64Array.h"
#include "vtk_glew.h"

#include <cmath>

namespace strata
{

std::vector<vtkOpenGLRenderPass*> RenderUtilities::GetRenderPasses(vtkActor* actor)
{
  std::vector<vtkOpenGLRenderPass*> passes;
  vtkInformation* keys = actor ? actor->GetPropertyKeys() : nullptr;
  if (!keys || !keys->Has(vtkOpenGLRenderPass::RenderPasses()))
    return passes;
  for (int i = 0; i < keys->Length(vtkOpenGLRenderPass::RenderPasses()); ++i)
    if (auto* pass =
          vtkOpenGLRenderPass::SafeDownCast(keys->Get(vtkOpenGLRenderPass::RenderPasses(), i)))
      passes.push_back(pass);
  return passes;
}

strata::VolumeCut::Camera RenderUtilities::GetCutCamera(vtkRenderer* ren)
{
  vtkCamera* camera = ren->GetActiveCamera();
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  strata::VolumeCut::Camera cutCamera;
  camera->GetPosition(cutCamera.Position);
  if (camera->GetParallelProjection())
    cutCamera.PixelsPerUnit = height / (2.0 * camera->GetParallelScale());
  else
    cutCamera.PixelsPerRadian = strata::VolumeCut::PixelsPerRadian(height, camera->GetViewAngle());
  cutCamera.UseFrustum = true;
  camera->GetFrustumPlanes(ren->GetTiledAspectRatio(), cutCamera.FrustumPlanes);
  return cutCamera;
}

void RenderUtilities::GetLights(vtkRenderer* ren,
  std::vector<float>& directions,
  std::vector<float>& colors)
{
  directions.clear();
  colors.clear();
  vtkLightCollection* lights = ren->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    if (!light->GetSwitch() || directions.size() >= 24)
      continue;
    double pos[3], fp[3];
    light->GetTransformedPosition(pos);
    light->GetTransformedFocalPoint(fp);
    double dir[3] = { pos[0] - fp[0], pos[1] - fp[1], pos[2] - fp[2] };
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (len <= 0.0)
      continue;
    const double* c = light->GetDiffuseColor();
    for (int a = 0; a < 3; ++a)
    {
      directions.push_back(static_cast<float>(dir[a] / len));
      colors.push_back(static_cast<float>(c[a] * light->GetIntensity()));
    }
  }
}

void RenderUtilities::ToColumnMajor(const double rowMajor[16], float columnMajor[16])
{
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      columnMajor[4 * c + r] = static_cast<float>(rowMajor[4 * r + c]);
}

namespace
{
template<typename Array, typename Value>
void SetOneValue(vtkFieldData* out, const char* name, Value value)
{
  if (!out)
  {
    return;
  }
  vtkNew<Array> array;
  array->SetName(name);
  array->SetNumberOfValues(1);
  array->SetValue(0, value);
  out->RemoveArray(name);
  out->AddArray(array);
}
}

void RenderUtilities::SetField(vtkFieldData* out, const char* name, double value)
{
  SetOneValue<vtkDoubleArray>(out, name, value);
}

void RenderUtilities::SetField(vtkFieldData* out, const char* name, long long value)
{
  SetOneValue<vtkTypeInt64Array>(out, name, static_cast<vtkTypeInt64>(value));
}

void RenderUtilities::TextureBarrier()
{
  // Without either extension no pass reads back what it draws (the mappers check
  // HasTextureBarrier() first), so there is nothing to order.
  if (GLEW_VERSION_4_5 || GLEW_ARB_texture_barrier)
    glTextureBarrier();
  else if (GLEW_NV_texture_barrier)
    glTextureBarrierNV();
}

bool RenderUtilities::HasTextureBarrier()
{
  return GLEW_VERSION_4_5 || GLEW_ARB_texture_barrier || GLEW_NV_texture_barrier;
}

void RenderUtilities::ClearForReadBack(vtkOpenGLState* state)
{
  vtkOpenGLState::ScopedglClearColor clearSaver(state);
  state->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
  RenderUtilities::TextureBarrier();
}

RenderUtilities::ScopedPixelStore::ScopedPixelStore(unsigned int name, int value)
  : Name(name)
{
  glGetIntegerv(name, &this->Saved);
  glPixelStorei(name, value);
}

RenderUtilities::ScopedPixelStore::~ScopedPixelStore()
{
  glPixelStorei(this->Name, this->Saved);
}

RenderUtilities::ScopedEnable::ScopedEnable(unsigned int capability)
  : Capability(capability)
  , WasEnabled(glIsEnabled(capability) == GL_TRUE)
{
  glEnable(capability);
}

RenderUtilities::ScopedEnable::~ScopedEnable()
{
  if (!this->WasEnabled)
    glDisable(this->Capability);
}
}
