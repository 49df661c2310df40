// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkMultiVolumeRayCastMapper
 * @brief   Ray casts any number of overlapping volumes in one correct composite, fragment by
 *          fragment of a BSP tree over their boxes.
 *
 * The multi-volume ray caster of Lux and Froehlich (GPU-based ray casting of multiple
 * multi-resolution volume datasets, sections 3.3 and 3.4). Used like VTK's own multi-volume
 * path: a vtkMultiVolume whose member vtkVolumes carry their own vtkVolumeProperty and transform,
 * with the inputs on this mapper's ports (SetInputConnection(port, ...)); a single vtkVolume works
 * too. Volumes may differ in resolution, spacing, orientation (prop transform and vtkImageData
 * direction matrix) and scalar type.
 *
 * Each frame: the boxes of the volumes go into a strata::VolumeBSPTree (rebuilt only when a volume
 * moves); its convex fragments are sorted for the camera and each is ray cast in one pass by a
 * shader generated for the number of volumes covering it. Rays composite into a float
 * integration buffer (front to back or back to front), stop at the depth of the opaque geometry
 * already drawn, and the result is blended over the scene. Where volumes overlap their media mix
 * physically: extinctions add and emission is weighted by extinction, with extinction
 * tau = -ln(1 - opacity) / ScalarOpacityUnitDistance from each volume's transfer functions.
 * Point scalars of several components follow the property's IndependentComponents (2-4
 * independent, 2 colour + opacity, 4 RGBA; strata::MultiVolumeInput), in core or paged (a set of
 * component pools, strata::PagePoolFormat: a volume of one scalar per component in the atlas),
 * post-classified and unshaded; InterpolationType and the unit distances are each volume's (and
 * component's). All geometry is composed in double on the CPU relative to a local origin, so
 * volumes at UTM coordinates render like volumes at the origin.
 *
 * vtkGPUVolumeRayCastMapper is the superclass because vtkMultiVolume accepts no other mapper; none
 * of its OpenGL implementation is used.
 *
 * @sa strata::VolumeBSPTree vtkMultiVolume
 */
#ifndef vtkMultiVolumeRayCastMapper_h
#define vtkMultiVolumeRayCastMapper_h

#include "StrataRegion.h"          // For strata::Region
#include "StrataRenderingModule.h" // For export macro
#include "StrataVolumePager.h"     // For strata::VolumePager::Statistics
#include "vtkGPUVolumeRayCastMapper.h"

#include <array>  // For std::array
#include <map>    // For std::map
#include <memory> // For std::unique_ptr
#include <string> // For std::string
#include <vector> // For std::vector

class vtkActor;
class vtkFieldData;
class vtkIntArray;
class vtkWindow;

class STRATARENDERING_EXPORT vtkMultiVolumeRayCastMapper : public vtkGPUVolumeRayCastMapper
{
public:
  static vtkMultiVolumeRayCastMapper* New();
  vtkTypeMacro(vtkMultiVolumeRayCastMapper, vtkGPUVolumeRayCastMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum class CompositeOrders
  {
    FrontToBack, ///< fragments and samples nearest first; rays stop once nearly opaque
    BackToFront, ///< farthest first; no early termination
  };

  enum class Classifications
  {
    PostClassification,       ///< classify each sample (at segment midpoints)
    PreIntegrated,            ///< full 2-D table of segment integrals at the sample distance
    PreIntegratedApproximate, ///< the two-integral form: two 1-D tables, any segment length
  };

  ///@{
  /**
   * Classification (default PostClassification). Pre-integration integrates the transfer
   * function between the scalars at both ends of each step, so a coarse step still resolves
   * sharp features of the transfer function (strata::PreIntegrationTable).
   */
  void SetClassification(Classifications classification);
  Classifications GetClassification() const { return this->Classification; }
  ///@}

  ///@{
  /**
   * Samples per scalar axis of the pre-integration tables (default 256).
   */
  vtkSetClampMacro(PreIntegrationTableSize, int, 16, 4096);
  vtkGetMacro(PreIntegrationTableSize, int);
  ///@}

  ///@{
  /**
   * Virtualized volume data (default on): each volume is cut into bricks of BrickSize^3 voxels
   * sharing one voxel layer, with a down-sampled octree; one shared atlas texture of at most
   * AtlasBudget MB holds the bricks of all volumes chosen by a greedy split/collapse on their
   * screen-space error (strata::VolumeCut; the atlas is never larger than all bricks of all
   * levels), and each volume reaches its bricks through an index texture. Bricks that the transfer
   * function makes transparent are neither stored nor sampled. Off: one plain 3-D texture per
   * volume at full resolution.
   */
  vtkSetMacro(UseBrickAtlas, bool);
  vtkGetMacro(UseBrickAtlas, bool);
  vtkBooleanMacro(UseBrickAtlas, bool);
  vtkSetClampMacro(BrickSize, int, 4, 256);
  vtkGetMacro(BrickSize, int);
  vtkSetClampMacro(AtlasBudget, double, 0.001, 1048576.0);
  vtkGetMacro(AtlasBudget, double);
  ///@}

  ///@{
  /**
   * How 8- and 16-bit volumes are stored on the GPU (strata::BrickAtlasFormat): Float32, 4 bytes a
   * voxel; Normalized16 (default), R16 textures normalised and decoded in the shader, 2 bytes a
   * voxel, so one AtlasBudget holds 2x the bricks of float; Native, R8 as well when every volume
   * is 8-bit unsigned, 4x. Float volumes stay float. The shared atlas takes the widest type a
   * scene's volumes need; plain textures (UseBrickAtlas off) take each volume's own. Level 0 is
   * exact in every storage; coarser levels of in-core volumes are rounded to integers, as page
   * pools store them. A texture unit may filter R8 texels at lower precision than R16 and float
   * ones, hence Normalized16 as the default; the guide's accuracy page
   * (Documentation/accuracy.md) gives each storage's measured error and cost.
   */
  enum class ScalarStorages
  {
    Float32,
    Normalized16,
    Native
  };
  void SetScalarStorage(ScalarStorages storage);
  ScalarStorages GetScalarStorage() const { return this->ScalarStorage; }
  ///@}

  ///@{
  /**
   * Empty-space skipping (default on), in both compositing orders and with or without the
   * atlas: each volume keeps a grid of cells of SkipCellSize voxels per axis with the
   * chessboard distance to the nearest cell the transfer function makes visible
   * (strata::VolumeSkipGrid); a ray in empty space jumps out of the whole empty box around its cell
   * with one texel fetch, and resumes on its own sample lattice, so the image is unchanged.
   * Probed only after a transparent step. Off: no skipping code in the shaders.
   */
  vtkSetMacro(EmptySpaceSkipping, bool);
  vtkGetMacro(EmptySpaceSkipping, bool);
  vtkBooleanMacro(EmptySpaceSkipping, bool);
  vtkSetClampMacro(SkipCellSize, int, 1, 256);
  vtkGetMacro(SkipCellSize, int);
  ///@}

  ///@{
  /**
   * Out of core. An input produced by vtkPagePoolReader (recognised by vtkPagePoolProtocol:
   * the PAGE_POOL mark on the connection, the pool's identity on the data) is not read
   * through the pipeline: the
   * reader is asked for its coarsest level only, and the bricks are paged from the pool. The
   * cut (shared with in-core volumes, under AtlasBudget) may split a brick only when its
   * children's pages are in the RAM page cache (PageCacheBudget MB, LRU, worker threads); the
   * missing ones are queued at the brick's priority and the cut refines in later frames, at
   * most PagesPerFrame new bricks per frame. The render thread reads no page itself: each
   * pool's root (its coarsest level, one page) is the image the reader produced for the
   * pipeline, so a volume is drawn from the first frame on; only an input that is not that
   * image (another filter in between) makes the render thread read the root once. Pages that
   * fail to load give one VTK error each and the volume keeps its coarser bricks there. The
   * brick size is the pool's page size (all pools of a scene must share it).
   */
  vtkSetClampMacro(PageCacheBudget, double, 1.0, 1048576.0);
  vtkGetMacro(PageCacheBudget, double);
  vtkSetClampMacro(PagesPerFrame, int, 1, 65536);
  vtkGetMacro(PagesPerFrame, int);
  ///@}

  ///@{
  /**
   * Prefetch (default off): after a brick loads on demand, page-cache workers also read its six
   * neighbours and its parent, below every demand request, ahead of a moving camera. Off by
   * default because it measured worse where it should help: on the benchmark's fly-through it
   * read more and settled later, since prefetches in flight delay the demand loads queued
   * behind them (the guide's paging page, Documentation/paging.md, gives the figures). Worth
   * trying where reads are cheap and the camera pans steadily.
   */
  vtkSetMacro(Prefetch, bool);
  vtkGetMacro(Prefetch, bool);
  vtkBooleanMacro(Prefetch, bool);
  ///@}

  ///@{
  /**
   * PrefetchTimeSteps (default on): for an input that is a time series of page pools
   * (vtkPagePoolReader::AddTimeStep), the page-cache workers read, below every demand request,
   * the next step's pages of the bricks the current step's cut holds, the next step in the
   * direction of playback (the sign of the last step change, wrapping around), so that the
   * switch finds them in RAM and the render thread reads none (PagingStatistics StepPagesRead
   * and IoWaitFrames count what it read). The cache must hold two cuts for that.
   */
  vtkSetMacro(PrefetchTimeSteps, bool);
  vtkGetMacro(PrefetchTimeSteps, bool);
  vtkBooleanMacro(PrefetchTimeSteps, bool);
  ///@}

  ///@{
  /**
   * Level-of-detail feedback (default on), used while any input is paged; it then ranks the
   * bricks of every volume in the scene. The ray caster reports the detail it lacks, in the
   * same pass: the centre ray of every FeedbackScale-th pixel per axis (default 4, a buffer of
   * 1/4 x 1/4 of the viewport) writes, with image load/store into an R32UI texture, the packed
   * id (strata::FeedbackReduction: volume, level, brick) of one brick it reads data from (samples
   * and gradient taps) before it terminates whose cut level is coarser than the level its
   * footprint asks for (see LevelOfDetailThreshold): the one that costs the ray most, the
   * transmittance in front of the sample times 2^(levels too coarse), nearest first on ties. Why a
   * lacking brick rather than a fixed sample (say where the opacity crosses 1/2): the report moves
   * on as the cut refines, so over a few frames a ray walks all its bricks and every brick it reads
   * before it is opaque reaches the wanted level - the converged image along those rays is exactly
   * the image with every brick at that level - while one id per pixel suffices; a brick behind
   * opaque material or outside the view is never asked for, so it stays coarse. Why the costliest
   * one rather than the first: under a tight atlas a ray would keep asking for a near brick the
   * budget cannot give and never for the coarse ones behind it; by cost the budget goes where
   * coarseness shows (bench: lower error than the screen-space cut at every atlas budget). The
   * price: convergence takes a frame or two per brick a ray crosses, where the screen-space cut
   * asks for all at once.
   *
   * The buffer is read back through a pixel buffer object at the next frame (the GPU is not
   * waited on), reduced to (page, pixels) by strata::FeedbackReduction (OpenCL when FeedbackOpenCL
   * is on and a device is found, else on the CPU), the pixels are added to every ancestor
   * (PropagateToAncestors), and a node's split priority is the number of feedback pixels that
   * asked for detail below it. Satisfied rays stop asking, so a node keeps the largest
   * priority it had while the camera is still (the cut settles) and half of it for each frame
   * the camera moves. Back to front, rays know no opacity in front of a sample: the cost is
   * 2^(levels too coarse) alone and occlusion plays no part.
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
   * The detail the cut aims for, in pixels per voxel (default 0: the finest level the atlas
   * budget allows). Without feedback a node whose voxels cover at most this many pixels is not
   * split; with feedback a ray asks for the coarsest level whose voxels cover at most this
   * many pixels at the sample (level 0 when 0).
   */
  vtkSetClampMacro(LevelOfDetailThreshold, double, 0.0, 1.0e6);
  vtkGetMacro(LevelOfDetailThreshold, double);
  ///@}

  /// strata::VolumePager's counts (cut, cache, reads, roots, failures, feedback) and what the
  /// mapper adds on the GPU side; all zero when no input is paged.
  struct PagingStatistics : strata::VolumePager::Statistics
  {
    long long BytesUploaded = 0;       ///< to the atlas in the last frame (paged or not)
    double FeedbackMilliseconds = 0.0; ///< its read-back and reduction (propagation included)
    bool FeedbackOpenCL = false;       ///< whether OpenCL reduced it (else the CPU)
    double RenderMilliseconds = 0.0;   ///< the last Render, GPU finished (MeasureRenderTime)

    template<typename Visit>
    void ForEachField(Visit&& visit) const
    {
      strata::VolumePager::Statistics::ForEachField(visit);
      visit("BytesUploaded", this->BytesUploaded);
      visit("FeedbackMilliseconds", this->FeedbackMilliseconds);
      visit("FeedbackOpenCL", this->FeedbackOpenCL);
      visit("RenderMilliseconds", this->RenderMilliseconds);
    }
  };
  PagingStatistics GetPagingStatistics() const;
  /// The same statistics as one-value arrays named as the fields ("PendingPages", "BytesRead",
  /// "Converged", ...; strata::RenderUtilities::ToFieldData), for Python and ParaView.
  void GetPagingStatistics(vtkFieldData* statistics) const;
  /// Loads failed pages again (after a transient error).
  void RetryFailedPages();
  /// Waits (scripts, tests, benchmarks) until no page load is queued or running; false on timeout.
  bool WaitForPages(double seconds);

  /// Bricks resident in the atlas after the last frame, and atlas slots.
  int GetNumberOfResidentBricks() const;
  /// Resident (non-empty) cut bricks of the volume on input port `port`, counted by level.
  std::vector<int> GetResidentBricksPerLevel(int port) const;
  int GetNumberOfAtlasSlots() const;
  /// Bytes one brick takes in the atlas of the last frame (BrickSize^3 texels of its type), and
  /// that type's name ("uint8", "uint16", "float32").
  int GetAtlasBytesPerBrick() const;
  const char* GetAtlasScalarTypeName() const;

  ///@{
  /**
   * The cut of the volume on input port `port` as the last frame drew it: one (level, brick
   * index within the level, x fastest) per cut brick, transparent ones included, finest level
   * first. SetFixedCut makes the mapper draw that volume with exactly such a cut (paged or in
   * core; the atlas budget must hold it, paged bricks still arrive at PagesPerFrame a frame)
   * instead of choosing one, until RemoveAllFixedCuts. Why: the in-core rendering of a paged
   * frame's cut is the image that frame must be, so tests and bug reports can check any
   * intermediate frame of a paged fly-through, not only the converged one. Bricks that name no
   * node of the volume's tree are ignored.
   */
  std::vector<std::array<int, 2>> GetCutBricks(int port) const;
  void SetFixedCut(int port, const std::vector<std::array<int, 2>>& bricks);
  void RemoveAllFixedCuts();
  ///@}

  ///@{
  /// The same cuts as two-component arrays (level, brick), one tuple a brick, for Python.
  void GetCutBricks(int port, vtkIntArray* bricks) const;
  void SetFixedCut(int port, vtkIntArray* bricks);
  ///@}

  ///@{
  /**
   * Hold the cut (default off): while on, a render reuses the cut, atlas and index textures of
   * the render before it (no cut update, page load or upload, no feedback read) and feedback
   * rays add to the buffer the last unheld render cleared, keeping the costliest lacking brick
   * per texel over all held renders. For callers that draw one frame in several passes, such as
   * vtkHybridVolumeMapper's depth slabs: the frame shows one cut, and its feedback covers every
   * pass; GetPagingStatistics() stays that of the last unheld render, the frame's. Has no
   * effect on the first render or after the volumes, brick size or budget change.
   */
  vtkSetMacro(HoldCut, bool);
  vtkGetMacro(HoldCut, bool);
  vtkBooleanMacro(HoldCut, bool);
  ///@}

  /// The stage the rays are cast in (the values of strata::ComputeStage::Stages).
  enum class Stages
  {
    Auto,     ///< the faster of the two on this device, by a probe at the first render
    Fragment, ///< fragment shaders over each BSP fragment's back faces
    Compute,  ///< compute shaders over each BSP fragment's screen rectangle
  };

  ///@{
  /**
   * The stage (default Auto, or the environment's STRATA_RAY_CASTING_STAGE: Auto, Fragment or
   * Compute). Both stages run the same composed program, feature for feature; data-centre GPUs
   * run compute shaders many times faster than fragment shaders. Auto times the same kernel in
   * both once per device (GL_RENDERER) and process; Compute falls back to Fragment, with a
   * warning, without OpenGL 4.3 or where the rays' buffers need more image units than the
   * device has (2 + rays per pixel, + 1 with translucent surfaces).
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
   * Rays per pixel, 1 to 8 (default 1): anti-aliasing. Ray r starts at a sub-pixel position of a
   * fixed pattern and at a lattice phase staggered by r / R of the sample distance; the pixel is
   * the mean of its rays, each composited through all fragments on its own.
   */
  vtkSetClampMacro(RaysPerPixel, int, 1, 8);
  vtkGetMacro(RaysPerPixel, int);
  ///@}

  ///@{
  /**
   * Sub-pixel ray coherence (default off): with several rays per pixel, rays after the centre
   * one start where the centre ray first met a non-empty sample in the fragment, skipping the
   * empty space it crossed (exact where the empty space is wider than the pixel's footprint).
   */
  vtkSetMacro(RayCoherence, bool);
  vtkGetMacro(RayCoherence, bool);
  vtkBooleanMacro(RayCoherence, bool);
  ///@}

  ///@{
  /**
   * Compositing order (default FrontToBack). Both give the same image up to rounding and the
   * early-termination threshold.
   */
  void SetCompositeOrder(CompositeOrders order);
  CompositeOrders GetCompositeOrder() const { return this->CompositeOrder; }
  ///@}

  ///@{
  /**
   * Accumulated opacity at which front-to-back rays stop (default 0.999): the colour left out is
   * at most 1 - this of the pixel.
   */
  vtkSetClampMacro(TerminationOpacity, double, 0.5, 1.0);
  vtkGetMacro(TerminationOpacity, double);
  ///@}

  ///@{
  /**
   * The region this mapper draws (default none: the whole scene), a world box, for sort-last
   * parallel rendering in which each process draws one box of a partition of the scene and the
   * images are blended in box order (ParaView's ordered compositing over MPI ranks). Rays are
   * clipped to the box like by the faces of their BSP fragments, on the sample lattice every
   * process shares (anchored at the near plane): the step across a face is split there, as one
   * process splits steps at every fragment face, so the boxes of a partition together
   * integrate what one process would (within a step's split; TestParallel.py measures it), and
   * opaque geometry cut to the same box ends the rays at the same depths. The image is
   * premultiplied RGBA over what was drawn before (transparent black in IceT). Bricks that the
   * box grown by one sample distance and one voxel of their level misses count as empty: they
   * are neither paged, stored in the atlas nor sampled, so a process pages only its own share.
   * Fragments of the BSP tree outside the box are not drawn.
   */
  void SetRegion(const double bounds[6]);
  void RemoveRegion();
  /// False when no region is set.
  bool GetRegion(double bounds[6]) const;
  ///@}

  ///@{
  /**
   * Blend mode of the volume on input port `port`, one of vtkVolumeMapper::BlendModes
   * (COMPOSITE, MAXIMUM_INTENSITY, MINIMUM_INTENSITY, AVERAGE_INTENSITY, ADDITIVE,
   * ISOSURFACE); -1 (the default for every port) uses the mapper's own BlendMode
   * (SetBlendMode, default COMPOSITE), so a single volume behaves like VTK's mappers.
   * GetInputBlendMode returns what was set, GetEffectiveBlendMode what is drawn. SLICE is not
   * supported (drawn as COMPOSITE, with a warning).
   *
   * Where volumes of different modes overlap: composite volumes are media that mix (see the
   * class comment). An ISOSURFACE volume adds no medium: every crossing of one of its
   * property's isovalues (vtkVolumeProperty::GetIsoSurfaceValues) is a surface of the colour
   * and opacity its transfer functions give that value (shaded like the volume), composited
   * where it lies among the media. A MAXIMUM/MINIMUM/AVERAGE/ADDITIVE volume is reduced alone
   * along the ray over its whole box (the media of the others do not enter it) and the result is
   * one layer composited among the media at its own depth: at the sample of the maximum
   * (minimum), with the colour and opacity of that scalar; at the ray's entry into the volume for
   * AVERAGE and ADDITIVE, opaque grey as in VTK: AVERAGE the mean over the ray of opacity(s)
   * times s normalised to the transfer functions' range, over the samples inside
   * AverageIPScalarRange; ADDITIVE the same sum with each sample weighted by its length over
   * ScalarOpacityUnitDistance (VTK's per-sample sum when the two are equal), both clamped to 1.
   * A layer lands before the sample step that contains its depth. Reductions need texture
   * barriers (OpenGL 4.5 or ARB/NV_texture_barrier); they cost one pass per reduced volume.
   */
  void SetInputBlendMode(int port, int mode);
  int GetInputBlendMode(int port) const;
  int GetEffectiveBlendMode(int port) const;
  ///@}

  /*
   * Gradient opacity: a volume whose property has a gradient opacity function
   * (vtkVolumeProperty::SetGradientOpacity, not disabled) and is drawn COMPOSITE with
   * post-classification has each sample's opacity scaled by that function of the gradient
   * magnitude (scalar per world unit; central differences one voxel apart in index space, the
   * trilinear interpolant even for nearest volumes). Pre-integrated classification ignores it.
   */

  ///@{
  /**
   * Cropping per volume, vtkVolumeMapper's 27 regions (all flags: VTK_CROP_SUBVOLUME, FENCE,
   * CROSS, their inversions, any other bit set), beside the clipping planes. The mapper's own
   * Cropping, CroppingRegionPlanes and CroppingRegionFlags apply to every volume whose port has
   * none of its own; SetInputCropping gives port `port` its own (`cropping` false: that volume
   * uncropped whatever the mapper's), RemoveInputCropping returns it to the mapper's. Planes
   * (xmin, xmax, ymin, ymax, zmin, zmax) are in the volume's data coordinates, origin + index x
   * spacing per axis, before its direction matrix and prop transform, as in VTK; a region is
   * shown when bit x + 3 y + 9 z of the flags is set (x, y, z: 0 below an axis's first plane, 1
   * between, 2 above). Decided per sample (at the step's midpoint): a cropped-away sample of a
   * volume adds nothing, the other volumes there still do. GetEffectiveCropping: whether port
   * `port` is cropped, with its planes and flags.
   */
  void SetInputCropping(int port, bool cropping, const double planes[6], int flags);
  void RemoveInputCropping(int port);
  bool GetEffectiveCropping(int port, double planes[6], int& flags) const;
  ///@}

  ///@{
  /**
   * Translucent geometry among the volumes: actors (opacity below 1, any polygonal mapper) whose
   * surfaces each ray composites at the exact depth where it crosses them, in order with the
   * volume samples, front to back (e.g. a plane of opacity 0.4 through two overlapping volumes).
   * Give them to this mapper instead of the renderer (a renderer would blend them before the
   * volumes, over or under everything; add them there too and they are drawn twice); the
   * renderer's camera and lights draw them. Opaque geometry stays in the renderer and still
   * stops the rays (and hides surfaces behind it).
   *
   * How: each frame the actors are depth-peeled into TranslucentLayers layers (default 4, at
   * most 7) of colour and window depth per pixel, in front of the opaque depth
   * (strata::VolumeSurfaceLayers, a vtkOpenGLRenderPass on each actor's property keys); a ray
   * splits its lattice step at each layer it crosses and composites the layer there; layers in
   * front of, between or behind the volumes' fragments are composited in ray order too. Where
   * more than TranslucentLayers surfaces overlap a pixel, the farthest are dropped. A MIP,
   * MinIP, average or additive volume's layer (see SetInputBlendMode) and an isosurface are
   * composited with the surfaces in the order of their depths. Layers are
   * peeled once per pixel (at its centre): with several rays per pixel the surfaces' edges are
   * not anti-aliased. Needs the
   * front-to-back order and texture barriers (else the actors are not drawn, with a warning).
   * A scene without translucent actors compiles no surface code.
   *
   * Why not vtkDualDepthPeelingPass (vtkRenderer::UseDepthPeelingForVolumes): in VTK 9.1 it
   * injects code written for vtkOpenGLGPUVolumeRayCastMapper's own shader (its castRay(zStart,
   * zEnd), g_dataPos, ip_textureCoords, in_inverseVolumeMatrix) and expects one draw per volume
   * and peel writing its front/back blend targets; this mapper draws one program per BSP
   * fragment into its own float integration buffers.
   */
  void AddTranslucentActor(vtkActor* actor);
  void RemoveAllTranslucentActors();
  int GetNumberOfTranslucentActors() const;
  vtkSetClampMacro(TranslucentLayers, int, 1, 7);
  vtkGetMacro(TranslucentLayers, int);
  ///@}

  /**
   * Sub-pixel offset (in pixels from the pixel centre) of ray `ray` of `rays`; the offsets of
   * the R rays average to the centre. Tests and references use it to integrate the same rays.
   */
  static void GetRayOffset(int ray, int rays, double offset[2]);

  ///@{
  /**
   * Measure the render time (default off): each Render waits for the GPU to finish and records
   * its wall time in PagingStatistics::RenderMilliseconds. For benchmarks that must tell this
   * mapper's share of a frame from the rest (IceT's compositing, in parallel); the wait costs
   * the overlap of CPU and GPU work, so it is off otherwise.
   */
  vtkSetMacro(MeasureRenderTime, bool);
  vtkGetMacro(MeasureRenderTime, bool);
  vtkBooleanMacro(MeasureRenderTime, bool);
  ///@}

  /// Number of BSP fragments drawn in the last frame.
  int GetNumberOfFragments() const;

  ///@{
  /**
   * Shader sources built and programs compiled (handed to VTK's shader cache, or compiled
   * again after a release) since the mapper was made, counted by its composer
   * (strata::MultiVolumeShaderComposer): a frame that draws what the last one drew adds nothing.
   */
  int GetNumberOfShaderSourcesBuilt() const;
  int GetNumberOfShaderCompilations() const;
  ///@}

  ///@{
  /**
   * The source of the program the last render ran for a fragment covered by `numberOfVolumes`
   * volumes, in its stage (GetStageInUse: a fragment or a compute shader), empty if no such
   * fragment was drawn; the fragment stage's or the compute stage's source of that program
   * (empty if never built). For tests: a fragment of one unshaded volume must carry no loop
   * over other volumes, in either stage.
   */
  std::string GetShaderSource(int numberOfVolumes) const;
  std::string GetFragmentShaderSource(int numberOfVolumes) const;
  std::string GetComputeShaderSource(int numberOfVolumes) const;
  ///@}
  /// The reduction pass's source for blend mode `blendMode` as the last render ran it, in its
  /// stage (empty if no volume of that mode was drawn).
  std::string GetReductionShaderSource(int blendMode) const;

  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void GPURender(vtkRenderer* ren, vtkVolume* vol) override;
  /// Asks page-pool readers for their coarsest level (see PageCacheBudget).
  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  void GetReductionRatio(double ratio[3]) override;

protected:
  vtkMultiVolumeRayCastMapper();
  ~vtkMultiVolumeRayCastMapper() override;

  void PreRender(vtkRenderer*, vtkVolume*, double[6], double[2], int, unsigned int) override {}
  void RenderBlock(vtkRenderer*, vtkVolume*, unsigned int) override {}
  void PostRender(vtkRenderer*, int) override {}

  CompositeOrders CompositeOrder = CompositeOrders::FrontToBack;
  Classifications Classification = Classifications::PostClassification;
  int PreIntegrationTableSize = 256;
  int RaysPerPixel = 1;
  Stages Stage = Stages::Auto;
  bool UseBrickAtlas = true;
  ScalarStorages ScalarStorage = ScalarStorages::Normalized16;
  int BrickSize = 32;
  double AtlasBudget = 256.0;
  bool EmptySpaceSkipping = true;
  double PageCacheBudget = 512.0;
  int PagesPerFrame = 64;
  bool Prefetch = false;
  bool PrefetchTimeSteps = true;
  int SkipCellSize = 8;
  bool RayCoherence = false;
  double TerminationOpacity = 0.999;
  bool LevelOfDetailFeedback = true;
  int FeedbackScale = 4;
  bool FeedbackOpenCL = true;
  double LevelOfDetailThreshold = 0.0;
  bool HoldCut = false;
  strata::Region Region;
  bool MeasureRenderTime = false;
  int TranslucentLayers = 4;
  std::map<int, int> InputBlendModes; ///< by port; absent: the mapper's BlendMode
  struct InputCrop
  {
    bool Cropping = false;
    double Planes[6] = { 0, 0, 0, 0, 0, 0 };
    int Flags = 0;
  };
  std::map<int, InputCrop> InputCroppings; ///< by port; absent: the mapper's cropping

private:
  vtkMultiVolumeRayCastMapper(const vtkMultiVolumeRayCastMapper&) = delete;
  void operator=(const vtkMultiVolumeRayCastMapper&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
