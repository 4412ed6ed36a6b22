#pragma once
// Dempster combination of one map's evidence into another's, level by level:
// how another robot's map enters one's own, and how submaps make one map.
#include <cstdint>
#include <limits>

#include "geometry/pose2.hpp"
#include "grid/multires_map.hpp"

namespace dsswarm {

// The target tiles a combination writes: those whose lower edge lies in
// [from, to) metres along y, on every level (each tile in exactly one of
// several bands that split the line). Bands split the work of one
// combination between threads, each writing a map of its own.
struct TileBand {
  double from = -std::numeric_limits<double>::infinity();
  double to = std::numeric_limits<double>::infinity();
  bool holds(std::int32_t tile_row, double tile_height) const {
    const double edge = tile_row * tile_height;
    return edge >= from && edge < to;
  }
};

// Combines `source` (whose frame has pose `source_in_target` in the target's
// frame) into `target`, level by level. Each target cell takes the source's
// masses interpolated bilinearly at the cell centre — a convex blend of valid
// masses is a valid mass, and it spreads a rotated wall over the cells it
// crosses instead of aliasing it — and combines them with the target's
// evidence model (Dempster plus the unknown-mass floor). Cells the source knows
// nothing about are left alone (no tiles are allocated for them).
// A target with fewer levels takes the source's finest ones. Throws
// ConfigError if the two maps differ in resolution or the source has fewer levels.
void combine_into(MultiResMap& target, const MultiResMap& source, const Pose2& source_in_target,
                  const TileBand& band = {});

// The same for two maps whose cells coincide (same frame): cell by cell, no
// resampling. The same levels rule as combine_into.
void combine_aligned(MultiResMap& target, const MultiResMap& source, const TileBand& band = {});

}  // namespace dsswarm
