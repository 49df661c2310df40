// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   strata::CutPages
 * @brief   Which pages held in RAM a cut still needs: its nodes' and their ancestors'.
 *
 * A paging renderer holds (pins beyond the cache's LRU) the page of every node of its cut and of
 * every ancestor of one, so that a collapse always finds its parent in memory and a split its
 * node; everything else goes back to the cache, which may evict it. Shared by the volume mapper
 * (bricks) and strata::HeightFieldPager (tiles); the holder's map value is its own business.
 */
#ifndef StrataCutPages_h
#define StrataCutPages_h

#include "StrataVolumeBrickTree.h" // For strata::VolumeBrickTree
#include "StrataVolumeCut.h"       // For strata::VolumeCut

#include <iterator> // For std::next

namespace strata
{
class CutPages
{
public:
  /**
   * Drops from `held` (node id -> page, a std::map) every page that is neither the root, nor a
   * node of volume `volume`'s cut, nor an ancestor of one. Ancestors are numbered after their
   * descendants, so walking the map in key order decides every child before its parent.
   */
  template<typename Map>
  static void Prune(Map& held,
    const strata::VolumeCut& cut,
    int volume,
    const strata::VolumeBrickTree& tree)
  {
    for (auto it = held.begin(); it != held.end();)
    {
      const int n = it->first;
      bool keep = n == tree.GetRootId() || cut.IsInCut(volume, n);
      if (!keep && tree.GetNode(n).Level > 0)
      {
        int children[8];
        const int count = tree.GetChildren(n, children);
        for (int c = 0; c < count && !keep; ++c)
          keep = cut.IsInCut(volume, children[c]) || held.count(children[c]);
      }
      it = keep ? std::next(it) : held.erase(it);
    }
  }
};
}

#endif
