// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::HybridVolumeFile
 * @brief   A hybrid point/volume representation in memory, and its versioned file format.
 *
 * The output of strata::HybridVolumeBuilder (Wilson, Ma and McCormick, "A hybrid point and volume
 * rendering"): a low-resolution volume plus points where the low-resolution volume is wrong.
 * The renderer draws the low-resolution volume with hardware trilinear interpolation and adds
 * the points, whose error says how much opacity is missing there.
 *
 * Geometry (index space of the original volume, point v at index v, world = Origin + v *
 * Spacing). Low-resolution point L sits at original index L * Factor per axis, so the
 * low-resolution volume is uniform, with the same origin and spacing Factor * Spacing. It has
 * LowDimensions = ceil((n - 1) / f) + 1 points per axis (1 when n = 1): when f does not
 * divide n - 1 its last point lies up to f - 1 voxels beyond the original volume (its value
 * is filtered from clamped original samples). Reconstruct() is the trilinear interpolation of
 * the low-resolution volume at an original index, exactly what the texture unit computes.
 *
 * Point layout (16 bytes, little-endian, better than the paper's 6 or 9 bytes): uint16
 * Position[3] (original index, so dimensions are limited to 65536 per axis), uint16 Normal
 * (octahedral encoding, 8 bits per coordinate, angular error below 1.2 degrees, of the
 * normalised gradient of the original data in world units, pointing towards higher values;
 * a zero gradient is stored as +z), float Value (original value), float Error (original minus
 * reconstruction). Points are ordered by original linear index (x fastest), so a renderer
 * can draw them slice by slice.
 *
 * File format, version 1, little-endian:
 * @verbatim
 *   offset size  field
 *   0      8     magic "STRHYVOL"
 *   8      4     uint32 version (1)
 *   12     4     uint32 header size (160)
 *   16     12    int32 Dimensions[3]      original points per axis, each in [1, 65536]
 *   28     12    int32 Factor[3]          each 1, 2, 4 or 8
 *   40     12    int32 LowDimensions[3]   must equal ceil((n - 1) / f) + 1
 *   52     12    int32 ErrorGridStep[3]   each in [1, n]
 *   64     24    float64 Spacing[3]       finite, > 0
 *   88     24    float64 Origin[3]        finite
 *   112    4     uint32 Filter            0 box, 1 linear, 2 cubic, 3 optimized
 *   116    4     uint32 point size (16)
 *   120    8     float64 OverestimationBound (optimized filter only)
 *   128    8     float64 Threshold
 *   136    8     uint64 PointBudget (0: no budget)
 *   144    8     uint64 point count
 *   152    8     uint64 FNV-1a 64 of bytes [0, 152) and of everything after the header
 *   160          float32 low-resolution volume, x fastest
 *   ...          points, 16 bytes each; the file ends there
 * @endverbatim
 * Write() writes "<path>.partial" and renames it over the path once complete, so a reader
 * never sees a half-written file. Read() checks every field, the exact file size (before
 * allocating anything) and the checksum, and says what is wrong.
 *
 * @sa strata::HybridVolumeBuilder
 */
#ifndef StrataHybridVolumeFile_h
#define StrataHybridVolumeFile_h

#include "StrataCoreModule.h" // For export macro

#include <cstdint> // For fixed-width types
#include <string>  // For std::string
#include <vector>  // For std::vector

namespace strata
{
class STRATACORE_EXPORT HybridVolumeFile
{
public:
  enum class FilterType : uint32_t
  {
    Box = 0,
    Linear = 1,
    Cubic = 2,
    Optimized = 3
  };

  struct Point
  {
    uint16_t Position[3]; ///< original index
    uint16_t Normal;      ///< octahedral, see EncodeNormal()
    float Value;          ///< original value
    float Error;          ///< original minus reconstruction
  };

  static constexpr uint32_t FormatVersion = 1;
  static constexpr uint32_t HeaderSize = 160;
  static constexpr uint32_t PointSize = 16;
  static constexpr int MaximumDimension = 65536;

  ///@{
  /// What the builder fills and the file holds; see the class comment for their meaning.
  int Dimensions[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  double Origin[3] = { 0, 0, 0 };
  int Factor[3] = { 2, 2, 2 };
  int LowDimensions[3] = { 0, 0, 0 };
  int ErrorGridStep[3] = { 1, 1, 1 };
  FilterType Filter = FilterType::Cubic;
  double OverestimationBound = 0;
  double Threshold = 0;
  uint64_t PointBudget = 0;
  std::vector<float> LowResolution; ///< LowDimensions product values, x fastest
  std::vector<Point> Points;
  ///@}

  /// ceil((n - 1) / f) + 1, 1 for n = 1: low-resolution points along an axis of n points.
  static int GetLowResolutionDimension(int n, int f);

  /// Low-resolution value (i, j, k), indices clamped.
  float GetLowResolutionValue(int i, int j, int k) const;

  /**
   * Trilinear interpolation of the low-resolution volume at original index (x, y, z), in
   * double: low-resolution cell i = floor(x / f) (the last cell for the last point), weight
   * x / f - i. This is what the error is measured against.
   */
  double Reconstruct(double x, double y, double z) const;

  ///@{
  /// Octahedral normal encoding: high byte u, low byte v, each 8 bits. Zero vector -> +z.
  static uint16_t EncodeNormal(double nx, double ny, double nz);
  static void DecodeNormal(uint16_t code, double n[3]);
  ///@}

  /// Writes the file (temporary file, then rename). False with GetErrorMessage() on failure.
  bool Write(const std::string& path);
  /// Reads and validates a file; on failure the object is left empty.
  bool Read(const std::string& path);

  /// What is wrong with the header fields (dimensions, factors, steps, ...), empty if valid.
  std::string Validate() const;

  const std::string& GetErrorMessage() const { return this->ErrorMessage; }

private:
  std::string ErrorMessage;
};
}

#endif
