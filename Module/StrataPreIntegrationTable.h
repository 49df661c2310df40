// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::PreIntegrationTable
 * @brief   Pre-integrated classification of ray segments: full 2-D table, two-integral form.
 *
 * Post-classification samples the transfer function (TF) once per step, so TF features that the
 * scalar crosses between two samples are missed or alias into rings (the integrand's Nyquist
 * rate is the product of the field's and the TF's). Pre-integration (Engel, Kraus and Ertl 2001;
 * Bogolepov et al., papers/pre-integrated-ray-casting-fsaa) classifies a segment by its front and
 * back scalar and integrates the TF in between, so a step only has to resolve the field.
 *
 * Model, fixed for Strata: emission-absorption of physically mixed media. The TF is N entries
 * at equally spaced scalars over [ScalarMin, ScalarMax], linear between entries: colour c(s)
 * (RGB) and extinction tau(s) per unit length; the medium emits c tau per unit length
 * (associated colour). A segment of length d along which the scalar goes linearly from s_f
 * (front) to s_b (back), s(w) = s_f + w (s_b - s_f), has
 *
 *     alpha = 1 - exp(-d int_0^1 tau(s(w)) dw)
 *     C     = d int_0^1 c(s(w)) tau(s(w)) exp(-d int_0^w tau(s(w')) dw') dw   (premultiplied)
 *
 * and segments composite front to back: C_acc += (1 - A_acc) C; A_acc += (1 - A_acc) alpha.
 * Scalars are clamped to [ScalarMin, ScalarMax], as VTK's transfer functions clamp.
 * x = (s - ScalarMin) / (ScalarMax - ScalarMin) in [0, 1] is the normalised scalar used below.
 *
 * Evaluations (the Lookup* methods are CPU copies of the shader code, in float, for tests):
 * - Classify(): post-classification, alpha = 1 - exp(-d tau(s)), C = c(s) alpha.
 * - Integrate(): the exact segment integral for any (s_f, s_b, d), for reference integrators.
 * - full table: the segment integral for one step length d at M x M sample pairs,
 *   LookupFullTable() its bilinear texture lookup. Exact per linear piece of the TF except a
 *   4-point Gauss-Legendre rule for the mean opacity of sub-pieces of optical depth <= 0.5:
 *   error <= 1.3e-8 times the colour's total variation along the segment, far below float
 *   rounding (3e-8) and the table's interpolation error.
 * - two-integral form (the paper's approximation): 1-D prefix integrals T = int tau,
 *   K = int c tau, independent of d; LookupTwoIntegral() ignores the order of emission and
 *   absorption inside a segment.
 *
 * The s_b -> s_f limit (0/0 in the paper's formulas) never divides by a small difference:
 * Integrate() integrates over w and divides by s_b - s_f only to place TF entries strictly
 * between s_f and s_b; the full table's diagonal is Classify() and its lookup only interpolates;
 * the two-integral lookup widens a segment's scalar interval to one table spacing around its
 * mean when it is narrower (see LookupTwoIntegral()).
 *
 * Plain C++: the volume mapper uploads the tables as float textures, tests read them directly.
 *
 * @sa vtkVolumeProperty
 */
#ifndef StrataPreIntegrationTable_h
#define StrataPreIntegrationTable_h

#include "StrataCoreModule.h" // For export macro

#include <array>   // For std::array
#include <cstdint> // For std::uint64_t
#include <vector>  // For std::vector

namespace strata
{
class STRATACORE_EXPORT PreIntegrationTable
{
public:
  PreIntegrationTable();

  /**
   * Extinction per unit length for VTK's opacity alpha per unit distance u
   * (vtkVolumeProperty::ScalarOpacityUnitDistance): tau = -ln(1 - alpha) / u, so a segment of
   * length d gets VTK's corrected opacity 1 - (1 - alpha)^(d/u). alpha is clamped to
   * [0, 1 - 1e-6]: alpha = 1 would give tau = inf, which turns the prefix integrals into inf and
   * their differences into NaN; 1 - 1e-6 leaves 1e-6 of the light after one unit distance,
   * far below what an 8-bit display shows, and tau u = 13.8 stays finite.
   */
  static double OpacityToExtinction(double alpha, double unitDistance);

  /**
   * Sets the TF: n >= 1 entries at equally spaced scalars over [scalarMin, scalarMax]
   * (scalarMin < scalarMax, both finite), rgb = 3n colours, tau = n extinctions per unit length.
   * NaN or negative values become 0; tau is capped at 1e30 and colours at 1e6 so that every
   * table stays finite in float. Returns false and keeps the previous TF on invalid input.
   * Setting the same TF again invalidates nothing. Default: 2 entries, white, tau = 0, [0, 1].
   */
  bool SetTransferFunction(double scalarMin,
    double scalarMax,
    int n,
    const double* rgb,
    const double* tau);
  double GetScalarMin() const { return this->ScalarMin; }
  double GetScalarMax() const { return this->ScalarMax; }
  int GetNumberOfEntries() const { return static_cast<int>(this->Tau.size()); }
  /// Largest colour component of the TF (a uniform of the two-integral shader code).
  double GetMaximumColor() const { return this->MaxColor; }

  ///@{
  /**
   * Number M of table samples per scalar axis, clamped to [2, 4096]; default 256. Sample i is
   * at x_i = i / (M - 1). The full table takes 16 M^2 bytes (1 MiB for 256, 16 MiB for 1024).
   */
  void SetTableSize(int m);
  int GetTableSize() const { return this->TableSize; }
  ///@}

  ///@{
  /**
   * Step length d (world units) of the full table, >= 0 (capped at 1e30; NaN and negative
   * values are ignored); default 1. The integral table does not depend on it.
   */
  void SetStepLength(double d);
  double GetStepLength() const { return this->StepLength; }
  ///@}

  /**
   * Rebuild the table if its inputs changed since the last build; return true if rebuilt
   * (the owner uploads it again then). Each build also increments the build count, so a
   * mapper can compare the count it uploaded instead of tracking the return value.
   */
  bool UpdateFullTable();
  bool UpdateIntegralTable();
  unsigned long GetFullTableBuildCount() const { return this->FullBuildCount; }
  unsigned long GetIntegralTableBuildCount() const { return this->IntegralBuildCount; }

  /**
   * Hash (FNV-1a) of every input: TF, range, M and d. For owners that cache tables across
   * objects; an owner of a single table only needs the Update*() return values.
   */
  std::uint64_t GetHash() const;

  /**
   * Full table, M x M RGBA (premultiplied C, alpha), valid after UpdateFullTable().
   * Entry (i_f, i_b) for s_f = x_{i_f}, s_b = x_{i_b} is at float index 4 (i_b M + i_f): rows
   * are s_b. Upload as a 2-D RGBA32F texture, width (s_f) and height (s_b) M, LINEAR filtering,
   * CLAMP_TO_EDGE, read at u = (x_f (M - 1) + 0.5) / M, v = (x_b (M - 1) + 0.5) / M
   * (texel centres at the samples). The diagonal i_f = i_b is Classify(x_i, d).
   */
  const std::vector<float>& GetFullTable() const { return this->FullTable; }

  /**
   * Integral table, M RGBA entries (K_r, K_g, K_b, T) at x_i, valid after UpdateIntegralTable():
   * T(x) = int_0^x tau dx', K(x) = int_0^x c tau dx' over the normalised scalar, so that
   * (T(x_b) - T(x_f)) / (x_b - x_f) is the mean extinction per unit length. Exact at the
   * samples (prefix sums in double). Upload as a 1-D RGBA32F texture of width M; coordinate
   * as for the full table.
   */
  const std::vector<float>& GetIntegralTable() const { return this->IntegralTable; }

  /**
   * The TF itself, N RGBA entries (r, g, b, tau) at x_j = j / (N - 1), for post-classification
   * on the GPU: a 1-D RGBA32F texture read at u = (x (N - 1) + 0.5) / N with LINEAR filtering
   * is the piecewise-linear TF that Classify() and Integrate() use.
   */
  std::vector<float> GetTransferFunctionTable() const;

  /// Post-classification of a segment of length d at constant scalar s: {C_r, C_g, C_b, alpha}.
  std::array<double, 4> Classify(double s, double d) const;

  /**
   * Exact segment integral {C_r, C_g, C_b, alpha} (the model above) for any s_f, s_b, d >= 0,
   * computed like the full table's entries (same error bound). s_b == s_f is Classify(); no
   * threshold is needed otherwise, so the result is continuous in s_b down to 1 ulp.
   */
  std::array<double, 4> Integrate(double sf, double sb, double d) const;

  /**
   * What the shader gets from the full table at (s_f, s_b): bilinear interpolation between
   * texel centres, in float. Requires UpdateFullTable(). Hardware filtering may quantise the
   * weights (8 fractional bits on NVIDIA GPUs): then the GPU differs from this by at most 1/512
   * of the difference between neighbouring texels.
   */
  std::array<float, 4> LookupFullTable(float sf, float sb) const;

  /**
   * What the shader gets from the two-integral form for a segment of any length d, in float.
   * Requires UpdateIntegralTable(). With h = 1 / (M - 1), I(x) the table linearly interpolated
   * between texel centres (use texelFetch and mix on the GPU: 8-bit filter weights would be
   * amplified by the division below) and cMax = GetMaximumColor():
   *
   *     w = max(|x_b - x_f|, h);  lo = clamp((x_f + x_b) / 2 - w / 2, 0, 1 - w);  hi = lo + w
   *     tau = max((T(hi) - T(lo)) / (hi - lo), 0)
   *     k = clamp((K(hi) - K(lo)) / (hi - lo), 0, cMax tau)
   *     X = d tau;  alpha = 1 - exp(-X);  C = d k (1 - exp(-X)) / X
   *
   * with alpha = X (1 - X/2 + X^2/6) and C = d k (1 - X/2 + X^2/6) for X < 0.01.
   * The paper's C = d k ignores that a segment absorbs its own emission: it always exceeds
   * (k / tau) alpha, the exact value for a homogeneous segment, and can exceed alpha. The factor
   * (1 - exp(-X)) / X <= 1 turns it into that value: C = (k / tau) alpha, the extinction-weighted
   * mean colour times alpha, and C <= cMax alpha. Threshold of the s_b -> s_f limit: one table
   * spacing h. Narrower segments take the mean over one spacing around their mean scalar, so
   * s_b == s_f is post-classification at the mean scalar with the TF as the 1-D table resolves
   * it (it cannot see inside a spacing); unlike a switch to the exact point value, this is
   * continuous across the threshold and never divides by less than h.
   * Float prefix sums limit precision: tau carries an absolute error of about
   * 2.4e-7 T(1) / (hi - lo), so TFs whose extinction spans many decades (tau = 1e30 next to
   * tau = 1) need the full table.
   */
  std::array<float, 4> LookupTwoIntegral(float sf, float sb, float d) const;

private:
  struct Piece; // a stretch of one table cell on which the TF is linear
  double Normalize(double s) const;
  float NormalizeF(float s) const;
  void EvaluateTF(double x, double rgb[3], double& tau) const;
  std::vector<Piece> BuildPieces(std::vector<int>& cellStart) const;

  double ScalarMin = 0.0;
  double ScalarMax = 1.0;
  std::vector<double> Rgb; // 3 N
  std::vector<double> Tau; // N
  double MaxColor = 1.0;
  int TableSize = 256;
  double StepLength = 1.0;

  bool FullTableValid = false;
  bool IntegralTableValid = false;
  unsigned long FullBuildCount = 0;
  unsigned long IntegralBuildCount = 0;
  std::vector<float> FullTable;
  std::vector<float> IntegralTable;
};
}

#endif
