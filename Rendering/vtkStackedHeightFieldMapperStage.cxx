// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// vtkStackedHeightFieldMapper's compute stage (strata::ComputeStage): the frame's choice of
// stage, and the pass as one dispatch over the box's screen rectangle whose staged colours and
// depths one fragment pass resolves into the frame buffer. The program is the fragment stage's
// composed source rewritten; uniforms, textures and feedback are the same in both stages.
#include "vtkStackedHeightFieldMapper.h"
#include "vtkStackedHeightFieldMapperInternals.h"

#include "StrataComputeStage.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>

void vtkStackedHeightFieldMapper::SetStage(Stages stage)
{
  if (stage != this->Stage)
  {
    this->Stage = stage;
    this->Modified();
  }
}

vtkStackedHeightFieldMapper::Stages vtkStackedHeightFieldMapper::GetStageInUse() const
{
  return static_cast<Stages>(this->Internals->Stage.GetStageInUse());
}

const char* vtkStackedHeightFieldMapper::GetStageInUseAsString() const
{
  return strata::ComputeStage::StageName(this->Internals->Stage.GetStageInUse());
}

double vtkStackedHeightFieldMapper::GetStageProbeRatio() const
{
  return this->Internals->Stage.GetProbeRatio();
}

void vtkStackedHeightFieldMapper::vtkInternals::ChooseStage(Self* self,
  vtkOpenGLRenderWindow* renWin,
  Frame& frame)
{
  strata::HeightFieldShaderComposer::Key key;
  key.Translucent = frame.Translucent;
  const strata::ComputeStage::Outputs outputs =
    strata::HeightFieldShaderComposer::GetComputeOutputs(key);
  const int images = strata::ComputeStage::DepthImageUnit(outputs) + 1;
  frame.Compute = this->Stage.Choose(self, renWin, static_cast<int>(self->Stage), images) ==
                  strata::ComputeStage::Compute;
}

void vtkStackedHeightFieldMapper::vtkInternals::DrawCompute(vtkOpenGLRenderWindow* renWin,
  vtkShaderProgram* program,
  const Frame& frame,
  bool writeDepth)
{
  // The box the fragment stage rasterises, in grid space (cells and heights).
  const double gx = this->NX - 1, gy = this->NY - 1;
  const bool range = this->ZRange[0] <= this->ZRange[1];
  const double z0 = range ? this->ZRange[0] : 0.0, z1 = range ? this->ZRange[1] : 0.0;
  const double slack = 1e-5 * std::max({ 1.0, std::abs(z0), std::abs(z1) });
  double corners[24];
  for (int i = 0; i < 8; ++i)
  {
    corners[3 * i] = (i & 1) ? gx : 0.0;
    corners[3 * i + 1] = (i & 2) ? gy : 0.0;
    corners[3 * i + 2] = (i & 4) ? z1 + slack : z0 - slack;
  }
  const int size[2] = { frame.Viewport[2], frame.Viewport[3] };
  int rect[4];
  if (!strata::ComputeStage::ScreenRect(frame.GridToClip, corners, 8, size, 0.0, rect))
    return;
  // A peel draws into its own buffers at (0, 0); the renderer's pass at its viewport's corner.
  const int origin[2] = { frame.Peel ? 0 : frame.Viewport[0], frame.Peel ? 0 : frame.Viewport[1] };
  const strata::HeightFieldShaderComposer::Key& key = this->LastKey;
  const strata::ComputeStage::Outputs outputs =
    strata::HeightFieldShaderComposer::GetComputeOutputs(key);
  this->Staging.Bind(renWin, size[0], size[1], outputs);
  strata::ComputeStage::Dispatch(program, rect, origin);
  this->Staging.Unbind();
  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable cullSaver(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglEnableDisable depthSaver(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  state->vtkglDisable(GL_CULL_FACE);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthMask(writeDepth ? GL_TRUE : GL_FALSE);
  // Resolve's barrier makes the images' stores visible to its texel fetches.
  this->Staging.Resolve(renWin, rect, origin);
}
