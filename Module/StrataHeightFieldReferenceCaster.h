// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::HeightFieldReferenceCaster
 * @brief   Exact first hits of rays with a height-field stack, in double precision, brute force.
 *
 * The reference the GPU ray caster is tested and benchmarked against. No acceleration and no
 * sampling: a 2-D DDA visits every cell the ray crosses, and in each cell the ray is intersected
 * with every layer's bilinear patch by solving the quadratic z(t) = h(x(t), y(t)) in local cell
 * coordinates. The first cell with a root holds the first hit. Holes (a NaN corner) are skipped.
 * Heights are the stack's float32 values widened to double, i.e. the very surfaces the GPU sees.
 */
#ifndef StrataHeightFieldReferenceCaster_h
#define StrataHeightFieldReferenceCaster_h

#include "StrataCoreModule.h" // For export macro

#include <limits> // For infinity
#include <vector> // For std::vector

namespace strata
{
class HeightFieldStack;
}

namespace strata
{
class STRATACORE_EXPORT HeightFieldReferenceCaster
{
public:
  explicit HeightFieldReferenceCaster(const strata::HeightFieldStack& stack);

  struct Hit
  {
    int Layer = -1; ///< -1: no hit
    double T = std::numeric_limits<double>::infinity();
    double Point[3] = { 0.0, 0.0, 0.0 }; ///< grid coordinates of the hit
  };

  /**
   * First hit of origin + t * direction for t in [tMin, tMax], grid coordinates.
   */
  Hit Cast(const double origin[3], const double direction[3], double tMin, double tMax) const;

  /**
   * Every crossing of origin + t * direction with every layer for t in [tMin, tMax], in ray
   * order (equal t: lower layer first), grid coordinates: all roots of each crossed cell's
   * bilinear patches, a root on a cell boundary once. The model of translucent horizons.
   */
  std::vector<Hit> CastAll(const double origin[3],
    const double direction[3],
    double tMin,
    double tMax) const;

  /**
   * One ray per pixel centre of a width x height image. ndcToGrid (row-major 4x4, column
   * vectors) maps normalised device coordinates to homogeneous grid coordinates; each ray runs
   * from the near plane (NDC z = -1) to the far plane (z = +1), as the GPU's does. Fills
   * layers (-1 for none) and grid-space hit points (3 per pixel, NaN for none), bottom row
   * first. Uses all cores.
   */
  void CastImage(const double ndcToGrid[16],
    int width,
    int height,
    std::vector<int>& layers,
    std::vector<double>& points) const;

private:
  const strata::HeightFieldStack& Stack;
};
}

#endif
