// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::HybridVolumeBuilder
 * @brief   Preprocessing of the hybrid point/volume representation: low-resolution volume
 *          plus points where it is wrong.
 *
 * Wilson, Ma and McCormick's preprocessing ("A hybrid point and volume rendering", section
 * "Preprocessing"), streamed: the original volume is read twice, slab by slab, through a
 * callback, so volumes far larger than memory can be converted.
 *
 * Pass 1, low resolution. Low-resolution point L sits at original index c = L f per axis
 * (geometry in strata::HybridVolumeFile); its value is the separable filter sum_d w(d) s(c + d)
 * over original samples, indices clamped to the volume, weights normalised to sum 1:
 * - Box: |d| < f/2 weight 1, |d| = f/2 weight 1/2 (a box of width f, centred).
 * - Linear: tent 1 - |d|/f, |d| < f.
 * - Cubic: Catmull-Rom (Keys, a = -1/2) scaled by f, |d| < 2f (the paper's default).
 * - Optimized: the paper's compromise for non-decreasing transfer functions: the cubic value,
 *   capped at min(s(x)) + bound over the original samples x the low-resolution value
 *   influences (|x - c| < f on every axis). Trilinear weights are non-negative and sum to 1,
 *   so the reconstruction never exceeds the original by more than the bound anywhere
 *   (bound 0: the paper's "minimum function"; the value is rounded down to float).
 * Each original slice is filtered in x and y as it is read; only the (4f - 1) filtered planes
 * the z filter needs are kept.
 *
 * Pass 2, error and points. The error grid is every ErrorGridStep-th original point per axis
 * (index i s for i s <= n - 1; step 1 is the original resolution). The error is
 * e = s(x) - Reconstruct(x), evaluated in double. Selection: every point with |e| > Threshold;
 * with a PointBudget N > 0, only the N largest |e| among them, ties broken by the smaller
 * linear index (x fastest), so the output is deterministic. Points are emitted in linear
 * index order. Normals are central differences of the original data in world units
 * (one-sided at the border), encoded by strata::HybridVolumeFile::EncodeNormal.
 *
 * Memory: MemoryLimit bounds the original slices held at once (read chunk plus the 3 slices
 * of the central differences); the outputs (low-resolution volume, points, and the budget
 * heap of N points) are not counted. Output is identical for any limit.
 *
 * @sa strata::HybridVolumeFile
 */
#ifndef StrataHybridVolumeBuilder_h
#define StrataHybridVolumeBuilder_h

#include "StrataCoreModule.h"       // For export macro
#include "StrataHybridVolumeFile.h" // For the output and FilterType

#include <cstddef>    // For size_t
#include <cstdint>    // For uint64_t
#include <functional> // For std::function
#include <string>     // For std::string

namespace strata
{
class STRATACORE_EXPORT HybridVolumeBuilder
{
public:
  using FilterType = strata::HybridVolumeFile::FilterType;
  /**
   * Fills `count` z slices starting at `first`, dims[0] * dims[1] floats each, x fastest,
   * into `out`. Returns false on a read error (the build then fails).
   */
  using SlabSource = std::function<bool(int first, int count, float* out)>;
  /// Called with the completed fraction in [0, 1] (pass 1 is the first half).
  using ProgressCallback = std::function<void(double fraction)>;

  /// The original volume: points per axis (each in [1, 65536]), spacing, origin, source.
  void SetInput(const int dims[3],
    const double spacing[3],
    const double origin[3],
    SlabSource source);

  ///@{
  /// Down-sampling factor per axis: 1, 2, 4 or 8 (default 2).
  void SetFactor(int f) { this->SetFactor(f, f, f); }
  void SetFactor(int fx, int fy, int fz);
  ///@}
  ///@{
  /// Down-sampling filter (default Cubic) and, for Optimized, the largest over-estimation
  /// allowed (default 0, >= 0).
  void SetFilter(FilterType filter) { this->Filter = filter; }
  FilterType GetFilter() const { return this->Filter; }
  void SetOverestimationBound(double bound) { this->OverestimationBound = bound; }
  double GetOverestimationBound() const { return this->OverestimationBound; }
  ///@}
  ///@{
  /// Error grid step per axis in original points, >= 1 (default 1: the original resolution).
  void SetErrorGridStep(int s) { this->SetErrorGridStep(s, s, s); }
  void SetErrorGridStep(int sx, int sy, int sz);
  ///@}
  ///@{
  /// Points need |error| > Threshold (default 0, >= 0), or Importance > Threshold when set.
  void SetThreshold(double t) { this->Threshold = t; }
  double GetThreshold() const { return this->Threshold; }
  ///@}

  /**
   * What a point is worth, from the original value and its reconstruction, in place of |error|
   * for the threshold and the budget (default: none, |error|). A renderer that can only add
   * opacity over the low-resolution volume gains nothing from a point whose value the transfer
   * function makes no more opaque than the reconstruction: with the opacity function known at
   * preprocessing, max(0, opacity(original) - opacity(reconstruction)) spends the bytes where
   * the image is wrong (vtkHybridVolumeFilter::SetOpacityFunction).
   */
  using Importance = std::function<double(double original, double reconstruction)>;
  void SetImportance(Importance importance) { this->ImportanceFunction = std::move(importance); }
  ///@{
  /// At most this many points, the largest errors (default 0: no budget).
  void SetPointBudget(uint64_t n) { this->PointBudget = n; }
  uint64_t GetPointBudget() const { return this->PointBudget; }
  ///@}
  ///@{
  /// Working memory for original slices, in MB (default 256; fractions allowed).
  void SetMemoryLimit(double megabytes) { this->MemoryLimit = megabytes; }
  double GetMemoryLimit() const { return this->MemoryLimit; }
  ///@}
  void SetProgressCallback(ProgressCallback callback) { this->Progress = std::move(callback); }

  /// Runs both passes into `out`. False with GetErrorMessage() on bad settings or read errors.
  bool Build(strata::HybridVolumeFile& out);

  /// Most original slices held at once during the last Build (read chunk included).
  size_t GetPeakSlicesHeld() const { return this->PeakSlicesHeld; }
  const std::string& GetErrorMessage() const { return this->ErrorMessage; }

private:
  class SliceReader;
  bool BuildLowResolution(strata::HybridVolumeFile& out, SliceReader& reader);
  bool BuildPoints(strata::HybridVolumeFile& out, SliceReader& reader);

  int Dimensions[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  double Origin[3] = { 0, 0, 0 };
  SlabSource Source;
  int Factor[3] = { 2, 2, 2 };
  FilterType Filter = FilterType::Cubic;
  double OverestimationBound = 0;
  int ErrorGridStep[3] = { 1, 1, 1 };
  double Threshold = 0;
  Importance ImportanceFunction;
  uint64_t PointBudget = 0;
  double MemoryLimit = 256;
  ProgressCallback Progress;
  size_t PeakSlicesHeld = 0;
  std::string ErrorMessage;
};
}

#endif
