#include "swarm/map_merge.hpp"

#include <algorithm>

namespace dsswarm {

MultiResMap compose_working_map(const MultiResMap& own, const std::vector<MapLayer>& foreign) {
  std::vector<const MapLayer*> ordered;
  for (const MapLayer& l : foreign) ordered.push_back(&l);
  std::sort(ordered.begin(), ordered.end(), [](const MapLayer* a, const MapLayer* b) { return a->origin < b->origin; });
  MultiResMap working = own;
  for (const MapLayer* l : ordered)
    if (l->map) combine_into(working, *l->map, l->origin_in_holder);
  return working;
}

}  // namespace dsswarm
