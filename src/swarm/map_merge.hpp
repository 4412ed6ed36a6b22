#pragma once
// Bringing another robot's evidence into one's own map: resample each level
// of the foreign map into the own frame and combine cell by cell with
// Dempster's rule (the chapter's map merging).
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/multires_map.hpp"
#include "swarm/map_snapshot.hpp"

namespace dsswarm {

// Combines `source` (whose frame has pose `source_in_target` in the target's
// frame) into `target`, level by level. Each target cell takes the source's
// masses interpolated bilinearly at the cell centre — a convex blend of valid
// masses is a valid mass, and it spreads a rotated wall over the cells it
// crosses instead of aliasing it — and combines them with the target's
// evidence model (Dempster plus the unknown-mass floor). Cells the source knows
// nothing about are left alone (no tiles are allocated for them).
// Throws ConfigError if the two maps differ in resolution or levels.
void combine_into(MultiResMap& target, const MultiResMap& source, const Pose2& source_in_target);

// The map a robot localizes in: its own evidence ⊕ every foreign layer, in a
// fixed order (by origin), so that the result depends only on what is known,
// not on the order in which it arrived.
MultiResMap compose_working_map(const MultiResMap& own, const std::vector<MapLayer>& foreign);

}  // namespace dsswarm
