// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "vtkMultiVolumeRayCastMapper.h"
#include "vtkMultiVolumeRayCastMapperInternals.h"

#include "StrataBrickAtlasAllocator.h"
#include "StrataBrickAtlasFormat.h"
#include "StrataBrickAtlasTexture.h"
#include "StrataComputeStage.h"
#include "StrataFeedbackBuffer.h"
#include "StrataFeedbackReduction.h"
#include "StrataGraphicsResources.h"
#include "StrataMultiVolumeInput.h"
#include "StrataMultiVolumeShaderComposer.h"
#include "StrataPagePoolFile.h"
#include "StrataRenderUtilities.h"
#include "StrataVolumeBrickTree.h"
#include "StrataVolumeFragmentGeometry.h"
#include "StrataVolumeIntegrationBuffers.h"
#include "StrataVolumePager.h"
#include "StrataVolumeSurfaceLayers.h"
#include "vtkPagePoolProtocol.h"

#include "vtkCamera.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkInformationStringKey.h"
#include "vtkInformationStringVectorKey.h"
#include "vtkIntArray.h"
#include "vtkLightCollection.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiVolume.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTextureUnitManager.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <set>

using namespace vtkMultiVolumeRayCastMapperFrame;

namespace
{
constexpr int MaxPlanes = 64;
constexpr int FeedbackLevels = strata::FeedbackReduction::MaxLevels;

// The mapper's ScalarStorage in the atlas format's terms.
strata::BrickAtlasFormat::Storage AtlasStorage(vtkMultiVolumeRayCastMapper::ScalarStorages storage)
{
  switch (storage)
  {
    case vtkMultiVolumeRayCastMapper::ScalarStorages::Normalized16:
      return strata::BrickAtlasFormat::Storage::Normalized16;
    case vtkMultiVolumeRayCastMapper::ScalarStorages::Native:
      return strata::BrickAtlasFormat::Storage::Native;
    default:
      return strata::BrickAtlasFormat::Storage::Float32;
  }
}

bool IsReduced(int mode)
{
  return mode == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ||
         mode == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND ||
         mode == vtkVolumeMapper::AVERAGE_INTENSITY_BLEND ||
         mode == vtkVolumeMapper::ADDITIVE_BLEND;
}

// The volume's coarsest level as floats when the image the reader produced is one page (the
// pager pads it into the root page).
std::vector<float> RootValues(vtkImageData* image, int brickSize, int component, int dims[3])
{
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData() ? image->GetPointData()->GetScalars() : nullptr;
  if (!scalars || dims[0] > brickSize || dims[1] > brickSize || dims[2] > brickSize ||
      scalars->GetNumberOfTuples() != vtkIdType(dims[0]) * dims[1] * dims[2])
  {
    return {};
  }
  std::vector<float> values(static_cast<size_t>(scalars->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
    values[i] = static_cast<float>(scalars->GetComponent(i, component));
  return values;
}

// Whether a BSP fragment (local frame) lies wholly outside a world box.
bool OutsideRegion(const strata::VolumeBSPTree::Fragment& fragment,
  const strata::VolumeBSPTree::Vector3& origin,
  const strata::Region& region)
{
  for (int a = 0; a < 3; ++a)
  {
    double lo = VTK_DOUBLE_MAX, hi = -VTK_DOUBLE_MAX;
    for (const auto& v : fragment.Vertices)
    {
      lo = std::min(lo, v[a] + origin[a]);
      hi = std::max(hi, v[a] + origin[a]);
    }
    if (hi < region[2 * a] || lo > region[2 * a + 1])
      return true;
  }
  return false;
}

// The longest level-0 voxel edge over the axes with voxels (strata::VolumeCut's voxel size).
double LongestVoxelEdge(const FrameVolume& e)
{
  double longest = 0.0, any = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double edge = std::sqrt(std::pow(e.IndexToWorld->GetElement(0, a), 2) +
                                  std::pow(e.IndexToWorld->GetElement(1, a), 2) +
                                  std::pow(e.IndexToWorld->GetElement(2, a), 2));
    any = std::max(any, edge);
    longest = e.Dims[a] > 1 ? std::max(longest, edge) : longest;
  }
  return longest > 0.0 ? longest : (any > 0.0 ? any : 1.0);
}
}

// --- The volumes of this frame: a vtkMultiVolume's members on their ports, or one volume; a
// page pool behind an input (vtkPagePoolProtocol) pages it, and pools fix the brick size.
bool vtkMultiVolumeRayCastMapper::vtkInternals::CollectVolumes(Self* self,
  vtkVolume* vol,
  Frame& frame)
{
  auto* multi = vtkMultiVolume::SafeDownCast(vol);
  const int count = multi ? self->GetInputCount() : 1;
  for (int port = 0; port < self->GetNumberOfInputPorts() && int(frame.Volumes.size()) < count;
       ++port)
  {
    if (self->GetNumberOfInputConnections(port) == 0)
      continue;
    vtkVolume* member = multi ? multi->GetVolume(port) : vol;
    auto* image = vtkImageData::SafeDownCast(self->GetTransformedInput(port));
    if (!member || !image || !member->GetProperty())
      continue;
    FrameVolume e;
    e.Port = port;
    e.Input = image;
    e.Property = member->GetProperty();
    e.Mode = self->GetEffectiveBlendMode(port);
    if (e.Mode == vtkVolumeMapper::SLICE_BLEND || e.Mode < 0 ||
        e.Mode > vtkVolumeMapper::SLICE_BLEND)
    {
      vtkWarningWithObjectMacro(
        self, "Blend mode " << e.Mode << " of port " << port << " is not supported: composite.");
      e.Mode = vtkVolumeMapper::COMPOSITE_BLEND;
    }
    if (!strata::MultiVolumeInput::CollectComponents(
          self, port, image, e.Property, e.Mode, e.ComponentMode, this->ComponentLimitsWarned))
      continue;
    frame.AnyReduced = frame.AnyReduced || IsReduced(e.Mode);
    image->GetDimensions(e.Dims);
    const double* o = image->GetOrigin();
    const double* s = image->GetSpacing();
    const double* d = image->GetDirectionMatrix()->GetData();
    // (The image handed over is a transformed copy: the pool is read from the input's data.)
    const vtkPagePoolProtocol::Identity pool = vtkPagePoolProtocol::GetInputPool(
      self->GetInputInformation(port, 0), self->GetInputDataObject(port, 0));
    if (pool.IsValid())
    {
      const strata::PagePoolFile* file = this->OpenPool(self, port, 0, pool);
      if (!file)
        continue;
      const strata::PagePoolFile::Header& h = file->GetHeader();
      e.Pool = pool;
      if (!this->OpenComponentPools(self, *file, e))
        continue;
      std::copy(h.Dimensions, h.Dimensions + 3, e.Dims);
      o = h.Origin;
      s = h.Spacing;
      d = h.Direction;
      const int B = file->GetPageSize();
      if (frame.AnyPooled && B != frame.BrickSize)
      {
        vtkErrorWithObjectMacro(self,
          "Paged volumes of page sizes " << frame.BrickSize << " and " << B
                                         << " cannot share one atlas.");
        return false;
      }
      frame.BrickSize = B;
      frame.AnyPooled = true;
    }
    // index -> world: prop * [D diag(spacing) | origin].
    vtkNew<vtkMatrix4x4> imageMatrix;
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
        imageMatrix->SetElement(r, c, d[3 * r + c] * s[c]);
      imageMatrix->SetElement(r, 3, o[r]);
    }
    double planes[6];
    e.Cropped = self->GetEffectiveCropping(port, planes, e.CropFlags);
    for (int a = 0; a < 3; ++a)
    {
      // Data coordinates (origin + index x spacing) to index coordinates.
      const double p0 = (planes[2 * a] - o[a]) / s[a], p1 = (planes[2 * a + 1] - o[a]) / s[a];
      e.CropLo[a] = static_cast<float>(std::min(p0, p1));
      e.CropHi[a] = static_cast<float>(std::max(p0, p1));
    }
    e.IndexToWorld = vtkSmartPointer<vtkMatrix4x4>::New();
    vtkMatrix4x4::Multiply4x4(member->GetMatrix(), imageMatrix, e.IndexToWorld);
    frame.Classification = std::max(frame.Classification, e.Property->GetMTime());
    frame.Volumes.push_back(e);
  }
  this->CloseUnusedPools(frame);
  if (!frame.AnyPooled)
    frame.BrickSize = self->BrickSize;
  // Volumes of several components in core are read from plain textures (of a float channel
  // each) unless a paged volume needs the atlas; there, each component is a volume of one
  // scalar (paged from its pool, or with its own in-core tree).
  const bool anyComponents = std::any_of(frame.Volumes.begin(),
    frame.Volumes.end(),
    [](const FrameVolume& e) { return e.ComponentMode != Components::One; });
  frame.Atlas = (self->UseBrickAtlas && !anyComponents) || frame.AnyPooled;
  // The pager's volumes: the frame's (component 0), then their components 1, 2, 3.
  for (FrameVolume& e : frame.Volumes)
    e.Channels =
      frame.Atlas ? strata::MultiVolumeShaderComposer::GetNumberOfComponents(e.ComponentMode) : 1;
  for (int c = 0; c < 4; ++c)
    for (size_t v = 0; v < frame.Volumes.size(); ++v)
      if (c < frame.Volumes[v].Channels)
      {
        frame.Volumes[v].PagerVolumes[c] = static_cast<int>(frame.PagerVolumes.size());
        frame.PagerVolumes.push_back({ static_cast<int>(v), c });
      }
  return !frame.Volumes.empty();
}

// A channel paged before and not in this frame (its port in core now, or with fewer components,
// or its pool failed) is closed, or the pager would go on drawing the old pool there.
void vtkMultiVolumeRayCastMapper::vtkInternals::CloseUnusedPools(const Frame& frame)
{
  std::set<int> paged;
  for (const FrameVolume& e : frame.Volumes)
    for (int c = 0; e.Pool.IsValid() &&
                    c < strata::MultiVolumeShaderComposer::GetNumberOfComponents(e.ComponentMode);
         ++c)
      paged.insert(strata::VolumePager::GetChannel(e.Port, c));
  for (auto it = this->ShownPools.begin(); it != this->ShownPools.end();)
  {
    if (paged.count(it->first))
    {
      ++it;
      continue;
    }
    this->Pager.ClosePool(it->first);
    this->HeldValid = false;
    it = this->ShownPools.erase(it);
  }
}

// The pool of component `component` of a paged port (`pool` names component 0's): the step of
// its series the input shows (its identity's TimeStep), and the next step in the direction of
// playback prefetched (strata::VolumePager::FollowPlayback).
const strata::PagePoolFile* vtkMultiVolumeRayCastMapper::vtkInternals::OpenPool(Self* self,
  int port,
  int component,
  const vtkPagePoolProtocol::Identity& pool)
{
  const int step = pool.TimeStep;
  const int steps = static_cast<int>(pool.Series.size());
  const int channel = strata::VolumePager::GetChannel(port, component);
  const std::string name = strata::PagePoolFormat::GetComponentFileName(pool.FileName, component);
  std::string error;
  const strata::PagePoolFile* file = this->Pager.OpenPool(channel, name, error, step);
  if (!file)
  {
    vtkErrorWithObjectMacro(
      self, "Cannot page the volume on port " << port << " from \"" << name << "\": " << error);
    return nullptr;
  }
  auto& [shown, warned] = this->ShownPools[channel];
  this->HeldValid = this->HeldValid && shown == name;
  shown = name;
  const int followed = this->Pager.FollowPlayback(channel, step, steps);
  const int next = self->PrefetchTimeSteps ? followed : -1;
  const std::string nextName =
    next >= 0 && next < steps
      ? strata::PagePoolFormat::GetComponentFileName(pool.Series[next], component)
      : std::string();
  if (!this->Pager.SetNextStep(channel, next, nextName, error) && error != warned)
    vtkWarningWithObjectMacro(self, "Cannot prefetch time step " << next << ": " << error);
  warned = error;
  return file;
}

// The pools of components 1, 2, 3 of a paged volume whose component 0 is `first`: as many as
// its input has components, each a member of `first`'s set
// (strata::PagePoolFormat::CheckComponent).
bool vtkMultiVolumeRayCastMapper::vtkInternals::OpenComponentPools(Self* self,
  const strata::PagePoolFile& first,
  const FrameVolume& e)
{
  const int count = strata::MultiVolumeShaderComposer::GetNumberOfComponents(e.ComponentMode);
  if (first.GetHeader().Components != count)
  {
    vtkErrorWithObjectMacro(self,
      "The volume on port " << e.Port << " has " << count << " components and its pool \""
                            << e.Pool.FileName << "\" " << first.GetHeader().Components << ".");
    return false;
  }
  for (int c = 1; c < count; ++c)
  {
    const strata::PagePoolFile* file = this->OpenPool(self, e.Port, c, e.Pool);
    std::string error;
    if (!file ||
        !strata::PagePoolFormat::CheckComponent(first.GetHeader(), file->GetHeader(), c, error))
    {
      if (file)
        vtkErrorWithObjectMacro(self, "Cannot page the volume on port " << e.Port << ": " << error);
      return false;
    }
  }
  return true;
}

// Feedback ranks the bricks of every volume while any is paged. It needs image load/store, and
// page ids of 32 bits: at most 62 volumes and 2^21 bricks per level (strata::FeedbackReduction).
bool vtkMultiVolumeRayCastMapper::vtkInternals::SupportsFeedback(Self* self, const Frame& frame)
{
  if (!frame.AnyPooled || !self->LevelOfDetailFeedback)
    return false;
  bool idsFit =
    static_cast<int>(frame.PagerVolumes.size()) <= strata::FeedbackReduction::MaxDataSets;
  const int B = frame.BrickSize;
  for (const auto& e : frame.Volumes)
  {
    uint64_t bricks = 1;
    for (int a = 0; a < 3; ++a)
      bricks *= e.Dims[a] <= 1 ? 1 : (static_cast<uint64_t>(e.Dims[a]) - 1 + B - 2) / (B - 1);
    idsFit = idsFit && bricks <= strata::FeedbackReduction::MaxPagesPerLevel;
  }
  const bool imageStore = GLEW_VERSION_4_2 || GLEW_ARB_shader_image_load_store;
  if ((!imageStore || !idsFit) && !this->FeedbackUnsupportedWarned)
  {
    vtkWarningWithObjectMacro(self,
      << (imageStore ? "More than 62 volumes or 2^21 bricks in a level"
                     : "No image load/store (OpenGL 4.2)")
      << ": paging without level-of-detail feedback (the screen-space cut).");
    this->FeedbackUnsupportedWarned = true;
  }
  return imageStore && idsFit;
}

// --- Per input: scalars as float, the brick tree (atlas) or plain texture, the transfer
// table; then the skip grids (cell ranges when the data change, distances when the table does).
bool vtkMultiVolumeRayCastMapper::vtkInternals::UpdateInputs(Self* self,
  vtkOpenGLRenderWindow* renWin,
  Frame& frame)
{
  for (const FrameVolume& e : frame.Volumes)
  {
    strata::MultiVolumeInput& input = this->Inputs[e.Port];
    if (!e.Pool.IsValid() && !input.HasScalarsOf(e.Input))
    {
      int cellFlag = 0;
      vtkDataArray* scalars = vtkAbstractMapper::GetScalars(
        e.Input, self->ScalarMode, self->ArrayAccessMode, self->ArrayId, self->ArrayName, cellFlag);
      if (!scalars || cellFlag)
      {
        vtkErrorWithObjectMacro(self, "Volume on port " << e.Port << " has no point scalars.");
        return false;
      }
      input.UpdateScalars(e.Input, scalars, renWin);
    }
    else if (e.Pool.IsValid() && e.ComponentMode == Components::RGBA)
      input.UpdateColorRanges(e.Input->GetPointData()->GetScalars());
    if (!e.Pool.IsValid() && frame.Atlas)
    {
      std::string error;
      const int built = input.UpdateTree(
        e.Dims, frame.BrickSize, self->ScalarStorage != Self::ScalarStorages::Float32, error);
      if (built < 0)
      {
        vtkErrorWithObjectMacro(
          self, "Cannot brick the volume on port " << e.Port << ": " << error);
        return false;
      }
      if (built > 0)
        this->Pager.InvalidateCut(); // the cut must be rebuilt with this tree
    }
    if (!frame.Atlas)
      input.UpdatePlainTexture(renWin, e.Dims, AtlasStorage(self->ScalarStorage));
    input.UpdateTransfer(renWin, e.Property);
    input.UpdateComponentTables(renWin, e.Property, e.ComponentMode);
    std::vector<double> iso;
    vtkContourValues* contours = e.Property->GetIsoSurfaceValues();
    for (int i = 0; e.Mode == vtkVolumeMapper::ISOSURFACE_BLEND && contours &&
                    i < contours->GetNumberOfContours();
         ++i)
      iso.push_back(contours->GetValue(i));
    if (iso.size() > 8)
      vtkWarningWithObjectMacro(
        self, "Port " << e.Port << " has " << iso.size() << " isovalues; the first 8 are drawn.");
    input.SetBlendMode(e.Mode, iso);
    input.UpdateGradientOpacity(renWin, e.Property);
  }
  for (const FrameVolume& e : frame.Volumes)
  {
    // Of a paged set of components, the ranges of the opacity component's pool.
    const int opacity = strata::MultiVolumeInput::GetOpacityComponent(e.ComponentMode);
    const int pool = std::max(opacity, 0);
    if (self->EmptySpaceSkipping && opacity >= 0)
      this->Inputs[e.Port].UpdateSkipGrid(
        this->Pager.GetPoolTree(strata::VolumePager::GetChannel(e.Port, pool)),
        e.Pool.FileName.empty()
          ? e.Pool.FileName
          : strata::PagePoolFormat::GetComponentFileName(e.Pool.FileName, pool),
        e.Dims,
        self->SkipCellSize,
        opacity);
  }
  return true;
}

// --- Camera, composed in double relative to the tree's local origin; the mapper's clipping
// planes (world; VTK keeps the side the normal points to) in the fragments' convention,
// dot(n, p) + w <= 0 inside, in the local frame: each fragment's ray is clipped by them like
// by its own faces, on the same sample lattice.
void vtkMultiVolumeRayCastMapper::vtkInternals::SetUpView(Self* self,
  vtkRenderer* ren,
  Frame& frame)
{
  int* vp = frame.Viewport;
  ren->GetTiledSizeAndOrigin(&vp[2], &vp[3], &vp[0], &vp[1]);
  vtkCamera* camera = ren->GetActiveCamera();
  const auto& origin = this->Geometry.GetOrigin();
  vtkNew<vtkMatrix4x4> worldToClip;
  worldToClip->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1));
  frame.ToWorld->Identity();
  for (int i = 0; i < 3; ++i)
    frame.ToWorld->SetElement(i, 3, origin[i]);
  vtkMatrix4x4::Multiply4x4(worldToClip, frame.ToWorld, frame.LocalToClip);
  vtkMatrix4x4::Invert(frame.LocalToClip, frame.ClipToLocal);
  for (int i = 0; self->ClippingPlanes && i < self->ClippingPlanes->GetNumberOfItems(); ++i)
  {
    vtkPlane* plane = self->ClippingPlanes->GetItem(i);
    double n[3], o[3];
    plane->GetNormal(n);
    plane->GetOrigin(o);
    double w = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      frame.ClipPlanes.push_back(static_cast<float>(-n[c]));
      w += n[c] * (o[c] - origin[c]);
    }
    frame.ClipPlanes.push_back(static_cast<float>(w));
  }
  for (int a = 0; self->Region.IsSet() && a < 6; ++a)
  {
    // Face a: x_(a/2) >= Region[a] for even a, <= for odd a.
    const double sign = (a % 2) ? 1.0 : -1.0;
    for (int c = 0; c < 3; ++c)
      frame.RegionPlanes.push_back(c == a / 2 ? static_cast<float>(sign) : 0.f);
    frame.RegionPlanes.push_back(static_cast<float>(-sign * (self->Region[a] - origin[a / 2])));
  }
  std::copy(worldToClip->GetData(), worldToClip->GetData() + 16, frame.View.begin());
  frame.View[16] = vp[2];
  frame.View[17] = vp[3];
  frame.Moved = frame.View != this->LastView;
  this->LastView = frame.View;
  for (auto& e : frame.Volumes)
  {
    // local -> index: IndexToWorld^-1 (local + origin), once per frame for all fragments.
    vtkNew<vtkMatrix4x4> worldToIndex, localToIndex;
    vtkMatrix4x4::Invert(e.IndexToWorld, worldToIndex);
    vtkMatrix4x4::Multiply4x4(worldToIndex, frame.ToWorld, localToIndex);
    strata::RenderUtilities::ToColumnMajor(localToIndex->GetData(), e.LocalToIndex);
  }
}

// --- Brick atlas: the cut through all volumes' octrees for this camera (strata::VolumePager),
// bricks uploaded into the shared atlas, one index texture per volume. Held (HoldCut): the
// last render's cut, atlas and index textures as they are.
bool vtkMultiVolumeRayCastMapper::vtkInternals::UpdateAtlas(Self* self,
  vtkRenderer* ren,
  Frame& frame)
{
  std::vector<strata::VolumePager::Volume> volumes;
  for (const std::array<int, 2>& pagerVolume : frame.PagerVolumes)
  {
    // (Not a structured binding: C++17 lambdas cannot capture one, clang says so.)
    const FrameVolume& e = frame.Volumes[pagerVolume[0]];
    const int c = pagerVolume[1];
    strata::VolumePager::Volume v;
    v.Port = strata::VolumePager::GetChannel(e.Port, c);
    v.Tree = !e.Pool.IsValid() ? this->Inputs[e.Port].GetTree(c) : nullptr;
    std::copy(e.IndexToWorld->GetData(), e.IndexToWorld->GetData() + 16, v.IndexToWorld);
    const strata::MultiVolumeInput* input = &this->Inputs[e.Port];
    const Components mode = e.ComponentMode;
    v.Opacity = [input, mode, c](double lo, double hi)
    { return input->ComponentVisibility(mode, c, lo, hi); };
    // Pre-integrated segments read both ends: no end may fall on an empty brick's stand-in
    // next to visible data.
    v.Halo = self->Classification != Classifications::PostClassification;
    if (e.Pool.IsValid())
    {
      // The reader's coarsest level is the root page: the pager takes it without a read.
      vtkImageData* image = e.Input;
      const int B = frame.BrickSize;
      v.RootValues = [image, B, c](int dims[3]) { return RootValues(image, B, c, dims); };
    }
    volumes.push_back(v);
  }
  const bool halo = !volumes.empty() && volumes[0].Halo;
  if (halo != this->CutHalo || self->Region != this->CutRegion)
    this->Pager.InvalidateCut();
  this->CutHalo = halo;
  this->CutRegion = self->Region;
  if (!this->Atlas.IsAllocated())
    this->Pager.InvalidateCut();
  if (this->Max3DTexture == 0)
  {
    GLint max3D = 2048;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3D);
    this->Max3DTexture = max3D;
  }
  bool rebuilt = false;
  std::string error;
  this->Pager.SetAtlasStorage(AtlasStorage(self->ScalarStorage));
  if (!this->Pager.SetVolumes(
        volumes, frame.BrickSize, self->AtlasBudget, this->Max3DTexture, rebuilt, error))
  {
    vtkErrorWithObjectMacro(self, << error);
    return false;
  }
  if (rebuilt)
    this->Atlas.Allocate(this->Pager.GetAtlas().GetTextureSize(), this->Pager.GetAtlasType());
  frame.Hold = self->HoldCut && this->HeldValid && !rebuilt;
  if (frame.Hold)
    return true;
  this->HeldValid = false;
  if (!this->UpdateCut(self, ren, frame))
    return false;
  for (size_t v = 0; v < volumes.size(); ++v)
  {
    std::vector<uint16_t> table;
    this->Pager.BuildIndexTable(static_cast<int>(v), table);
    this->Atlas.SetIndex(volumes[v].Port,
      this->Pager.GetTree(static_cast<int>(v))->GetLevelBricks(0),
      frame.BrickSize,
      table);
  }
  this->ResidentBricks = this->Pager.GetAtlas().GetNumberOfUsedSlots();
  this->HeldValid = true;
  return true;
}

// The frame's cut: feedback demand from the last frame's buffer (kept while the camera is
// still, halved for each frame it moves), roots, the paged bricks in RAM, then the uploads.
bool vtkMultiVolumeRayCastMapper::vtkInternals::UpdateCut(Self* self,
  vtkRenderer* ren,
  Frame& frame)
{
  bool feedbackCurrent = false;
  if (this->Pager.PrepareDemand(frame.Feedback, frame.Moved))
    this->Feedback.Drop(); // written for another cut
  if (frame.Feedback && this->Feedback.IsPending())
  {
    // Feedback of another view, or of other transfer functions or weights (which may have
    // shown bricks it never saw), is used but is not current: the cut has not converged.
    const bool sameView =
      this->FeedbackView == frame.View && this->FeedbackClassification == frame.Classification;
    const auto start = std::chrono::steady_clock::now();
    std::vector<strata::FeedbackReduction::Entry> asked;
    this->Feedback.SetUseOpenCL(self->FeedbackOpenCL);
    this->Feedback.Read(asked);
    this->Pager.AddFeedback(asked);
    this->Paging.FeedbackOpenCL = this->Feedback.GetLastReadUsedOpenCL();
    this->Paging.FeedbackMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    feedbackCurrent = sameView;
  }
  strata::VolumePager::Settings settings;
  settings.CacheBudgetMiB = self->PageCacheBudget;
  settings.PagesPerFrame = self->PagesPerFrame;
  settings.Prefetch = self->Prefetch;
  settings.Feedback = frame.Feedback;
  settings.ErrorThreshold = self->LevelOfDetailThreshold;
  std::vector<strata::VolumeCut::Upload> uploads;
  std::string error;
  strata::VolumeCut::Camera cutCamera = strata::RenderUtilities::GetCutCamera(ren);
  cutCamera.Region = self->Region;
  // One step past the exit face (the voxel of each node's level covers gradient taps and an
  // automatic step, half a voxel).
  cutCamera.RegionMargin = self->AutoAdjustSampleDistances ? 0.0 : self->SampleDistance;
  const int missing = this->Pager.Update(cutCamera, settings, feedbackCurrent, uploads, error);
  if (missing < 0)
  {
    vtkErrorWithObjectMacro(self, << error);
    return false;
  }
  for (const std::string& failure : this->Pager.TakeNewFailures())
    vtkErrorWithObjectMacro(self, << failure << "; showing the coarser level.");
  const std::string clamped = this->Pager.TakeBudgetWarning();
  if (!clamped.empty())
    vtkWarningWithObjectMacro(self, << clamped);
  static_cast<strata::VolumePager::Statistics&>(this->Paging) = this->Pager.GetStatistics();
  if (missing > 0)
    vtkWarningWithObjectMacro(
      self, << missing << " bricks found no atlas slot: raise AtlasBudget.");
  this->UploadBricks(self, uploads, frame);
  return true;
}

void vtkMultiVolumeRayCastMapper::vtkInternals::UploadBricks(Self* self,
  const std::vector<strata::VolumeCut::Upload>& uploads,
  const Frame& frame)
{
  const int B = frame.BrickSize;
  const size_t voxels = size_t(B) * B * B;
  const auto atlasType = this->Pager.GetAtlasType();
  const int texel = strata::BrickAtlasFormat::GetTexelSize(atlasType);
  std::vector<float> scratch;
  // Float atlases take the values as they are; normalised ones their encoding.
  const bool encode = strata::BrickAtlasFormat::IsNormalized(atlasType);
  std::vector<unsigned char> texels(encode ? voxels * texel : 0);
  this->Atlas.BeginUploads();
  this->Paging.BytesUploaded = 0;
  for (const auto& u : uploads)
  {
    const float* data = this->Pager.GetBrick(u, scratch);
    if (!data)
    {
      vtkErrorWithObjectMacro(self, "Brick " << u.Node << " entered the cut without its page.");
      const FrameVolume& e = frame.Volumes[frame.PagerVolumes[u.Volume][0]];
      scratch.assign(voxels,
        static_cast<float>(this->Inputs[e.Port].GetComponentEmptyScalar(
          e.ComponentMode, frame.PagerVolumes[u.Volume][1])));
      data = scratch.data();
    }
    if (encode)
      strata::BrickAtlasFormat::Encode(
        data, voxels, atlasType, this->Pager.GetVolumeType(u.Volume), texels.data());
    this->Atlas.UploadBrick(this->Pager.GetAtlas().GetSlotPosition(u.Slot),
      B,
      encode ? static_cast<const void*>(texels.data()) : data);
    this->Paging.BytesUploaded += static_cast<long long>(voxels * texel);
  }
  this->Atlas.EndUploads();
}

// --- The sample distance, and the pre-integration tables (rebuilt only when a transfer
// function or the step changed).
void vtkMultiVolumeRayCastMapper::vtkInternals::UpdatePreIntegration(Self* self,
  vtkOpenGLRenderWindow* renWin,
  Frame& frame)
{
  frame.SampleDistance = self->SampleDistance;
  // The shaders divide by the step: a step of 0 (or less) would make every ray NaN.
  const bool valid = self->SampleDistance > 0.0 && std::isfinite(self->SampleDistance);
  if (!valid && !this->SampleDistanceWarned)
  {
    vtkErrorWithObjectMacro(self,
      "SampleDistance " << self->SampleDistance
                        << " is not a positive length: half the smallest voxel edge is used.");
    this->SampleDistanceWarned = true;
  }
  if (self->AutoAdjustSampleDistances || !valid)
  {
    // Half the smallest voxel edge of any volume, in world units.
    frame.SampleDistance = VTK_DOUBLE_MAX;
    for (const auto& e : frame.Volumes)
      for (int c = 0; c < 3; ++c)
      {
        const double len = std::sqrt(std::pow(e.IndexToWorld->GetElement(0, c), 2) +
                                     std::pow(e.IndexToWorld->GetElement(1, c), 2) +
                                     std::pow(e.IndexToWorld->GetElement(2, c), 2));
        frame.SampleDistance = std::min(frame.SampleDistance, 0.5 * len);
      }
  }
  if (self->Classification == Classifications::PostClassification)
    return;
  for (const auto& e : frame.Volumes)
    this->Inputs[e.Port].UpdatePreIntegration(
      renWin, self->Classification, self->PreIntegrationTableSize, frame.SampleDistance);
}

// --- Feedback: one R32UI texel per FeedbackScale x FeedbackScale pixels, cleared to 0 (no
// page), and its R32F cost, on image units 0 and 1 for the whole frame (a held render adds to
// what the frame's earlier passes wrote); and what the rays need to name a page and, with a
// footprint, to ask for a level.
void vtkMultiVolumeRayCastMapper::vtkInternals::PrepareFeedback(Self* self,
  vtkRenderer* ren,
  vtkOpenGLRenderWindow* renWin,
  Frame& frame)
{
  // A held frame keeps the reports so far, unless the images were just (re)made: their texels
  // are undefined then (zero on llvmpipe, old memory on a GPU), and imageLoad compares with them.
  const bool allocated =
    this->Feedback.Allocate(renWin, frame.Viewport[2], frame.Viewport[3], self->FeedbackScale);
  if (allocated || !frame.Hold)
    this->Feedback.Clear(renWin);
  this->Feedback.BindImages(true);
  // The size of one pixel at distance r from the eye, times the error threshold: what a voxel
  // of the wanted level may cover.
  vtkCamera* camera = ren->GetActiveCamera();
  const double tau = self->LevelOfDetailThreshold;
  const int height = frame.Viewport[3];
  if (camera->GetParallelProjection())
    frame.FeedbackFootprint[0] =
      static_cast<float>(tau * 2.0 * camera->GetParallelScale() / height);
  else
    frame.FeedbackFootprint[1] =
      static_cast<float>(tau / strata::VolumeCut::PixelsPerRadian(height, camera->GetViewAngle()));
  const double* eye = camera->GetPosition();
  const auto& origin = this->Geometry.GetOrigin();
  for (int c = 0; c < 3; ++c)
    frame.FeedbackEye[c] = static_cast<float>(eye[c] - origin[c]);
  frame.FeedbackLod.resize(frame.Volumes.size());
  frame.LevelBricks.resize(frame.Volumes.size());
  for (size_t v = 0; v < frame.Volumes.size(); ++v)
  {
    const strata::VolumeBrickTree* tree = this->Pager.GetTree(static_cast<int>(v));
    frame.FeedbackLod[v] = { static_cast<float>(1.0 / LongestVoxelEdge(frame.Volumes[v])),
      static_cast<float>(std::min(tree->GetNumberOfLevels(), FeedbackLevels) - 1) };
    frame.LevelBricks[v].assign(3 * FeedbackLevels, 1);
    for (int l = 0; l < tree->GetNumberOfLevels() && l < FeedbackLevels; ++l)
      std::copy(
        tree->GetLevelBricks(l), tree->GetLevelBricks(l) + 3, frame.LevelBricks[v].begin() + 3 * l);
  }
}

// --- Fragments in order, each with the program for its volumes, composited into the
// integration buffers; then the feedback is queued for the next frame.
void vtkMultiVolumeRayCastMapper::vtkInternals::DrawFragments(Self* self,
  vtkRenderer* ren,
  vtkOpenGLRenderWindow* renWin,
  Frame& frame)
{
  vtkOpenGLState* state = renWin->GetState();
  this->Buffers.Bind(renWin, frame.Rays, this->SurfaceLayers.GetProgress());
  vtkOpenGLState::ScopedglViewport viewportSaver(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendSaver(state);
  vtkOpenGLState::ScopedglEnableDisable blendEnable(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthEnable(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cullEnable(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  // VTK leaves its scissor on the renderer's window rectangle; the buffers sit at (0, 0) of
  // their own textures, so a renderer off the window's origin lost part of its volumes.
  vtkOpenGLState::ScopedglEnableDisable scissorEnable(state, GL_SCISSOR_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglViewport(0, 0, frame.Viewport[2], frame.Viewport[3]);
  // The fragments read these buffers back (prior opacity, surface progress) from the first
  // draw on, so the clear is followed by a texture barrier.
  strata::RenderUtilities::ClearForReadBack(state);
  if (frame.Compute)
    this->BindComputeTargets(this->Buffers, frame, true);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglEnable(GL_BLEND);
  if (frame.FrontToBack)
    state->vtkglBlendFuncSeparate(GL_ONE_MINUS_DST_ALPHA, GL_ONE, GL_ONE_MINUS_DST_ALPHA, GL_ONE);
  else
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  // Back faces: every ray through a convex fragment crosses exactly one, also when the camera
  // is inside it; depth clamping keeps faces beyond the far plane.
  state->vtkglEnable(GL_CULL_FACE);
  state->vtkglCullFace(GL_FRONT);
  const strata::RenderUtilities::ScopedEnable depthClamp(GL_DEPTH_CLAMP);

  std::vector<int> order;
  vtkCamera* camera = ren->GetActiveCamera();
  const double* eye = camera->GetPosition();
  const double* dop = camera->GetDirectionOfProjection();
  const strata::VolumeBSPTree::Vector3 eyeV = { eye[0], eye[1], eye[2] };
  const strata::VolumeBSPTree::Vector3 dirV = { dop[0], dop[1], dop[2] };
  const bool parallel = camera->GetParallelProjection() != 0;
  if (frame.FrontToBack)
    this->Geometry.GetTree().SortFrontToBack(eyeV, parallel, dirV, order);
  else
    this->Geometry.GetTree().SortBackToFront(eyeV, parallel, dirV, order);
  this->LastKeys.clear();
  this->LastReduceKeys.clear();
  this->LastFragments = 0;
  if (frame.Feedback)
    this->PrepareFeedback(self, ren, renWin, frame);
  if (frame.AnyReduced)
  {
    this->Buffers.Unbind(renWin);
    this->DrawReductions(self, renWin, order, frame);
    this->Buffers.Bind(renWin, frame.Rays, this->SurfaceLayers.GetProgress());
    state->vtkglViewport(0, 0, frame.Viewport[2], frame.Viewport[3]);
    state->vtkglEnable(GL_BLEND);
    if (frame.Compute)
      this->BindComputeTargets(this->Buffers, frame, true);
  }
  for (int f : order)
  {
    if (!this->DrawFragment(self, renWin, f, frame))
      break;
  }
  state->vtkglCullFace(GL_BACK); // VTK's default; its actors set their own
  if (frame.Compute)
    UnbindComputeTargets(frame);
  this->Buffers.Unbind(renWin);
  if (frame.Feedback)
  {
    // Copied into the pixel buffer now, mapped at the next frame: no wait for the GPU here.
    this->Feedback.UnbindImages();
    this->Feedback.Queue(renWin);
    this->FeedbackView = frame.View;
    this->FeedbackClassification = frame.Classification;
  }
}

// --- Reductions: each MIP, MinIP, average or additive volume alone, fragment by fragment
// into its layer buffers (one per ray, cleared to "not met"), each fragment reading what the
// ones before left under a texture barrier; the integration then reads them as layers.
void vtkMultiVolumeRayCastMapper::vtkInternals::DrawReductions(Self* self,
  vtkOpenGLRenderWindow* renWin,
  const std::vector<int>& order,
  Frame& frame)
{
  vtkOpenGLState* state = renWin->GetState();
  state->vtkglDisable(GL_BLEND);
  for (size_t v = 0; v < frame.Volumes.size(); ++v)
  {
    if (!IsReduced(frame.Volumes[v].Mode))
      continue;
    strata::VolumeIntegrationBuffers& layer = this->LayerBuffers[frame.Volumes[v].Port];
    layer.Bind(renWin, frame.Rays);
    state->vtkglViewport(0, 0, frame.Viewport[2], frame.Viewport[3]);
    // The first fragment reads the cleared state back ("not met"): a barrier after the clear.
    strata::RenderUtilities::ClearForReadBack(state);
    if (frame.Compute)
      this->BindComputeTargets(layer, frame, false);
    for (int f : order)
    {
      const auto& boxes = this->Geometry.GetTree().GetFragment(f).BoxIndices;
      if (std::find(boxes.begin(), boxes.end(), static_cast<int>(v)) != boxes.end() &&
          !this->DrawFragment(self, renWin, f, frame, static_cast<int>(v)))
        break;
    }
    layer.Unbind(renWin);
  }
}

// How volume v's texels decode (strata::BrickAtlasFormat): the atlas's type or its plain texture's.
bool vtkMultiVolumeRayCastMapper::vtkInternals::GetDecode(const Frame& frame,
  int v,
  float decode[2]) const
{
  const strata::MultiVolumeInput& input = this->Inputs.at(frame.Volumes[v].Port);
  const auto texels = frame.Atlas ? this->Pager.GetAtlasType() : input.GetPlainTextureType();
  const auto values = frame.Atlas ? this->Pager.GetVolumeType(v) : input.GetScalarType();
  double scale = 1.0, offset = 0.0;
  strata::BrickAtlasFormat::GetDecode(texels, values, scale, offset);
  decode[0] = static_cast<float>(scale);
  decode[1] = static_cast<float>(offset);
  return strata::BrickAtlasFormat::IsNormalized(texels);
}

// The program's features for `volumes` (frame indices) of a fragment, or for the reduction
// pass of volumes[0].
strata::MultiVolumeShaderComposer::FragmentKey vtkMultiVolumeRayCastMapper::vtkInternals::MakeKey(
  Self* self,
  const std::vector<int>& volumes,
  bool reduce,
  const Frame& frame) const
{
  strata::MultiVolumeShaderComposer::FragmentKey key;
  key.Volumes = static_cast<int>(volumes.size());
  bool components = false, unskipped = false;
  for (int v : volumes)
  {
    const FrameVolume& e = frame.Volumes[v];
    const bool one = e.ComponentMode == Components::One;
    components = components || !one;
    unskipped = unskipped || strata::MultiVolumeInput::GetOpacityComponent(e.ComponentMode) < 0;
    key.Shaded.push_back(one && frame.Lit && e.Property->GetShade(0) != 0 && !IsReduced(e.Mode));
    key.Modes.push_back(e.Mode);
    key.Cropped.push_back(e.Cropped);
    key.GradientOpacity.push_back(one && !reduce && e.Mode == vtkVolumeMapper::COMPOSITE_BLEND &&
                                  self->Classification == Classifications::PostClassification &&
                                  this->Inputs.at(e.Port).HasGradientOpacity());
    key.ComponentModes.push_back(e.ComponentMode);
    int silent = 0; // the components of weight 0 (all weigh 1 unless independent)
    for (int c = 1; c < strata::MultiVolumeShaderComposer::GetNumberOfComponents(e.ComponentMode);
         ++c)
      silent |= this->Inputs.at(e.Port).ShowsComponent(c) ? 0 : 1 << c;
    key.SilentComponents.push_back(silent);
    float decode[2];
    key.Normalized.push_back(this->GetDecode(frame, v, decode));
  }
  if (!components)
  {
    key.ComponentModes.clear(); // one key for scenes of one-component volumes
    key.SilentComponents.clear();
  }
  key.Reduce = reduce;
  key.Surfaces = reduce ? 0 : frame.Surfaces;
  // A fragment with a volume of several components is post-classified (its components have no
  // pre-integration tables) and not skipped with independent ones (no skip grid for their mix).
  key.Classification = components ? Classifications::PostClassification : self->Classification;
  key.FrontToBack = reduce || frame.FrontToBack;
  key.Barrier = !reduce && frame.Barrier;
  key.Rays = frame.Rays;
  key.Coherent = self->RayCoherence && frame.Rays > 1 && !frame.AnyReduced;
  key.Atlas = frame.Atlas;
  key.Skipping =
    self->EmptySpaceSkipping && !unskipped &&
    !(reduce && frame.Volumes[volumes[0]].Mode == vtkVolumeMapper::AVERAGE_INTENSITY_BLEND);
  // Feedback comes from the volumes a program samples (a layer's bricks report in its pass).
  bool samples = reduce;
  for (int v : volumes)
    samples = samples || !IsReduced(frame.Volumes[v].Mode);
  key.Feedback = frame.Feedback && samples;
  key.Footprint = frame.Footprint && samples;
  return key;
}

// One fragment: its program (the composer's, by the fragment's features), its uniforms and
// textures, the draw, and the barriers the next fragment needs; with `reduce` >= 0 the
// reduction pass of that volume. False: stop drawing.
bool vtkMultiVolumeRayCastMapper::vtkInternals::DrawFragment(Self* self,
  vtkOpenGLRenderWindow* renWin,
  int f,
  Frame& frame,
  int reduce)
{
  const auto& frag = this->Geometry.GetTree().GetFragment(f);
  // The reduction pass of one volume draws that volume alone; the composite pass the
  // fragment's own (referenced, not copied: this runs per fragment and pass).
  std::vector<int> reduced;
  if (reduce >= 0)
    reduced.push_back(reduce);
  const std::vector<int>& volumes = reduce >= 0 ? reduced : frag.BoxIndices;
  const int k = static_cast<int>(volumes.size());
  if (k == 0 || this->Geometry.GetVertexCount(f) == 0)
    return true;
  if (self->Region.IsSet() && OutsideRegion(frag, this->Geometry.GetOrigin(), self->Region))
    return true; // another process's box
  if (static_cast<int>(frag.Planes.size() + frame.ClipPlanes.size() / 4) > MaxPlanes)
  {
    vtkErrorWithObjectMacro(self,
      "A BSP fragment has " << frag.Planes.size() << " faces and there are "
                            << frame.ClipPlanes.size() / 4 << " clipping planes; at most "
                            << MaxPlanes << " in all are supported.");
    return true;
  }
  const strata::MultiVolumeShaderComposer::FragmentKey key =
    this->MakeKey(self, volumes, reduce >= 0, frame);
  std::string log;
  vtkShaderProgram* program = frame.Compute ? this->Composer.ReadyComputeProgram(renWin, key, log)
                                            : this->Composer.ReadyFragmentProgram(renWin, key);
  if (!program)
  {
    vtkErrorWithObjectMacro(self,
      "The multi-volume " << (frame.Compute ? "compute" : "fragment") << " shader for " << k
                          << " volumes did not compile or link. " << log);
    return false;
  }
  if (reduce >= 0)
    this->LastReduceKeys[frame.Volumes[reduce].Mode] = key;
  else
    this->LastKeys[k] = key;
  if (!frame.Compute)
    this->Geometry.Bind(program);
  this->SetFragmentUniforms(self, program, f, volumes, key, frame);
  vtkTextureObject* depth = this->Buffers.GetSceneDepth();
  depth->Activate();
  program->SetUniformi("uSceneDepth", depth->GetTextureUnit());
  this->SurfaceLayers.SetUniforms(program);
  // Read back: this pass's own buffers (early termination, or a reduction's state so far),
  // and the layers of the reduced volumes of the fragment.
  std::vector<vtkTextureObject*> readBack;
  for (int r = 0; (key.Barrier || key.Reduce) && r < frame.Rays; ++r)
  {
    strata::VolumeIntegrationBuffers& target =
      key.Reduce ? this->LayerBuffers[frame.Volumes[reduce].Port] : this->Buffers;
    readBack.push_back(target.GetAccumulation(r));
    readBack.back()->Activate();
    program->SetUniformi(
      ("uAccumulation" + std::to_string(r)).c_str(), readBack.back()->GetTextureUnit());
  }
  for (int i = 0; !key.Reduce && i < k; ++i)
  {
    const FrameVolume& e = frame.Volumes[volumes[i]];
    for (int r = 0; IsReduced(e.Mode) && r < frame.Rays; ++r)
    {
      readBack.push_back(this->LayerBuffers[e.Port].GetAccumulation(r));
      readBack.back()->Activate();
      program->SetUniformi(("uLayer" + std::to_string(i) + "_" + std::to_string(r)).c_str(),
        readBack.back()->GetTextureUnit());
    }
  }
  vtkTextureUnitManager* units = renWin->GetTextureUnitManager();
  std::vector<int> rawUnits;
  if (frame.Atlas)
  {
    const int unit = units->Allocate();
    rawUnits.push_back(unit);
    renWin->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_3D, this->Atlas.GetAtlasName());
    program->SetUniformi("uAtlas", unit);
    const auto& size = this->Atlas.GetSize();
    const float atlasSize[3] = { float(size[0]), float(size[1]), float(size[2]) };
    program->SetUniform3f("uAtlasSize", atlasSize);
    program->SetUniformf("uBrickSize", static_cast<float>(frame.BrickSize));
  }
  std::vector<strata::MultiVolumeInput::Binding> bindings(k);
  for (int i = 0; i < k; ++i)
  {
    const int v = volumes[i];
    const FrameVolume& e = frame.Volumes[v];
    strata::MultiVolumeInput::Binding& b = bindings[i];
    b.Classification = key.Classification;
    b.BlendMode = e.Mode;
    b.CropLo = e.Cropped ? e.CropLo : nullptr;
    b.CropHi = e.CropHi;
    b.CropFlags = e.CropFlags;
    b.GradientOpacity = key.GradientOpacity[i];
    b.AverageRange = self->GetAverageIPScalarRange();
    b.Atlas = frame.Atlas;
    b.IndexTexture = frame.Atlas ? this->Atlas.GetIndexName(e.Port) : 0;
    for (int c = 1; c < e.Channels; ++c)
      b.ComponentIndexTextures[c - 1] =
        this->Atlas.GetIndexName(strata::VolumePager::GetChannel(e.Port, c));
    b.TableBricks = frame.Atlas ? this->Pager.GetTree(v)->GetLevelBricks(0) : nullptr;
    b.BrickSize = frame.BrickSize;
    b.Normalized = this->GetDecode(frame, v, b.Decode);
    b.Skipping = key.Skipping;
    b.ComponentMode = e.ComponentMode;
    b.Shaded = key.Shaded[i];
    b.SampleDistance = frame.SampleDistance;
    b.LocalToIndex = e.LocalToIndex;
    b.Dims = e.Dims;
    this->Inputs[e.Port].Bind(renWin, program, i, e.Property, b, rawUnits);
  }
  if (frame.Compute)
  {
    this->DispatchFragment(program, f, frame); // with the barriers the next one needs
  }
  else
  {
    this->Geometry.Draw(f);
    if (frame.Feedback)
    {
      // The next fragment's comparison must see this one's reports.
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    // The next fragment reads what this one wrote into the bound buffers (its opacity, the
    // surface progress, the reduction state): a texture barrier between the two draws.
    if (key.Barrier || key.Reduce || key.Surfaces > 0)
      strata::RenderUtilities::TextureBarrier();
  }
  for (int i = 0; i < k; ++i)
    this->Inputs[frame.Volumes[volumes[i]].Port].Unbind(bindings[i]);
  for (vtkTextureObject* texture : readBack)
    texture->Deactivate();
  for (int unit : rawUnits)
  {
    renWin->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_3D, 0);
    units->Free(unit);
  }
  this->SurfaceLayers.Deactivate();
  depth->Deactivate();
  if (!frame.Compute)
    this->Geometry.Unbind();
  this->LastFragments += reduce < 0 ? 1 : 0;
  return true;
}

// The fragment's frame-wide uniforms: matrices, viewport, its outline and planes, the sample
// distance, termination, feedback and lights.
void vtkMultiVolumeRayCastMapper::vtkInternals::SetFragmentUniforms(Self* self,
  vtkShaderProgram* program,
  int f,
  const std::vector<int>& volumes,
  const strata::MultiVolumeShaderComposer::FragmentKey& key,
  const Frame& frame)
{
  float m[16];
  strata::RenderUtilities::ToColumnMajor(frame.LocalToClip->GetData(), m);
  program->SetUniformMatrix4x4("uLocalToClip", m);
  strata::RenderUtilities::ToColumnMajor(frame.ClipToLocal->GetData(), m);
  program->SetUniformMatrix4x4("uClipToLocal", m);
  const float width = float(frame.Viewport[2]), height = float(frame.Viewport[3]);
  const float viewport[4] = { 0.f, 0.f, width, height };
  program->SetUniform4f("uViewport", viewport);
  const float viewportSize[2] = { width, height };
  program->SetUniform2f("uViewportSize", viewportSize);
  program->SetUniform3f("uCentroid", this->Geometry.GetCentroid(f).data());
  // Sub-pixel rays reach half a pixel diagonal from the centre: 1.5 pixels of dilation covers
  // them also along edges that are not perpendicular to the direction from the centre.
  program->SetUniformf("uDilate", frame.Rays > 1 ? 1.5f : 0.0f);
  program->SetUniformf("uSampleDistance", static_cast<float>(frame.SampleDistance));
  if (frame.Feedback)
  {
    program->SetUniformi("uFeedback", 0);
    program->SetUniformi("uFeedbackScore", 1);
    program->SetUniformi("uFeedbackScale", self->FeedbackScale);
    program->SetUniform3f("uFeedbackEye", frame.FeedbackEye);
    program->SetUniform2f("uFeedbackFootprint", frame.FeedbackFootprint);
    for (int i = 0; i < key.Volumes; ++i)
    {
      const int v = volumes[i];
      const std::string n = std::to_string(i);
      program->SetUniformi(("uFeedbackSet" + n).c_str(), v);
      for (int c = 1; c < frame.Volumes[v].Channels; ++c)
        program->SetUniformi(
          ("uFeedbackSet" + n + "c" + std::to_string(c)).c_str(), frame.Volumes[v].PagerVolumes[c]);
      program->SetUniform1iv(
        ("uLevelBricks" + n).c_str(), 3 * FeedbackLevels, frame.LevelBricks[v].data());
      program->SetUniform2f(("uFeedbackLod" + n).c_str(), frame.FeedbackLod[v].data());
    }
  }
  if (std::find(key.Shaded.begin(), key.Shaded.end(), true) != key.Shaded.end())
  {
    const int lights = static_cast<int>(frame.LightDirections.size() / 3);
    program->SetUniformi("uNumLights", lights);
    if (lights > 0)
    {
      program->SetUniform3fv("uLightDirection",
        lights,
        reinterpret_cast<const float(*)[3]>(frame.LightDirections.data()));
      program->SetUniform3fv(
        "uLightColor", lights, reinterpret_cast<const float(*)[3]>(frame.LightColors.data()));
    }
  }
  std::vector<float> planes = this->Geometry.GetPlanes(f);
  planes.insert(planes.end(), frame.ClipPlanes.begin(), frame.ClipPlanes.end());
  program->SetUniformi("uNumPlanes", static_cast<int>(planes.size() / 4));
  program->SetUniform4fv("uPlanes",
    static_cast<int>(planes.size() / 4),
    reinterpret_cast<const float(*)[4]>(planes.data()));
  program->SetUniformi("uNumRegionPlanes", static_cast<int>(frame.RegionPlanes.size() / 4));
  if (!frame.RegionPlanes.empty())
    program->SetUniform4fv(
      "uRegionPlanes", 6, reinterpret_cast<const float(*)[4]>(frame.RegionPlanes.data()));
  if (frame.FrontToBack)
    program->SetUniformf("uTerminationOpacity", static_cast<float>(self->TerminationOpacity));
}

// --- Blend the integration buffers over the scene: the pixel is the mean of its rays.
void vtkMultiVolumeRayCastMapper::vtkInternals::Composite(vtkOpenGLRenderWindow* renWin,
  const Frame& frame)
{
  vtkShaderProgram* program =
    this->Composer.ReadyCompositeProgram(renWin, frame.Rays, frame.Surfaces);
  if (!program)
    return;
  this->SurfaceLayers.SetUniforms(program);
  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglViewport viewportSaver(state);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendSaver(state);
  vtkOpenGLState::ScopedglEnableDisable blendEnable(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthEnable(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cullEnable(state, GL_CULL_FACE);
  vtkOpenGLState::ScopedglDepthMask depthMaskSaver(state);
  state->vtkglViewport(frame.Viewport[0], frame.Viewport[1], frame.Viewport[2], frame.Viewport[3]);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglEnable(GL_BLEND);
  state->vtkglDisable(GL_CULL_FACE);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  this->Buffers.Composite(program, frame.Viewport, frame.Rays);
  this->SurfaceLayers.Deactivate();
}

vtkStandardNewMacro(vtkMultiVolumeRayCastMapper);

vtkMultiVolumeRayCastMapper::vtkMultiVolumeRayCastMapper()
  : Internals(new vtkInternals(this))
{
  // A fixed sample distance unless the user asks otherwise: accuracy is a setting, not a
  // by-product of the frame rate.
  this->AutoAdjustSampleDistances = 0;
  this->Stage = static_cast<Stages>(strata::ComputeStage::DefaultStage());
}

vtkMultiVolumeRayCastMapper::~vtkMultiVolumeRayCastMapper()
{
  // GL names die in their own context: the callback makes it current if the window lives.
  this->Internals->GraphicsResources.Release();
}

void vtkMultiVolumeRayCastMapper::SetRegion(const double bounds[6])
{
  if (this->Region.Set(bounds))
    this->Modified();
}

void vtkMultiVolumeRayCastMapper::RemoveRegion()
{
  if (this->Region.Remove())
    this->Modified();
}

bool vtkMultiVolumeRayCastMapper::GetRegion(double bounds[6]) const
{
  return this->Region.Get(bounds);
}

void vtkMultiVolumeRayCastMapper::GetRayOffset(int ray, int rays, double offset[2])
{
  // A rotated-grid-like pattern in pixels from the centre; the first R of these for R rays.
  static const double pattern[8][2] = { { 0.0, 0.0 },
    { 0.25, 0.25 },
    { -0.25, -0.25 },
    { 0.375, -0.125 },
    { -0.375, 0.125 },
    { -0.125, 0.375 },
    { 0.125, -0.375 },
    { 0.4375, 0.4375 } };
  // Re-centred so that the mean of the R rays is the pixel centre for every R (otherwise two
  // rays would shift the image by 1/8 pixel).
  const int count = std::min(std::max(rays, 1), 8);
  double mean[2] = { 0.0, 0.0 };
  for (int i = 0; i < count; ++i)
  {
    mean[0] += pattern[i][0] / count;
    mean[1] += pattern[i][1] / count;
  }
  const int r = std::min(std::max(ray, 0), count - 1);
  offset[0] = pattern[r][0] - mean[0];
  offset[1] = pattern[r][1] - mean[1];
}

void vtkMultiVolumeRayCastMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& in = *this->Internals;
  // The GPU copies only: the inputs' trees, tables and skip grids (CPU) stay, and their
  // textures are made again from them at the next render, without reading the data again.
  for (auto& input : in.Inputs)
    input.second.ReleaseGraphicsResources(window);
  in.Pager.InvalidateCut();
  in.Geometry.ReleaseGraphicsResources();
  in.Atlas.ReleaseGraphicsResources();
  in.Feedback.ReleaseGraphicsResources();
  in.Buffers.ReleaseGraphicsResources(window);
  in.SurfaceLayers.ReleaseGraphicsResources(window);
  for (auto& layer : in.LayerBuffers)
    layer.second.ReleaseGraphicsResources(window);
  in.LayerBuffers.clear();
  in.Composer.ReleaseGraphicsResources();
  in.HeldValid = false;
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkMultiVolumeRayCastMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  // A page pool behind an input: ask its reader for the coarsest level only (one page); the
  // ray caster pages the rest itself (see GPURender).
  for (int port = 0; port < this->GetNumberOfInputPorts(); ++port)
  {
    if (this->GetNumberOfInputConnections(port) == 0)
      continue;
    this->GetInputAlgorithm(port, 0)->UpdateInformation();
    vtkPagePoolProtocol::RequestCoarsestLevel(this->GetInputInformation(port, 0));
  }
  const auto start = std::chrono::steady_clock::now();
  this->Superclass::Render(ren, vol);
  if (this->MeasureRenderTime)
  {
    glFinish();
    this->Internals->Paging.RenderMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
}

vtkTypeBool vtkMultiVolumeRayCastMapper::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const vtkTypeBool result = this->Superclass::ProcessRequest(request, inputVector, outputVector);
  // Whatever updates the inputs (GetBounds, the render), a pool's reader serves its coarsest
  // level only: the bricks are paged, not read through the pipeline.
  vtkPagePoolProtocol::RequestCoarsestLevels(request, inputVector, this->GetNumberOfInputPorts());
  return result;
}

vtkMultiVolumeRayCastMapper::PagingStatistics vtkMultiVolumeRayCastMapper::GetPagingStatistics()
  const
{
  return this->Internals->Paging;
}

void vtkMultiVolumeRayCastMapper::GetPagingStatistics(vtkFieldData* statistics) const
{
  strata::RenderUtilities::ToFieldData(this->Internals->Paging, statistics);
}

void vtkMultiVolumeRayCastMapper::RetryFailedPages()
{
  this->Internals->Pager.RetryFailedPages();
}

bool vtkMultiVolumeRayCastMapper::WaitForPages(double seconds)
{
  return this->Internals->Pager.WaitForIdle(seconds);
}

// One frame: what to draw, its inputs on the GPU, the view, the cut and atlas, then the
// fragments into the integration buffers and their blend over the scene.
void vtkMultiVolumeRayCastMapper::GPURender(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!renWin)
  {
    vtkErrorMacro("vtkMultiVolumeRayCastMapper needs an OpenGL render window.");
    return;
  }
  in.GraphicsResources.Register(renWin);
  Frame frame;
  if (!in.CollectVolumes(this, vol, frame))
    return;
  frame.Feedback = in.SupportsFeedback(this, frame);
  frame.Footprint = frame.Feedback && this->LevelOfDetailThreshold > 0.0;
  std::vector<vtkMatrix4x4*> indexToWorld;
  std::vector<const int*> dims;
  for (const FrameVolume& e : frame.Volumes)
  {
    indexToWorld.push_back(e.IndexToWorld);
    dims.push_back(e.Dims);
  }
  in.Geometry.Update(indexToWorld, dims);
  if (!in.UpdateInputs(this, renWin, frame))
    return;
  in.SetUpView(this, ren, frame);
  if (frame.Atlas && !in.UpdateAtlas(this, ren, frame))
  {
    return;
  }
  frame.Rays = this->RaysPerPixel;
  in.Buffers.Prepare(renWin, frame.Viewport, frame.Rays);
  frame.FrontToBack = this->CompositeOrder == CompositeOrders::FrontToBack;
  // Early termination across fragments reads the integration buffer's own pixel while drawing
  // into it: defined under a texture barrier (each pixel is read and written once per fragment).
  // Reductions read their layer buffers the same way.
  const bool barriers = strata::RenderUtilities::HasTextureBarrier();
  frame.Barrier = frame.FrontToBack && barriers;
  if (frame.AnyReduced && !barriers)
  {
    vtkErrorMacro("MIP, MinIP, average and additive blending need texture barriers (OpenGL "
                  "4.5, ARB or NV_texture_barrier): those volumes are drawn composite.");
    for (FrameVolume& e : frame.Volumes)
      e.Mode = IsReduced(e.Mode) ? int(vtkVolumeMapper::COMPOSITE_BLEND) : e.Mode;
    frame.AnyReduced = false;
  }
  for (auto it = in.LayerBuffers.begin(); it != in.LayerBuffers.end();)
  {
    // Layers of volumes no longer reduced are freed.
    const int port = it->first;
    const bool used = std::any_of(frame.Volumes.begin(),
      frame.Volumes.end(),
      [port](const FrameVolume& e) { return e.Port == port && IsReduced(e.Mode); });
    if (!used)
      it->second.ReleaseGraphicsResources(renWin);
    it = used ? std::next(it) : in.LayerBuffers.erase(it);
  }
  for (const FrameVolume& e : frame.Volumes)
    if (IsReduced(e.Mode))
      in.LayerBuffers[e.Port].Prepare(renWin, frame.Viewport, frame.Rays);
  in.UpdatePreIntegration(this, renWin, frame);
  strata::RenderUtilities::GetLights(ren, frame.LightDirections, frame.LightColors);
  frame.Lit = ren->GetLights()->GetNumberOfItems() > 0;
  frame.Surfaces = in.SurfaceLayers.Peel(ren,
    renWin,
    in.Buffers.GetSceneDepth(),
    frame.Viewport,
    this->TranslucentLayers,
    frame.Rays,
    frame.Barrier);
  in.ChooseStage(this, renWin, frame);
  in.DrawFragments(this, ren, renWin, frame);
  in.Composite(renWin, frame);
  vtkOpenGLCheckErrorMacro("failed after multi-volume ray casting");
}

void vtkMultiVolumeRayCastMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CompositeOrder: "
     << (this->CompositeOrder == CompositeOrders::FrontToBack ? "FrontToBack" : "BackToFront")
     << "\n";
  os << indent << "TranslucentActors: " << this->GetNumberOfTranslucentActors()
     << ", TranslucentLayers: " << this->TranslucentLayers << "\n";
  os << indent << "Classification: " << static_cast<int>(this->Classification) << "\n";
  os << indent << "PreIntegrationTableSize: " << this->PreIntegrationTableSize << "\n";
  os << indent << "UseBrickAtlas: " << this->UseBrickAtlas << "\n";
  os << indent << "ScalarStorage: " << static_cast<int>(this->ScalarStorage) << "\n";
  os << indent << "BrickSize: " << this->BrickSize << "\n";
  os << indent << "AtlasBudget: " << this->AtlasBudget << " MB\n";
  os << indent << "RaysPerPixel: " << this->RaysPerPixel << "\n";
  os << indent << "Stage: " << strata::ComputeStage::StageName(static_cast<int>(this->Stage))
     << " (last frame: " << this->GetStageInUseAsString() << ")\n";
  os << indent << "RayCoherence: " << this->RayCoherence << "\n";
  os << indent << "TerminationOpacity: " << this->TerminationOpacity << "\n";
  os << indent << "EmptySpaceSkipping: " << this->EmptySpaceSkipping << "\n";
  os << indent << "SkipCellSize: " << this->SkipCellSize << "\n";
  os << indent << "PageCacheBudget: " << this->PageCacheBudget << " MB\n";
  os << indent << "PagesPerFrame: " << this->PagesPerFrame << "\n";
  os << indent << "Prefetch: " << this->Prefetch << "\n";
  os << indent << "PrefetchTimeSteps: " << this->PrefetchTimeSteps << "\n";
  os << indent << "LevelOfDetailFeedback: " << this->LevelOfDetailFeedback << "\n";
  os << indent << "FeedbackScale: " << this->FeedbackScale << "\n";
  os << indent << "FeedbackOpenCL: " << this->FeedbackOpenCL << "\n";
  os << indent << "LevelOfDetailThreshold: " << this->LevelOfDetailThreshold << " pixels\n";
  os << indent << "HoldCut: " << this->HoldCut << "\n";
  os << indent << "MeasureRenderTime: " << this->MeasureRenderTime << "\n";
  os << indent << "Region: ";
  this->Region.Print(os);
  os << "\n";
  for (const auto& mode : this->InputBlendModes)
    os << indent << "Blend mode of port " << mode.first << ": " << mode.second << "\n";
  for (const auto& crop : this->InputCroppings)
    os << indent << "Cropping of port " << crop.first << ": " << crop.second.Cropping
       << ", flags 0x" << std::hex << crop.second.Flags << std::dec << "\n";
  os << indent << "Fragments (last frame): " << this->Internals->LastFragments << "\n";
}
