#pragma once
// Step 1 of placing another robot's scan (relative_pose.hpp): every heading ×
// every lattice position within the search radius, scored on the coarsest
// level, and the best few distinct modes among them for the refinement.
// It is most of an encounter's matching work, so it is written for speed;
// its scores are those of interpolated_occupancy (unknown counting 0) to the bit.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "geometry/pose2.hpp"
#include "grid/ds_grid.hpp"
#include "sensor/scan_points.hpp"
#include "swarm/relative_pose.hpp"

namespace dsswarm {

struct CoarsePlacement {
  float score = 0.0f;      // weighted mean cell value under the points, [0, 1]
  std::uint32_t rank_tie = 0;  // position in the search order: among equal scores the earlier ranks first
  Pose2 pose;
};

// `points` thinned evenly to about config.coarse_points, scored at every
// heading (config.coarse_step_theta) × every position of a square lattice
// (config.coarse_step_xy) within config.search_radius of `near`, in the order
// heading, then y, then x.
std::vector<CoarsePlacement> exhaustive_search(const DsGrid& grid, const std::vector<ScanPoint>& points,
                                               const Eigen::Vector2d& near, const RelativePoseConfig& config);

// The best `count` placements that are pairwise distinct modes
// (distinct_modes), best first.
std::vector<Pose2> distinct_best(std::vector<CoarsePlacement> all, int count, const RelativePoseConfig& config);

}  // namespace dsswarm
