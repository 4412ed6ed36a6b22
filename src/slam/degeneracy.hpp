#pragma once
// Which way does a scan pin the robot down? Each point's surface normal (the
// line fitted to its neighbours along the scan) constrains the position across the surface
// only; the normals' scatter matrix says how well each direction is held. In
// a corridor whose end is out of range every normal is sideways: along the
// corridor the scan tells nothing, and the score's only slope there comes
// from the map's frontier (the scan's far points land on unknown cells ahead
// and on known ones behind), which pulls a moving robot back to where it has
// mapped, scan after scan (simulated robots stuck that way for metres). Where
// the scan is degenerate the match keeps the prediction's position along the
// weak direction and takes the rest, as degeneracy-aware odometry does
// (Zhang et al., "On degeneracy of optimization-based state estimation", 2016).
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "geometry/pose2.hpp"
#include "sensor/scan_points.hpp"

namespace dsswarm {

struct DegeneracyConfig {
  // A scan is degenerate when the smaller eigenvalue of its normals' scatter
  // matrix is below this share of the larger one (0 disables).
  double min_ratio = 0.01;
  // A point's normal is that of the line through the points within
  // `normal_radius` of it among its `normal_neighbors` scan neighbours each
  // side; fewer than `min_patch` of them, or a patch further from a line than
  // `max_patch_spread` (its eigenvalue ratio: a corner, clutter), gives none.
  double normal_radius = 0.25;  // m
  int normal_neighbors = 10;
  int min_patch = 5;
  double max_patch_spread = 0.1;
  int min_normals = 20;  // fewer normals: no judgement (too little to tell)

  void validate() const;  // throws ConfigError naming the field
};

// The unit surface normals (robot base frame, sign arbitrary) of the points
// whose neighbourhood is a line (see DegeneracyConfig).
std::vector<Eigen::Vector2d> surface_normals(const std::vector<ScanPoint>& points, const DegeneracyConfig& config);

// The direction (unit, robot base frame) the scan leaves unconstrained, if any.
std::optional<Eigen::Vector2d> weak_direction(const std::vector<ScanPoint>& points, const DegeneracyConfig& config);

// `matched`, with its position along `weak` (base frame of `prior`) put back
// to the prior's; its heading and the rest of its position kept.
Pose2 hold_along(const Pose2& prior, const Pose2& matched, const Eigen::Vector2d& weak);

}  // namespace dsswarm
