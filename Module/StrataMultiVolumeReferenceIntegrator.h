// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::MultiVolumeReferenceIntegrator
 * @brief   Emission-absorption composite of overlapping volumes, in double precision, fine steps.
 *
 * The reference the GPU multi-volume ray caster is tested and benchmarked against. Overlapping
 * volumes mix physically (Lux and Froehlich, multi-volume ray casting: a region covered by
 * several volumes is one medium), so the reference does not depend on any fragment sorting.
 *
 * Conventions (fixed for the project):
 * - Volume: point data like vtkImageData. Point (i, j, k) lies at
 *   Origin + Direction * (i sx, j sy, k sz); the 4x4 ModelMatrix (the vtkVolume's prop matrix,
 *   affine, row-major, column vectors) maps that to world. Scalars are x fastest. The domain is
 *   the box spanned by the points, index range [0, n-1] per axis; an axis with n == 1 is one
 *   spacing thick, index range [-0.5, 0.5], values constant across it. Interpolation is nearest
 *   or trilinear, clamped at the borders, per volume.
 * - Classification: a transfer function tabulated as N entries over [smin, smax], piecewise
 *   linear in s, clamped outside; RGB colour c(s) and opacity alpha(s) per UnitDistance u
 *   (vtkVolumeProperty's ScalarOpacityUnitDistance). Table opacities are clamped to
 *   1 - 1e-6. Extinction tau = -ln(1 - alpha) / u, emission c tau (associated colour).
 * - Mixing: where volumes overlap, tau = sum tau_i and emission = sum c_i tau_i.
 * - Result per pixel: premultiplied RGB and alpha = 1 - transmittance, over a transparent
 *   background: C = int E(t) T(t) dt, T(t) = exp(-int tau).
 * - Camera: as strata::HeightFieldReferenceCaster, one ray per pixel centre from the near plane
 *   (NDC z = -1) to the far plane (z = +1) through a clip->world matrix (row-major, column
 *   vectors); images are bottom row first, 4 doubles per pixel. Optional per-pixel start and
 *   stop: window depths in [0, 1] (NDC z = 2 d - 1, glDepthRange(0, 1)) mapped through the
 *   same matrix, or world distances from the ray's near-plane point.
 * - Precision: all geometry is held relative to a local origin (the first volume's centre,
 *   rounded to an integer), so UTM-scale scenes (x ~ 6e5, y ~ 6.7e6) keep full precision in
 *   everything computed here: a translated scene and camera give the bitwise same image. The
 *   clip->local matrix is formed with fused multiply-adds. What no code can undo is the
 *   rounding of a UTM clip->world matrix itself: its translation column is off by up to
 *   ulp(6.7e6) / 2 = 4.7e-10, which perspective divides by w ~ 1 / eye distance (rays 30 units
 *   from the eye move by ~3e-9 world units).
 *
 * Integration. Each ray is clipped exactly against every volume's box (slabs in the volume's
 * index space) and cut into pieces at every volume's box faces and cell planes (integer planes
 * for trilinear, half-integer planes for nearest) and, inside trilinear cells, at the roots of
 * s(t) = s_k for every transfer-function node s_k where a slope changes (s(t) is a cubic in a
 * cell). Inside a piece tau and E are smooth. A piece lies in one cell of every volume covering
 * it, so its length is at most Lmax = min over those volumes of the cell's chord along the ray;
 * it is split into K = ceil(Lmax / h) equal steps, h = StepFraction * smallest voxel edge of the
 * scene (the ratio is taken 1e-12 smaller first, so that exactly integral ratios, as for
 * axis-aligned rays, do not round up by one on the last bit). Every step is composited with tau and
 * E taken at its midpoint and exact exponential attenuation: C += T (E / tau) (1 - exp(-tau dl)), T
 * *= exp(-tau dl). K depends only on the ray's direction and on which volumes cover a piece, and
 * pieces move continuously with the ray, so the image has no step-phase noise: it is continuous in
 * the camera and the scene.
 *
 * Error. Piecewise-constant classification (constant data, or nearest interpolation) is
 * integrated exactly, up to rounding (about 1e-16 per step). Otherwise the scheme is second
 * order; to leading order in h the error of a ray covering world length L is bounded by
 *   |dA| <= L h^2 Tau2 / 24,
 *   |dC| <= L h^2 (cmax Tau2 / 24 + E2 / 24 + (E0 Tau1 + E1 Tau0) / 12),
 * where Tau0, Tau1, Tau2 bound tau and its first and second derivatives along the ray and
 * E0, E1, E2 those of the emission (world units, summed over the volumes), and cmax is the
 * largest colour. (Midpoint error of the optical depth, h^3 tau'' / 24 a step; the emission
 * term of a step is off by h^3 (E'' / 24 + (E tau' - E' tau) / 12).)
 * GetErrorBound() evaluates this from the data (largest edge differences and face twists of
 * every volume, largest transfer-function slopes), so it is conservative. Rays stop once
 * T < TerminationTransmittance, which adds at most cmax times that.
 *
 * Blend modes (Volume::Blend, numbered as vtkVolumeMapper::BlendModes). Composite volumes are the
 * media above. An IsoSurface volume adds no medium: each crossing of one of its IsoValues by its
 * (trilinear) scalar along the ray is a surface of colour c(v) and opacity alpha(v) (not scaled
 * by length), composited where it lies, between the media in front and behind. Maximum,
 * Minimum, Average and Additive volumes are each reduced alone over their whole chord and give
 * one layer, composited into the media at its depth: Maximum and Minimum at the scalar's largest
 * (smallest) value along the chord, colour c(s) alpha(s) and opacity alpha(s) there; Average and
 * Additive at the chord's entry, opaque grey g: Average g = int alpha(s) u dl / int dl over the
 * parts with s in AverageRange, Additive g = int alpha(s) u dl / UnitDistance, both clamped to
 * [0, 1], with u = (s - smin) / (smax - smin) over the table's range (VTK's definitions with
 * samples made into lengths). Reductions take midpoint samples every StepLength() (the extreme is
 * found to O(s'' h^2 / 8)).
 *
 * Gradient opacity (TransferFunction::GradientOpacity) scales a composite volume's opacity by a
 * function of its gradient magnitude |grad s| (world units), the gradient by central differences
 * of the interpolated scalar one voxel apart in index space (as the GPU takes it), evaluated at
 * every step's midpoint; the pieces are not cut at its kinks, so its error is first order where
 * the magnitude crosses one.
 *
 * Components (Volume::ComponentMode, vtkVolumeProperty's rules; composite volumes only). Each of
 * a volume's NumberOfComponents is interpolated on its own. Independent (2-4 components):
 * component i has its own function (Classification for i = 0, ComponentClassifications[i - 1]
 * after, each with its own UnitDistance) giving tau_i and c_i, and weight w_i in [0, 1]; they
 * make one medium of extinction sigma = sum_(w_i > 0) tau_i^2 / sum w_i tau_i and emission
 * sum w_i c_i tau_i. That is vtkGPUVolumeRayCastMapper's per-sample rule (opacity
 * sum a_i^2 / sum w_i a_i, colour sum w_i c_i a_i for step opacities a_i) in the limit of short
 * steps, so it does not depend on the sample distance. ColorOpacity (2 components): colour
 * c(s_0), opacity alpha(s_1), both from Classification. RGBA (4 components): colour
 * (s_k - ColorRange[k][0]) / (ColorRange[k][1] - ColorRange[k][0]), clamped to [0, 1], for
 * k = 0, 1, 2 (the caller states how its data type maps to colour), opacity alpha(s_3).
 * Pieces are cut at the kinks of every component's function. GetErrorBound() counts component
 * 0 alone (its bound is not derived for the mixing rules).
 *
 * Cropping (Volume::Cropping) hides a volume where its index point lies in a region whose flag is
 * off: the ray is cut at the crop planes too, and a piece (or a reduction's sample) of the volume
 * in a hidden region is left out, as if that volume were not there.
 *
 * Translucent surfaces (Surface, AddSurface): parallelograms of constant premultiplied colour
 * and opacity, such as a translucent vtkActor lit by ambient light alone. Each crossing of a ray
 * with one is a layer at its exact depth: the ray is cut there and the layer is composited over
 * what lies behind it, in ray order with the media, the isosurfaces and the reduced layers
 * (exact, up to rounding: no discretisation of its own). A surface beyond the ray's stop (opaque
 * geometry) is not reached. Curved surfaces come as crossing functions (AddSurfaceCrossings):
 * each gives, for a ray, its crossings and their colours, such as the translucent horizons of
 * a height-field stack (strata::HeightFieldReferenceCaster::CastAll, every root of every horizon's
 * bilinear patches); crossings at equal depth are composited in the order given.
 *
 * Limits: model matrices must be affine; boxes are closed, so a ray lying exactly in a face
 * shared by two volumes sees both (a set of measure zero); NaN scalars classify as the first
 * table entry. Cost: about 50 ns per step and covering volume on one core, steps h apart
 * (more where many volumes cut a ray into short pieces, each of which gets K steps); image
 * rows are split over std::thread.
 *
 * Plain C++17, no VTK: usable from tests, benchmarks and tools alike.
 *
 * @sa strata::HeightFieldReferenceCaster
 */
#ifndef StrataMultiVolumeReferenceIntegrator_h
#define StrataMultiVolumeReferenceIntegrator_h

#include "StrataCoreModule.h" // For export macro

#include <array>      // For std::array
#include <functional> // For std::function
#include <memory>     // For std::unique_ptr
#include <string>     // For std::string
#include <vector>     // For std::vector

namespace strata
{
class STRATACORE_EXPORT MultiVolumeReferenceIntegrator
{
public:
  enum class Interpolation
  {
    Nearest,
    Linear
  };

  /// How per-pixel start and stop values are given to IntegrateImage().
  enum class DepthKind
  {
    WindowDepth,  ///< window depth in [0, 1], through the clip->world matrix
    WorldDistance ///< world distance from the ray's near-plane point
  };

  /// As vtkVolumeMapper::BlendModes (Module/ links no VTK rendering): see the class comment.
  enum class Blend
  {
    Composite = 0,
    Maximum = 1,
    Minimum = 2,
    Average = 3,
    Additive = 4,
    IsoSurface = 5
  };

  struct TransferFunction
  {
    double Range[2] = { 0.0, 1.0 }; ///< [smin, smax] of the table; smin < smax unless N == 1
    std::vector<double> Opacity;    ///< N >= 1 entries, alpha per UnitDistance
    std::vector<double> Color;      ///< 3 N entries (RGB), or empty for white
    double UnitDistance = 1.0;      ///< world length the opacities refer to, > 0
    /// Gradient opacity: entries evenly over GradientRange of the gradient magnitude (scalar
    /// per world unit), piecewise linear, clamped; empty for none. It scales alpha.
    std::vector<double> GradientOpacity;
    double GradientRange[2] = { 0.0, 1.0 };
  };

  /// How a volume's point components are classified (see the class comment).
  enum class Components
  {
    One,          ///< one scalar through Classification
    Independent,  ///< 2-4 components, each through its own function and weight
    ColorOpacity, ///< 2: colour of the first, opacity of the second
    RGBA          ///< 4: the first three the colour, opacity of the fourth
  };

  struct Volume
  {
    int Dimensions[3] = { 1, 1, 1 };
    double Origin[3] = { 0.0, 0.0, 0.0 };
    double Spacing[3] = { 1.0, 1.0, 1.0 };
    double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };                         ///< row-major
    double ModelMatrix[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }; ///< row-major
    /// Point scalars, x fastest, NumberOfComponents per point (interleaved): fill exactly one
    /// of the two (float is what the GPU sees).
    std::vector<double> Scalars;
    std::vector<float> FloatScalars;
    int NumberOfComponents = 1; ///< 1 to 4, as ComponentMode requires
    Components ComponentMode = Components::One;
    /// Independent: the functions of components 1, 2, ... (component 0's is Classification).
    std::vector<TransferFunction> ComponentClassifications;
    double ComponentWeights[4] = { 1.0, 1.0, 1.0, 1.0 }; ///< Independent, each in [0, 1]
    /// RGBA: the scalars that map to colour 0 and 1, per colour component.
    double ColorRange[3][2] = { { 0.0, 1.0 }, { 0.0, 1.0 }, { 0.0, 1.0 } };
    Interpolation Sampling = Interpolation::Linear;
    TransferFunction Classification;
    Blend BlendMode = Blend::Composite;
    std::vector<double> IsoValues;                  ///< IsoSurface: the contour values
    double AverageRange[2] = { -1.0e300, 1.0e300 }; ///< Average: the scalars that count
    /// Cropping as vtkVolumeMapper's 27 regions: planes (xmin, xmax, ymin, ymax, zmin, zmax) in
    /// index coordinates; bit x + 3 y + 9 z of CropFlags shows region (x, y, z), 0 below an
    /// axis's first plane, 1 between, 2 above.
    bool Cropping = false;
    double CropPlanes[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
    int CropFlags = 0x0002000; ///< VTK_CROP_SUBVOLUME
  };

  /// A translucent parallelogram Corner + u Edge1 + v Edge2, u and v in [0, 1] (world).
  struct Surface
  {
    double Corner[3] = { 0.0, 0.0, 0.0 };
    double Edge1[3] = { 1.0, 0.0, 0.0 };
    double Edge2[3] = { 0.0, 1.0, 0.0 };
    double Color[4] = { 0.0, 0.0, 0.0, 0.0 }; ///< premultiplied RGB and opacity
  };

  /// A crossing of a ray with a surface: its ray parameter and premultiplied colour.
  struct Crossing
  {
    double T = 0.0;
    double Color[4] = { 0.0, 0.0, 0.0, 0.0 };
  };
  /**
   * Appends the crossings of origin + t direction (world coordinates) for t in [t0, t1) to
   * the list, in ray order; called from several threads at once.
   */
  using CrossingFunction = std::function<void(const double origin[3],
    const double direction[3],
    double t0,
    double t1,
    std::vector<Crossing>& crossings)>;

  /// Leading-order discretisation error bounds, per RGBA component (see the class comment).
  struct ErrorBound
  {
    double Alpha = 0.0;
    double Color = 0.0;
  };

  MultiVolumeReferenceIntegrator();
  ~MultiVolumeReferenceIntegrator();
  MultiVolumeReferenceIntegrator(const MultiVolumeReferenceIntegrator&) = delete;
  MultiVolumeReferenceIntegrator& operator=(const MultiVolumeReferenceIntegrator&) = delete;

  /**
   * Adds a volume (taken by value: move large scalars in). Returns its index, or -1 when the
   * description is invalid (GetLastError() says why). The first volume fixes the local origin.
   */
  int AddVolume(Volume volume);
  void RemoveAllVolumes();
  /// Adds a translucent surface (see the class comment); it stays until RemoveAllSurfaces.
  void AddSurface(const Surface& surface);
  void RemoveAllSurfaces();
  /// Adds a source of surface crossings (see the class comment); removed by RemoveAllSurfaces.
  void AddSurfaceCrossings(CrossingFunction crossings);
  int GetNumberOfVolumes() const;
  const std::string& GetLastError() const;

  ///@{
  /**
   * Largest step as a fraction of the smallest voxel edge (world length) of the scene.
   * Default 1/16.
   */
  void SetStepFraction(double fraction);
  double GetStepFraction() const;
  ///@}
  /// The largest step h in world units (0 without volumes).
  double GetStepLength() const;
  /// Smallest world-space voxel edge over all volumes (0 without volumes).
  double GetSmallestVoxelSize() const;

  ///@{
  /**
   * Rays stop once their transmittance falls below this. Default 1e-14.
   */
  void SetTerminationTransmittance(double transmittance);
  double GetTerminationTransmittance() const;
  ///@}

  ///@{
  /**
   * Threads IntegrateImage() splits rows over; 0 uses all cores. Default 0.
   */
  void SetNumberOfThreads(int threads);
  int GetNumberOfThreads() const;
  ///@}

  /// World point the scene's geometry is held relative to.
  void GetLocalOrigin(double origin[3]) const;

  /**
   * Composite along origin + t * direction for t in [t0, t1] (world coordinates; direction
   * need not be unit length). Returns premultiplied {R, G, B, A}.
   */
  std::array<double, 4> IntegrateRay(const double origin[3],
    const double direction[3],
    double t0,
    double t1) const;

  /**
   * One ray per pixel centre of a width x height image through clipToWorld (row-major 4x4,
   * column vectors), near plane to far plane. Optional start and stop hold width * height
   * values (bottom row first) of the given kind; a ray runs from the later of its near point
   * and start to the earlier of its far point and stop. Fills rgba with 4 values per pixel.
   */
  void IntegrateImage(const double clipToWorld[16],
    int width,
    int height,
    std::vector<double>& rgba,
    const double* start = nullptr,
    const double* stop = nullptr,
    DepthKind kind = DepthKind::WindowDepth) const;

  /**
   * Leading-order bound on the discretisation error of a ray covering world length
   * `length` of volume, at the current step (see the class comment).
   */
  ErrorBound GetErrorBound(double length) const;

private:
  /// What a volume must be for the integrator (vtkMultiVolumeReferenceValidation.cxx): null
  /// when it is, else why not.
  static const char* Validate(const Volume& volume);

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};
}

#endif
