// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::HeightFieldStack
 * @brief   N height fields on one lateral grid, as the ray casters and references see them.
 *
 * The one place that decides what a stack of horizons *is*: heights as float32 on an nx x ny
 * grid of points, x fastest; the surface over each cell is the bilinear interpolant of its four
 * corners; a cell with any corner NaN is a hole that rays pass through (null values become NaN
 * here). A grid that is one point wide in x or y is drawn as a ribbon one spacing wide (the
 * single column is duplicated at -0.5 and +0.5 spacing), so a horizon picked on a 2-D line
 * stays visible; GetIndexOffset says where grid coordinate 0 lies in image index space.
 *
 * Grid space, used by every Strata height-field algorithm: x in [0, nx-1] and y in [0, ny-1]
 * in cells, z = the height value itself. Layers are borrowed when they can be (float input,
 * no null value present, no ribbon expansion) and copied otherwise, so a 16M-point horizon is
 * not held twice.
 *
 * Plain C++ (no VTK data types): the mapper fills it from vtkImageData, tests from arrays.
 */
#ifndef StrataHeightFieldStack_h
#define StrataHeightFieldStack_h

#include "StrataCoreModule.h" // For export macro

#include <cstddef> // For size_t
#include <memory>  // For std::unique_ptr
#include <string>  // For std::string
#include <vector>  // For std::vector

namespace strata
{
class STRATACORE_EXPORT HeightFieldStack
{
public:
  HeightFieldStack() = default;
  ~HeightFieldStack();
  HeightFieldStack(const HeightFieldStack&) = delete;
  HeightFieldStack& operator=(const HeightFieldStack&) = delete;

  /**
   * Starts a stack on an nx x ny grid of points (as stored, before ribbon expansion). Returns
   * false, with GetErrorMessage() saying why, for empty or absurd sizes.
   */
  bool Initialize(int nx, int ny);

  ///@{
  /**
   * Adds a layer of nx*ny heights, x fastest. Values equal to nullValue (when useNull), NaN,
   * and |v| >= 1e30 (the no-data marker of several formats) become holes. The float version
   * borrows `values` when nothing needs changing: they must then outlive the stack.
   */
  bool AddLayer(const float* values, bool useNull = false, double nullValue = 0.0);
  bool AddLayer(const double* values, bool useNull = false, double nullValue = 0.0);
  ///@}

  /// Effective grid size in points, always >= 2 in each direction.
  int GetNX() const { return this->NX; }
  int GetNY() const { return this->NY; }
  /// Grid size as given to Initialize.
  int GetInputNX() const { return this->InputNX; }
  int GetInputNY() const { return this->InputNY; }
  /// Image index of grid coordinate 0 in x and y: 0, or -0.5 for a ribbon-expanded axis.
  double GetIndexOffset(int axis) const { return this->IndexOffset[axis]; }
  int GetNumberOfLayers() const { return static_cast<int>(this->Layers.size()); }
  /// Heights of layer k on the effective grid, NaN for no data.
  const float* GetLayer(int k) const { return this->Layers[k].Values; }
  /// Height of layer k at point (i, j) of the effective grid.
  float GetHeight(int k, int i, int j) const
  {
    return this->Layers[k].Values[static_cast<size_t>(j) * this->NX + i];
  }
  /// Range of the valid heights of layer k (min > max when the layer has no data).
  double GetLayerMin(int k) const { return this->Layers[k].Min; }
  double GetLayerMax(int k) const { return this->Layers[k].Max; }
  /// Number of no-data points of layer k (on the input grid).
  size_t GetNumberOfHoles(int k) const { return this->Layers[k].Holes; }
  /**
   * Layer k's bilinear interpolant at grid point (x, y) (clamped to the grid), over the valid
   * corners of its cell only, their weights renormalised, so that a value next to a hole stays
   * the nearest data's rather than becoming NaN; false (value untouched) when all four corners
   * are holes. The rule the horizon colouring draws a second grid (an attribute on the lateral
   * grid) with, on the GPU and in its references.
   */
  bool Interpolate(int k, double x, double y, double& value) const;
  /// True when any layer has a no-data point: only then does the shader test for holes.
  bool HasHoles() const;
  /// Bounds over all layers of the valid heights.
  void GetZRange(double range[2]) const;
  const std::string& GetErrorMessage() const { return this->ErrorMessage; }

private:
  struct Layer
  {
    const float* Values = nullptr;
    std::unique_ptr<float[]> Owned;
    double Min = 0.0;
    double Max = -1.0;
    size_t Holes = 0;
  };
  template<typename T>
  bool AddLayerT(const T* values, bool useNull, double nullValue, bool mayBorrow);

  int InputNX = 0;
  int InputNY = 0;
  int NX = 0;
  int NY = 0;
  double IndexOffset[2] = { 0.0, 0.0 };
  std::vector<Layer> Layers;
  std::string ErrorMessage;
};
}

#endif
