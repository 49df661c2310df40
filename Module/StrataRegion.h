// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::Region
 * @brief   An optional world box: the share of a scene that one process of a sort-last
 *          parallel render draws.
 *
 * The mappers' SetRegion/RemoveRegion/GetRegion keep one (vtkMultiVolumeRayCastMapper clips
 * its rays and fragments to it, vtkStackedHeightFieldMapper its hits), and strata::VolumeCut's
 * camera carries it so that bricks outside are never paged. Bounds are (xmin, xmax, ymin,
 * ymax, zmin, zmax) in world coordinates. Set and Remove say whether anything changed, so
 * that the owner calls Modified() only then.
 */
#ifndef StrataRegion_h
#define StrataRegion_h

#include <algorithm> // For std::copy, std::equal
#include <ostream>   // For std::ostream

namespace strata
{
class Region
{
public:
  /// Sets the box; false when it was that box already.
  bool Set(const double bounds[6])
  {
    if (this->Active && std::equal(bounds, bounds + 6, this->Bounds))
      return false;
    this->Active = true;
    std::copy(bounds, bounds + 6, this->Bounds);
    return true;
  }
  /// Unsets the box (the whole scene); false when none was set.
  bool Remove()
  {
    const bool was = this->Active;
    this->Active = false;
    return was;
  }
  /// Copies the box into `bounds`; false, `bounds` untouched, when none is set.
  bool Get(double bounds[6]) const
  {
    if (this->Active)
      std::copy(this->Bounds, this->Bounds + 6, bounds);
    return this->Active;
  }
  bool IsSet() const { return this->Active; }
  /// Bound i of the box (meaningful when IsSet()).
  double operator[](int i) const { return this->Bounds[i]; }
  bool operator==(const Region& o) const
  {
    return this->Active == o.Active &&
           (!this->Active || std::equal(this->Bounds, this->Bounds + 6, o.Bounds));
  }
  bool operator!=(const Region& o) const { return !(*this == o); }
  /// The six bounds, or "(none)".
  void Print(std::ostream& os) const
  {
    if (!this->Active)
    {
      os << "(none)";
      return;
    }
    for (int i = 0; i < 6; ++i)
      os << (i ? " " : "") << this->Bounds[i];
  }

private:
  bool Active = false;
  double Bounds[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
};
}

#endif
