// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// vtkMultiVolumeRayCastMapper's compute stage (strata::ComputeStage): the frame's choice of
// stage, its targets on image units, and one BSP fragment dispatched over its screen rectangle.
// The program is the fragment stage's composed source rewritten; the rest of a frame (inputs,
// atlas, uniforms, surface layers, the final blend) is the same in both stages.
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkMultiVolumeRayCastMapperInternals.h"

#include "StrataComputeStage.h"
#include "StrataMultiVolumeShaderComposer.h"
#include "StrataVolumeIntegrationBuffers.h"
#include "StrataVolumeSurfaceLayers.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkTextureObject.h"
#include "vtk_glew.h"

#include <vector>

void vtkMultiVolumeRayCastMapper::SetStage(Stages stage)
{
  if (stage != this->Stage)
  {
    this->Stage = stage;
    this->Modified();
  }
}

vtkMultiVolumeRayCastMapper::Stages vtkMultiVolumeRayCastMapper::GetStageInUse() const
{
  return static_cast<Stages>(this->Internals->Stage.GetStageInUse());
}

const char* vtkMultiVolumeRayCastMapper::GetStageInUseAsString() const
{
  return strata::ComputeStage::StageName(this->Internals->Stage.GetStageInUse());
}

double vtkMultiVolumeRayCastMapper::GetStageProbeRatio() const
{
  return this->Internals->Stage.GetProbeRatio();
}

void vtkMultiVolumeRayCastMapper::vtkInternals::ChooseStage(Self* self,
  vtkOpenGLRenderWindow* renWin,
  Frame& frame)
{
  const int outputs = frame.Rays + (frame.Surfaces > 0 ? 1 : 0);
  frame.Compute =
    this->Stage.Choose(self,
      renWin,
      static_cast<int>(self->Stage),
      strata::ComputeStage::FirstImageUnit + outputs) == strata::ComputeStage::Compute;
}

void vtkMultiVolumeRayCastMapper::vtkInternals::BindComputeTargets(
  strata::VolumeIntegrationBuffers& buffers,
  const Frame& frame,
  bool progress)
{
  for (int r = 0; r < frame.Rays; ++r)
    glBindImageTexture(strata::ComputeStage::FirstImageUnit + r,
      buffers.GetAccumulation(r)->GetHandle(),
      0,
      GL_FALSE,
      0,
      GL_READ_WRITE,
      GL_RGBA32F);
  vtkTextureObject* surfaces = this->SurfaceLayers.GetProgress();
  if (progress && surfaces)
    glBindImageTexture(strata::ComputeStage::FirstImageUnit + frame.Rays,
      surfaces->GetHandle(),
      0,
      GL_FALSE,
      0,
      GL_READ_WRITE,
      GL_RGBA32F);
}

void vtkMultiVolumeRayCastMapper::vtkInternals::UnbindComputeTargets(const Frame& frame)
{
  for (int r = 0; r <= frame.Rays; ++r)
    glBindImageTexture(
      strata::ComputeStage::FirstImageUnit + r, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
}

void vtkMultiVolumeRayCastMapper::vtkInternals::DispatchFragment(vtkShaderProgram* program,
  int f,
  const Frame& frame)
{
  const auto& vertices = this->Geometry.GetTree().GetFragment(f).Vertices;
  std::vector<double> points;
  points.reserve(3 * vertices.size());
  for (const auto& v : vertices)
    points.insert(points.end(), { v[0], v[1], v[2] });
  const int size[2] = { frame.Viewport[2], frame.Viewport[3] };
  int rect[4];
  // Sub-pixel rays reach half a pixel diagonal beyond the centres (the fragment stage dilates
  // the outline by 1.5 pixels for them).
  if (!strata::ComputeStage::ScreenRect(frame.LocalToClip,
        points.data(),
        static_cast<int>(vertices.size()),
        size,
        frame.Rays > 1 ? 2.0 : 0.0,
        rect))
    return;
  // The integration buffers sit at (0, 0) of their textures, as the fragment stage's viewport.
  const int origin[2] = { 0, 0 };
  strata::ComputeStage::Dispatch(program, rect, origin);
  // The next fragment blends onto what this one stored (image loads), reads its opacity, the
  // surface progress or the reduction state (texel fetches), and so does the final blend.
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}
