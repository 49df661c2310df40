// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStackedHeightFieldMapper
 * @brief   Draws a stack of N height fields (horizons) in one ray-casting pass.
 *
 * The single-pass stacked height-field ray caster of Lux and Froehlich: a global min-max
 * quadtree over tiles of the lateral grid (empty-space skipping) whose nodes carry sorted lists
 * of disjoint depth intervals naming the horizons inside them (strata::MinMaxQuadtree). A ray walks
 * the tree top-down, evaluates a leaf's intervals front-to-back or back-to-front by its vertical
 * direction, and stops at the first hit; inside a tile it searches each candidate horizon
 * linearly (step LinearSearchStep cells) and refines the crossing by bisection.
 *
 * Inputs are vtkImageData of nx x ny x 1 points on one lateral grid, one per horizon, as
 * repeatable connections on port 0; the height is the active point scalar (or ArrayName) times
 * HeightScale along the image's third axis, so origin, spacing and the direction matrix (grid
 * rotation) are honoured. NaN, |v| >= 1e30 and NullValue (when UseNullValue) are holes.
 * Horizons may cross, touch and overlap. It writes a correct gl_FragDepth, so horizons and
 * ordinary VTK geometry occlude each other in one scene, and lights like any VTK surface using
 * the actor's vtkProperty (ambient, diffuse, specular) and the renderer's lights.
 *
 * Out of core: when the inputs are vtkPagePoolReader outputs of tile pools, the mapper pages
 * the horizons itself (strata::HeightFieldPager): the readers only serve their coarsest level, a
 * RAM cache filled by worker threads (PageCacheBudget) feeds a GPU atlas of tiles
 * (AtlasBudget, PagesPerFrame uploads per frame), the shader reads heights through a page
 * table, and the quadtree describes the resident data. Tiles of different levels are stitched
 * (no cracks) and refined tiles blend in over MorphFrames frames (no pops). Every frame shows a
 * complete, coarser surface until the cut settles; converged, the image equals the in-core one.
 *
 * Colours: one per horizon, or a lookup table over depth (ColorMode), or per horizon its own:
 * a lookup table over its depth (SetHorizonLookupTable) or over a second grid on the same
 * lateral grid, a point array of its input such as the thickness to the next horizon or an
 * amplitude extracted along it (SetHorizonColorArray), bilinear over the valid corners of the
 * hit cell (strata::HeightFieldStack::Interpolate), its no-data points in the table's NaN colour.
 *
 * Only what the scene uses is compiled: no lighting code when lighting is off, no lookup
 * table code with solid colours, no per-horizon sources unless a horizon has one, no attribute
 * sampling unless a horizon is coloured by a grid, no hole test when no horizon has holes.
 * GetShaderSource returns the source last used.
 *
 * @code
 * vtkNew<vtkStackedHeightFieldMapper> mapper;
 * mapper->AddInputConnection(top->GetOutputPort());
 * mapper->AddInputConnection(base->GetOutputPort());
 * mapper->SetHeightScale(-1.0); // depths grow downwards
 * vtkNew<vtkActor> actor;
 * actor->SetMapper(mapper);
 * renderer->AddActor(actor);
 * @endcode
 *
 * @sa strata::MinMaxQuadtree strata::HeightFieldStack strata::HeightFieldReferenceCaster
 */
#ifndef vtkStackedHeightFieldMapper_h
#define vtkStackedHeightFieldMapper_h

#include "StrataHeightFieldPager.h" // For strata::HeightFieldPager::Statistics
#include "StrataRegion.h"           // For strata::Region
#include "StrataRenderingModule.h"  // For export macro
#include "vtkMapper.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string
#include <vector> // For std::vector

class vtkFieldData;
namespace strata
{
class HeightFieldStack;
}
class vtkImageData;
class vtkMatrix4x4;
class vtkScalarsToColors;
class vtkWindow;

class STRATARENDERING_EXPORT vtkStackedHeightFieldMapper : public vtkMapper
{
public:
  static vtkStackedHeightFieldMapper* New();
  vtkTypeMacro(vtkStackedHeightFieldMapper, vtkMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum class ColorModes
  {
    Solid,       ///< one colour per horizon (SetHorizonColor, or a built-in palette)
    LookupTable, ///< the LookupTable (or a built-in depth colour map) over the height value
  };
  enum class OutputModes
  {
    Shaded,    ///< colour and lighting
    HorizonId, ///< flat colour id + 1 packed in 24-bit RGB, for tests and picking
  };

  ///@{
  /**
   * Horizons are inputs on port 0, one connection each, bottom of the list drawn with the last
   * id: AddInputConnection(reader->GetOutputPort()) for a pipeline, AddInputData(image) for an
   * image made in memory (from NumPy, say). RemoveAllInputs() empties the stack.
   */
  void AddInputData(vtkImageData* horizon);
  using vtkAlgorithm::AddInputConnection;
  ///@}

  ///@{
  /**
   * Tile size of the quadtree's leaves, in cells (default 64). Smaller tiles skip more empty
   * space at the cost of a deeper tree.
   */
  vtkSetClampMacro(TileSize, int, 2, 4096);
  vtkGetMacro(TileSize, int);
  ///@}

  ///@{
  /**
   * Largest distance between two samples of the linear search, in cells along the ground
   * (default 0.5). Every cell boundary is also a sample. Smaller is more exact on grazing rays
   * and slower: see `scripts/bench heightfield`.
   */
  vtkSetClampMacro(LinearSearchStep, double, 1e-3, 1.0);
  vtkGetMacro(LinearSearchStep, double);
  ///@}

  /// The stage the rays are cast in (the values of strata::ComputeStage::Stages).
  enum class Stages
  {
    Auto,     ///< the faster of the two on this device, by a probe at the first render
    Fragment, ///< a fragment shader over the stack's box
    Compute,  ///< one compute dispatch over the box's screen rectangle
  };

  ///@{
  /**
   * The stage (default Auto, or the environment's STRATA_RAY_CASTING_STAGE: Auto, Fragment or
   * Compute). Both stages run the same composed program, feature for feature: the compute stage
   * leaves its colours and depths in images, which one fragment pass writes into the frame
   * buffer under the same depth test and blending. Auto times the same kernel in both stages
   * once per device (GL_RENDERER) and process; Compute falls back to Fragment, with a warning,
   * without OpenGL 4.3.
   */
  void SetStage(Stages stage);
  Stages GetStage() const { return this->Stage; }
  void SetStageToAuto() { this->SetStage(Stages::Auto); }
  void SetStageToFragment() { this->SetStage(Stages::Fragment); }
  void SetStageToCompute() { this->SetStage(Stages::Compute); }
  ///@}

  /// The stage the last frame was cast in (Fragment or Compute; Auto before the first frame).
  Stages GetStageInUse() const;
  const char* GetStageInUseAsString() const;
  /// Auto's probe on this device: compute / fragment time of the same kernel (0 if not probed).
  double GetStageProbeRatio() const;

  ///@{
  /**
   * Scale from the scalar value to the image's third axis (default 1). -1 draws depths as
   * growing downwards; a larger magnitude exaggerates relief.
   */
  vtkSetMacro(HeightScale, double);
  vtkGetMacro(HeightScale, double);
  ///@}

  ///@{
  /**
   * A value that marks no data (e.g. -999.25), used when UseNullValue is on (default off).
   */
  vtkSetMacro(NullValue, double);
  vtkGetMacro(NullValue, double);
  vtkSetMacro(UseNullValue, bool);
  vtkGetMacro(UseNullValue, bool);
  vtkBooleanMacro(UseNullValue, bool);
  ///@}

  ///@{
  /**
   * Name of the point array holding the heights; empty (default) uses the active scalars.
   */
  vtkSetStdStringFromCharMacro(HeightArrayName);
  vtkGetCharFromStdStringMacro(HeightArrayName);
  ///@}

  ///@{
  /// How horizons are coloured (default Solid).
  void SetColorMode(ColorModes mode);
  ColorModes GetColorMode() const { return this->ColorMode; }
  ///@}

  ///@{
  /// What the fragments carry (default Shaded).
  void SetOutputMode(OutputModes mode);
  OutputModes GetOutputMode() const { return this->OutputMode; }
  ///@}

  /**
   * Colour of horizon `index` in Solid mode; horizons without one use a built-in palette.
   */
  void SetHorizonColor(int index, double r, double g, double b);

  /**
   * Lookup table over the height value for LookupTable mode (separate from vtkMapper's own); null
   * (default) uses a built-in depth colour map over the stack's range. Its own range is used when
   * it has one.
   */
  void SetHeightLookupTable(vtkScalarsToColors* lut);

  /**
   * Colours horizon `index` by the point array `name` of its input (one value per grid point;
   * NaN and |v| >= 1e30 are no data) through its lookup table (SetHorizonLookupTable, else the
   * built-in colour map over the array's range); null or empty (default) colours it as
   * ColorMode says. In core only: paged horizons carry heights only (a warning, then depth).
   */
  void SetHorizonColorArray(int index, const char* name);

  /**
   * Lookup table of horizon `index`, over its colour array or, without one, over its height
   * value, whatever ColorMode says; its own range when it has one, else the array's (or the
   * stack's) range. Values of no data take its NaN colour. Null (default) removes it.
   */
  void SetHorizonLookupTable(int index, vtkScalarsToColors* lut);

  ///@{
  /**
   * Opacity of horizon `index` (default 1: opaque). A translucent horizon (below 1) is not
   * drawn by the renderer's passes; give the actor to the volume ray caster too
   * (vtkMultiVolumeRayCastMapper::AddTranslucentActor; it stays in the renderer for its opaque
   * horizons), which composites each translucent horizon where a ray crosses it, in ray order
   * with the volume samples and the other translucent surfaces (strata::VolumeSurfaceLayers: this
   * mapper's rays find, per peel, the first translucent hit behind the last layer; translucent
   * horizons that touch, equal where the ray meets them, are one layer, composited in index
   * order). Opaque horizons of the same stack still hide what lies behind them. With horizon
   * ids (OutputMode HorizonId) every horizon is opaque. The shaders of a stack whose horizons
   * are all opaque hold no translucency code.
   */
  void SetHorizonOpacity(int index, double opacity);
  double GetHorizonOpacity(int index) const;
  ///@}

  ///@{
  /**
   * Paging budgets, used when the inputs are tile pools, with the names and defaults of
   * vtkMultiVolumeRayCastMapper's: RAM page cache in MiB (default 512), GPU tile atlas in MiB
   * (default 256, floats; never more tiles than the GPU's array layers) and tiles uploaded per
   * frame (default 64).
   * Prefetch (default off): after a tile loads on demand, page-cache workers also read its four
   * neighbours and its parent ahead of a moving camera. Off: it settles a test's short path
   * sooner, but on the benchmark's paper-size fly-through it reads more for the same settling
   * and frame times (the guide's paging page, Documentation/paging.md, gives the figures).
   */
  vtkSetClampMacro(PageCacheBudget, double, 1.0, 1048576.0);
  vtkGetMacro(PageCacheBudget, double);
  vtkSetClampMacro(AtlasBudget, double, 0.001, 1048576.0);
  vtkGetMacro(AtlasBudget, double);
  vtkSetClampMacro(PagesPerFrame, int, 1, 65536);
  vtkGetMacro(PagesPerFrame, int);
  vtkSetMacro(Prefetch, bool);
  vtkGetMacro(Prefetch, bool);
  vtkBooleanMacro(Prefetch, bool);
  ///@}

  ///@{
  /**
   * Frames over which a refined tile blends from its parent's surface to its own (default 4;
   * 0: at once). Levels are stitched, so no cut shows a crack; this keeps a refinement from
   * popping too: frame k of n shows parent + (own - parent) k / n (strata::HeightFieldPager::
   * SetMorphFrames). The price: a blending tile is uploaded every frame, and settling takes n
   * more frames.
   */
  vtkSetClampMacro(MorphFrames, int, 0, 64);
  vtkGetMacro(MorphFrames, int);
  ///@}

  ///@{
  /**
   * Level-of-detail feedback while paging (default on): the ray caster writes the tile each
   * sampled ray hit, at the level its pixel footprint wants, into a buffer of 1/FeedbackScale
   * of the viewport per axis (default 4; one pixel of each lattice cell per frame, cycling),
   * reduced to a (tile, pixels) list that drives the cut, so tiles hidden under other horizons
   * or out of view stay coarse. Off: every tile is refined by its screen-space error.
   * FeedbackOpenCL (default on): reduce the buffer with OpenCL when a device is found, else on
   * the CPU (strata::FeedbackReduction; both give the same list).
   */
  vtkSetMacro(LevelOfDetailFeedback, bool);
  vtkGetMacro(LevelOfDetailFeedback, bool);
  vtkBooleanMacro(LevelOfDetailFeedback, bool);
  vtkSetClampMacro(FeedbackScale, int, 1, 64);
  vtkGetMacro(FeedbackScale, int);
  vtkSetMacro(FeedbackOpenCL, bool);
  vtkGetMacro(FeedbackOpenCL, bool);
  vtkBooleanMacro(FeedbackOpenCL, bool);
  ///@}

  ///@{
  /**
   * When the feedback buffer is read (default off: right after the frame is drawn). It is
   * copied into a pixel buffer object after the draw; off maps it at once, on maps it at the
   * next frame, before that frame's cut update, so the CPU does not wait for the GPU to finish
   * the frame it just queued (the cut sees the same feedback either way). On llvmpipe, where
   * every draw finishes inside the call, mapping at once measured faster (the guide's paging
   * page, Documentation/paging.md, gives the figures): hence the default; on a GPU turn it on.
   */
  vtkSetMacro(DeferFeedbackReadBack, bool);
  vtkGetMacro(DeferFeedbackReadBack, bool);
  vtkBooleanMacro(DeferFeedbackReadBack, bool);
  ///@}

  ///@{
  /**
   * Pixels a cell may cover before feedback asks for a finer level; 0 (default) asks for the
   * finest level wherever a ray hits, so the converged image is the in-core one. 1 stops at
   * about one cell per pixel, saving the I/O of sub-pixel detail.
   */
  vtkSetClampMacro(LevelOfDetailThreshold, double, 0.0, 1.0e6);
  vtkGetMacro(LevelOfDetailThreshold, double);
  ///@}

  /// What paging did in the last frame (all zero when the inputs are in core).
  /// The pager's statistics (strata::HeightFieldPager::Statistics: cut, cache, reads, failures) and
  /// what the mapper adds on the GPU side.
  struct PagingStatistics : strata::HeightFieldPager::Statistics
  {
    bool Paged = false;
    int AtlasSlots = 0;                ///< tiles the atlas holds
    long long BytesUploaded = 0;       ///< this frame, tiles and stitched borders
    bool FeedbackUsed = false;         ///< the cut was driven by feedback this frame
    double FeedbackMilliseconds = 0.0; ///< mapping and reduction of the last buffer
    bool FeedbackOpenCL = false;       ///< whether OpenCL reduced it (else the CPU)

    template<typename Visit>
    void ForEachField(Visit&& visit) const
    {
      strata::HeightFieldPager::Statistics::ForEachField(visit);
      visit("Paged", this->Paged);
      visit("AtlasSlots", this->AtlasSlots);
      visit("BytesUploaded", this->BytesUploaded);
      visit("FeedbackUsed", this->FeedbackUsed);
      visit("FeedbackMilliseconds", this->FeedbackMilliseconds);
      visit("FeedbackOpenCL", this->FeedbackOpenCL);
    }
  };
  PagingStatistics GetPagingStatistics() const;
  /// The same statistics as one-value arrays named as the fields ("Paged", "CutTiles",
  /// "BytesRead", ...; strata::RenderUtilities::ToFieldData), for Python and ParaView.
  void GetPagingStatistics(vtkFieldData* statistics) const;
  /// Forgets failed page loads so that they are tried again.
  void RetryFailedPages();
  /// Waits (tests, benchmarks) until no page load is queued or running.
  bool WaitForPages(double seconds);
  /// True when the inputs are paged from tile pools (after a render or GetBounds).
  bool GetPaged() const;
  /// The pager (cut, page table, CPU reference of the lookup); meaningful when GetPaged().
  const strata::HeightFieldPager* GetPager() const;

  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  ///@{
  /**
   * The source of the program the last render ran, in its stage (GetStageInUse: a fragment or
   * a compute shader); the fragment stage's or the compute stage's source of that program
   * (empty if never built). Empty before the first render.
   */
  std::string GetShaderSource() const;
  std::string GetFragmentShaderSource() const;
  std::string GetComputeShaderSource() const;
  ///@}

  ///@{
  /**
   * Shader sources built and programs compiled (handed to VTK's shader cache, or compiled
   * again after a release) since the mapper was made, counted by its composer
   * (strata::HeightFieldShaderComposer): a frame that draws what the last one drew adds nothing.
   */
  int GetNumberOfShaderSourcesBuilt() const;
  int GetNumberOfShaderCompilations() const;
  ///@}

  ///@{
  /**
   * The region this mapper draws (default none: the whole stack), a world box, for sort-last
   * parallel rendering in which each process draws one box of a partition of the scene and the
   * images are blended in box order (ParaView's ordered compositing over MPI ranks). Each ray
   * looks for its first hit inside the box only, so the opaque surfaces are cut to it exactly
   * and the boxes of a partition together draw what one process would.
   */
  void SetRegion(const double bounds[6]);
  void RemoveRegion();
  /// False when no region is set.
  bool GetRegion(double bounds[6]) const;
  ///@}

  /**
   * The 4x4 matrix (row-major) from grid space (x, y in cells, z = scalar) to world space,
   * before the actor's matrix; valid after the inputs were read (a render or GetBounds).
   */
  void GetGridToWorld(double m[16]);

  /// The stack as the renderer sees it (after a render or GetBounds); null before.
  const strata::HeightFieldStack* GetStack();

  void Render(vtkRenderer* ren, vtkActor* actor) override;
  void ReleaseGraphicsResources(vtkWindow* win) override;
  double* GetBounds() override;
  void GetBounds(double bounds[6]) override { this->vtkMapper::GetBounds(bounds); }
  /// False when every horizon is translucent.
  bool HasOpaqueGeometry() override;
  /// True when some horizon is translucent (SetHorizonOpacity).
  bool HasTranslucentPolygonalGeometry() override;

protected:
  vtkStackedHeightFieldMapper();
  ~vtkStackedHeightFieldMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

private:
  vtkStackedHeightFieldMapper(const vtkStackedHeightFieldMapper&) = delete;
  void operator=(const vtkStackedHeightFieldMapper&) = delete;

  bool UpdateStack();
  bool UpdatePagedStack(const std::vector<vtkImageData*>& images);
  void SetPooledInputsToCoarsest();
  void ComputeBounds();

  strata::Region Region;
  int TileSize = 64;
  double LinearSearchStep = 0.5;
  Stages Stage = Stages::Auto;
  double HeightScale = 1.0;
  double NullValue = -999.25;
  bool UseNullValue = false;
  std::string HeightArrayName;
  double PageCacheBudget = 512.0;
  double AtlasBudget = 256.0;
  int PagesPerFrame = 64;
  bool Prefetch = false;
  int MorphFrames = 4;
  bool LevelOfDetailFeedback = true;
  int FeedbackScale = 4;
  double LevelOfDetailThreshold = 0.0;
  bool FeedbackOpenCL = true;
  bool DeferFeedbackReadBack = false;
  ColorModes ColorMode = ColorModes::Solid;
  OutputModes OutputMode = OutputModes::Shaded;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
