#pragma once
// Bringing another robot's evidence into one's own map: resample each level
// of the foreign map into the own frame and combine cell by cell with
// Dempster's rule (the chapter's map merging; combine_into, grid/map_combine).
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/map_combine.hpp"
#include "grid/multires_map.hpp"
#include "swarm/map_snapshot.hpp"

namespace dsswarm {

// The map a robot localizes in: its own evidence ⊕ every foreign layer, in a
// fixed order (by origin), so that the result depends only on what is known,
// not on the order in which it arrived.
// A layer's pieces (MapLayer::pieces) go in after its map, each at
// origin_in_holder ⊕ its pose.
MultiResMap compose_working_map(const MultiResMap& own, const std::vector<MapLayer>& foreign);

// A layer's evidence as one map in its origin's frame: its map ⊕ its pieces
// (its map alone, copied, when it has none).
MultiResMap layer_evidence(const MapLayer& layer);

}  // namespace dsswarm
