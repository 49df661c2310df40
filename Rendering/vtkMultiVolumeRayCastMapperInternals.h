// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Private to vtkMultiVolumeRayCastMapper's sources (not installed): what one frame draws
// (vtkMultiVolumeRayCastMapperFrame) and the mapper's internals, shared by the frame's code
// (vtkMultiVolumeRayCastMapper.cxx) and its settings and introspection
// (vtkMultiVolumeRayCastMapperSettings.cxx).
#ifndef vtkMultiVolumeRayCastMapperInternals_h
#define vtkMultiVolumeRayCastMapperInternals_h

#include "vtkMultiVolumeRayCastMapper.h"

#include "StrataBrickAtlasTexture.h"
#include "StrataComputeStage.h"
#include "StrataFeedbackBuffer.h"
#include "StrataGraphicsResources.h"
#include "StrataMultiVolumeInput.h"
#include "StrataMultiVolumeShaderComposer.h"
#include "StrataVolumeCut.h"
#include "StrataVolumeFragmentGeometry.h"
#include "StrataVolumeIntegrationBuffers.h"
#include "StrataVolumePager.h"
#include "StrataVolumeSurfaceLayers.h"

#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPagePoolProtocol.h"
#include "vtkSmartPointer.h"

#include <array>
#include <map>
#include <string>
#include <vector>

class vtkImageData;
class vtkOpenGLRenderWindow;
namespace strata
{
class PagePoolFile;
}
class vtkRenderer;
class vtkShaderProgram;
class vtkVolume;
class vtkVolumeProperty;

namespace vtkMultiVolumeRayCastMapperFrame
{
using ViewKey = std::array<double, 18>; ///< world -> clip, viewport width and height

// One volume of the current frame.
using Components = strata::MultiVolumeShaderComposer::Components;

struct FrameVolume
{
  int Port = 0;
  vtkImageData* Input = nullptr;
  vtkVolumeProperty* Property = nullptr;
  vtkSmartPointer<vtkMatrix4x4> IndexToWorld; ///< prop * image (origin, direction, spacing)
  float LocalToIndex[16];                     ///< the inverse from the local frame, for the GPU
  int Dims[3] = { 0, 0, 0 };
  /// The page pool the volume is paged from (invalid in core); Input is then a coarse stand-in.
  vtkPagePoolProtocol::Identity Pool;
  int Mode = vtkVolumeMapper::COMPOSITE_BLEND; ///< its effective blend mode
  bool Cropped = false;
  float CropLo[3], CropHi[3]; ///< the crop planes in index coordinates
  int CropFlags = 0;
  /// Several components: a composite medium (strata::MultiVolumeInput), from a plain texture or,
  /// when the frame uses the atlas, from a volume of one scalar per component there.
  Components ComponentMode = Components::One;
  /// In the atlas: that many volumes of the pager, component c's PagerVolumes[c] (component
  /// 0's is the frame's number of the volume), paged from the set's file of component c
  /// (strata::PagePoolFormat::GetComponentFileName of Pool).
  int Channels = 1;
  int PagerVolumes[4] = { 0, 0, 0, 0 };
};

// What one frame draws and how, gathered once and read by every step.
struct Frame
{
  std::vector<FrameVolume> Volumes;
  /// The pager's volumes: the frame's, then the components 1, 2, 3 of those that have several
  /// in the atlas; the frame volume and component of each.
  std::vector<std::array<int, 2>> PagerVolumes;
  int BrickSize = 32;
  bool AnyPooled = false;
  bool Atlas = true;
  bool Feedback = false;
  bool Footprint = false;
  bool Hold = false;
  int Viewport[4] = { 0, 0, 0, 0 }; ///< x, y, width, height in the window
  vtkNew<vtkMatrix4x4> ToWorld, LocalToClip, ClipToLocal;
  std::vector<float> ClipPlanes;   ///< inside: dot(n, p) + w <= 0, local frame
  std::vector<float> RegionPlanes; ///< the region's six faces (SetRegion), same convention
  ViewKey View{};
  vtkMTimeType Classification = 0; ///< the newest change of the volumes' properties
  bool Moved = false;
  double SampleDistance = 1.0;
  int Rays = 1;
  bool FrontToBack = true;
  bool Barrier = false;
  bool AnyReduced = false; ///< some volume is drawn as a layer by its own reduction pass
  int Surfaces = 0;        ///< translucent surface layers peeled this frame
  bool Compute = false;    ///< the compute stage: fragments dispatched, not drawn
  bool Lit = false;
  std::vector<float> LightDirections, LightColors;
  // Feedback uniforms: threshold x pixel size = x + y * distance, the eye, and per volume
  // 1 / level-0 voxel size with its coarsest level, and the bricks per axis of each level.
  float FeedbackFootprint[2] = { 0.f, 0.f };
  float FeedbackEye[3] = { 0.f, 0.f, 0.f };
  std::vector<std::array<float, 2>> FeedbackLod;
  std::vector<std::vector<int>> LevelBricks;
};
}

class vtkMultiVolumeRayCastMapper::vtkInternals
{
public:
  using Frame = vtkMultiVolumeRayCastMapperFrame::Frame;
  using FrameVolume = vtkMultiVolumeRayCastMapperFrame::FrameVolume;
  using ViewKey = vtkMultiVolumeRayCastMapperFrame::ViewKey;
  using Self = vtkMultiVolumeRayCastMapper;
  explicit vtkInternals(Self* self)
    : GraphicsResources(self, &Self::ReleaseGraphicsResources)
  {
  }

  strata::GraphicsResources<Self> GraphicsResources;
  strata::VolumeFragmentGeometry Geometry;
  std::map<int, strata::MultiVolumeInput> Inputs; // by input port
  strata::VolumePager Pager;
  strata::BrickAtlasTexture Atlas;
  strata::FeedbackBuffer Feedback{ true };
  strata::VolumeIntegrationBuffers Buffers;
  strata::VolumeSurfaceLayers SurfaceLayers; ///< with the translucent actors
  std::map<int, strata::VolumeIntegrationBuffers>
    LayerBuffers; ///< by port: reduced volumes' layers
  strata::MultiVolumeShaderComposer Composer;
  std::map<int, strata::MultiVolumeShaderComposer::FragmentKey>
    LastKeys; ///< by volumes, last frame
  std::map<int, strata::MultiVolumeShaderComposer::FragmentKey> LastReduceKeys; ///< by blend mode
  int LastFragments = 0;
  strata::ComputeStage::Choice Stage; ///< the stage of the last frame, Auto's probe ratio
  int ResidentBricks = 0;
  int Max3DTexture = 0;   ///< the GPU's, asked once
  bool HeldValid = false; ///< the cut, atlas and index textures are complete for HoldCut
  bool FeedbackUnsupportedWarned = false;
  bool ComponentLimitsWarned = false;
  bool SampleDistanceWarned = false;
  ViewKey FeedbackView{};                  ///< the view the queued feedback was rendered from
  vtkMTimeType FeedbackClassification = 0; ///< and the properties' (Frame::Classification)
  ViewKey LastView{};                      ///< the view of the last frame
  /// What decides which bricks are empty besides the transfer functions: the halo
  /// (pre-integration) and the region. When it changes the cut starts again from the roots:
  /// a brick that turns non-empty under a node already split has no page yet.
  bool CutHalo = false;
  strata::Region CutRegion;
  PagingStatistics Paging;
  /// By paged port: the pool shown (a new step's bricks end HoldCut) and the last prefetch
  /// warning (made once).
  std::map<int, std::array<std::string, 2>> ShownPools;

  bool CollectVolumes(Self* self, vtkVolume* vol, Frame& frame);
  const strata::PagePoolFile* OpenPool(Self* self,
    int port,
    int component,
    const vtkPagePoolProtocol::Identity& pool);
  bool OpenComponentPools(Self* self, const strata::PagePoolFile& first, const FrameVolume& e);
  /// Closes the pools of the channels the frame does not page (strata::VolumePager::ClosePool).
  void CloseUnusedPools(const Frame& frame);
  bool SupportsFeedback(Self* self, const Frame& frame);
  bool UpdateInputs(Self* self, vtkOpenGLRenderWindow* renWin, Frame& frame);
  void SetUpView(Self* self, vtkRenderer* ren, Frame& frame);
  bool UpdateAtlas(Self* self, vtkRenderer* ren, Frame& frame);
  /// Whether volume v's texels are normalised, and their decode (strata::BrickAtlasFormat).
  bool GetDecode(const Frame& frame, int v, float decode[2]) const;
  bool UpdateCut(Self* self, vtkRenderer* ren, Frame& frame);
  void UploadBricks(Self* self,
    const std::vector<strata::VolumeCut::Upload>& uploads,
    const Frame& frame);
  void UpdatePreIntegration(Self* self, vtkOpenGLRenderWindow* renWin, Frame& frame);
  void PrepareFeedback(Self* self, vtkRenderer* ren, vtkOpenGLRenderWindow* renWin, Frame& frame);
  void DrawFragments(Self* self, vtkRenderer* ren, vtkOpenGLRenderWindow* renWin, Frame& frame);
  void DrawReductions(Self* self,
    vtkOpenGLRenderWindow* renWin,
    const std::vector<int>& order,
    Frame& frame);
  strata::MultiVolumeShaderComposer::FragmentKey MakeKey(Self* self,
    const std::vector<int>& volumes,
    bool reduce,
    const Frame& frame) const;
  bool DrawFragment(Self* self,
    vtkOpenGLRenderWindow* renWin,
    int f,
    Frame& frame,
    int reduce = -1);
  /// The frame's stage (Self::Stage, the device, the image units its outputs need).
  void ChooseStage(Self* self, vtkOpenGLRenderWindow* renWin, Frame& frame);
  /// The compute stage's targets on their image units: `buffers`' rays, and the surface progress.
  void BindComputeTargets(strata::VolumeIntegrationBuffers& buffers,
    const Frame& frame,
    bool progress);
  static void UnbindComputeTargets(const Frame& frame);
  /// Fragment f dispatched over its screen rectangle with the bound compute program.
  void DispatchFragment(vtkShaderProgram* program, int f, const Frame& frame);
  void SetFragmentUniforms(Self* self,
    vtkShaderProgram* program,
    int f,
    const std::vector<int>& volumes,
    const strata::MultiVolumeShaderComposer::FragmentKey& key,
    const Frame& frame);
  void Composite(vtkOpenGLRenderWindow* renWin, const Frame& frame);
};

#endif
