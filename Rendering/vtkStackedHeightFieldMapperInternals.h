// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// Private to vtkStackedHeightFieldMapper's sources (not installed): the mapper's internals and
// what one frame draws with (vtkInternals::Frame), as vtkMultiVolumeRayCastMapperInternals.h
// holds the volume mapper's. Render is a list of the steps declared here.
#ifndef vtkStackedHeightFieldMapperInternals_h
#define vtkStackedHeightFieldMapperInternals_h

#include "vtkStackedHeightFieldMapper.h"

#include "StrataComputeStage.h"
#include "StrataComputeStaging.h"
#include "StrataFeedbackBuffer.h"
#include "StrataGraphicsResources.h"
#include "StrataHeightFieldPager.h"
#include "StrataHeightFieldShaderComposer.h"
#include "StrataHeightFieldStack.h"
#include "StrataHeightFieldStackBuffers.h"
#include "StrataHeightFieldTileAtlas.h"
#include "StrataMinMaxQuadtree.h"
#include "StrataVolumeSurfaceLayers.h"

#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

class vtkActor;
class vtkDataArray;
class vtkImageData;
class vtkOpenGLRenderWindow;
class vtkOpenGLRenderer;
class vtkRenderer;
class vtkScalarsToColors;
class vtkShaderProgram;
class vtkVolumeSurfacePeelPass;

class vtkStackedHeightFieldMapper::vtkInternals
{
public:
  using Self = vtkStackedHeightFieldMapper;
  explicit vtkInternals(Self* self)
    : GraphicsResources(self, &Self::ReleaseGraphicsResources)
  {
  }

  // CPU side
  strata::HeightFieldStack Stack;
  strata::MinMaxQuadtree Tree;
  std::vector<vtkSmartPointer<vtkDataArray>> Arrays; // keep borrowed layers alive
  vtkNew<vtkMatrix4x4> GridToWorld;
  vtkMTimeType BuildTime = 0;
  bool Valid = false;
  double Bounds[6] = { 0, -1, 0, -1, 0, -1 };
  std::map<int, std::array<double, 3>> HorizonColors;
  std::map<int, double> HorizonOpacities; ///< below 1 only
  vtkSmartPointer<vtkScalarsToColors> Lut;
  // Per horizon: a colour array (its name) and a lookup table; the arrays' values in core.
  std::map<int, std::string> ColorArrays;
  std::map<int, vtkSmartPointer<vtkScalarsToColors>> HorizonLuts;
  strata::HeightFieldStack Attributes;
  std::vector<int> AttributeLayer; ///< per horizon: its layer of Attributes, or -1
  vtkTimeStamp ColorsModified;
  // What the renderer draws, in core or paged: grid size, horizons, value range, holes.
  int NX = 0, NY = 0, Layers = 0;
  double ZRange[2] = { 0.0, -1.0 };
  bool Holes = false;

  // Paging (tile pools behind the inputs): the pager and the readers' coarsest levels as roots.
  bool Paged = false;
  strata::HeightFieldPager Pager;
  std::vector<std::vector<float>> RootValues;
  bool TreeDirty = true; ///< the pager's quadtree changed since it was uploaded
  // Level-of-detail feedback: the lattice phase, the view the queued buffer was written from.
  bool PendingViewChanged = false; ///< the queued frame's view differed from the one before
  int64_t FeedbackFrame = 0;
  bool FeedbackActive = false; ///< this frame's shader writes the buffer
  bool FeedbackUnsupportedWarned = false;
  bool UnsupportedTranslucentWarned = false;
  std::array<double, 16> LastView{};
  vtkStackedHeightFieldMapper::PagingStatistics Paging;

  // GPU side: the parts, and what of the data they hold.
  strata::GraphicsResources<Self> GraphicsResources;
  strata::HeightFieldStackBuffers Buffers;
  strata::HeightFieldTileAtlas Atlas;
  strata::FeedbackBuffer Feedback{ false };
  strata::HeightFieldShaderComposer Composer;
  strata::HeightFieldShaderComposer::Key LastKey;
  bool HasLastKey = false;
  strata::ComputeStaging Staging;     ///< the compute stage's pixels before they are resolved
  strata::ComputeStage::Choice Stage; ///< the stage of the last frame, Auto's probe ratio
  vtkMTimeType UploadTime = 0;
  vtkMTimeType ColorTime = 0;

  /// What this frame draws with, and how.
  struct Frame
  {
    bool Shaded = true;
    bool LookupTable = false;
    bool PerHorizon = false; ///< some horizon has its own table or colour array
    bool Lit = false;
    /// Skip in the opaque pass of a stack with translucent horizons, Layer in a peel.
    strata::HeightFieldShaderComposer::Translucency Translucent =
      strata::HeightFieldShaderComposer::Translucency::None;
    vtkVolumeSurfacePeelPass* Peel = nullptr; ///< the peel drawing this frame's layer
    double LutRange[2] = { 0.0, 1.0 };
    vtkNew<vtkMatrix4x4> GridToClip, ClipToGrid, GridToView;
    int Viewport[4] = { 0, 0, 0, 0 }; ///< x, y, width, height in the window
    bool Compute = false;             ///< the compute stage: one dispatch, staged, then resolved
  };

  bool ReadAttributes(Self* self, const std::vector<vtkImageData*>& images);
  /// pageFrame: advance paging (false in a peel, which redraws the frame's cut).
  bool Upload(Self* self,
    vtkRenderer* ren,
    vtkActor* actor,
    vtkOpenGLRenderWindow* renWin,
    bool pageFrame);
  bool ChooseTranslucency(Self* self, vtkActor* actor, Frame& frame);
  void SetPeelUniforms(vtkShaderProgram* program, const Frame& frame) const;
  bool UpdatePages(Self* self, vtkRenderer* ren, vtkActor* actor);
  void UpdateColors(Self* self, vtkOpenGLRenderWindow* renWin, Frame& frame);
  bool ColorsCurrent() const;
  double Opacity(int horizon) const;
  bool AnyTranslucent() const;
  bool AnyOpaque() const;
  std::vector<float> PerHorizonColors(Self* self) const;
  bool UseFeedback(Self* self);
  vtkShaderProgram* ReadyProgram(Self* self,
    vtkOpenGLRenderWindow* renWin,
    vtkOpenGLRenderer* oglRen,
    const Frame& frame);
  bool SetUniforms(Self* self,
    vtkRenderer* ren,
    vtkActor* actor,
    vtkShaderProgram* program,
    Frame& frame);
  void SetLightingUniforms(vtkOpenGLRenderer* ren,
    vtkActor* actor,
    vtkShaderProgram* program,
    const Frame& frame);
  void PrepareFeedback(Self* self,
    vtkOpenGLRenderWindow* renWin,
    vtkShaderProgram* program,
    const Frame& frame);
  /// writeDepth: false in the translucent pass (what lies behind stays visible to the rest).
  void Draw(vtkOpenGLRenderWindow* renWin, vtkShaderProgram* program, bool writeDepth);
  /// The frame's stage (Self::Stage, the device, the image units the pass needs).
  void ChooseStage(Self* self, vtkOpenGLRenderWindow* renWin, Frame& frame);
  /// The compute stage's draw: one dispatch over the box's screen rectangle into the staging
  /// images, resolved into the frame buffer under the fragment stage's depth test and blending.
  void DrawCompute(vtkOpenGLRenderWindow* renWin,
    vtkShaderProgram* program,
    const Frame& frame,
    bool writeDepth);
  void ReadFeedback(Self* self);
  /// The stack's textures (the tile atlas when paged, else the height array), the normals
  /// and the attributes bound for `program`; UnbindData undoes it.
  void BindData(vtkOpenGLRenderWindow* renWin, vtkShaderProgram* program, const Frame& frame);
  void UnbindData(vtkOpenGLRenderWindow* renWin, const Frame& frame);
  /// After the draw: the feedback image queued for read-back (now or at the next frame).
  void QueueFeedback(Self* self, vtkOpenGLRenderWindow* renWin, const Frame& frame);

  int HeightUnit = -1;    ///< the texture unit of the in-core heights while bound
  int AttributeUnit = -1; ///< the texture unit of the attributes while bound
};

#endif
