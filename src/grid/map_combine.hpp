#pragma once
// Dempster combination of one map's evidence into another's, level by level:
// how another robot's map enters one's own, and how submaps make one map.
#include "geometry/pose2.hpp"
#include "grid/multires_map.hpp"

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

// The same for two maps whose cells coincide (same frame): cell by cell, no
// resampling. Throws ConfigError if the two maps differ in resolution or levels.
void combine_aligned(MultiResMap& target, const MultiResMap& source);

}  // namespace dsswarm
