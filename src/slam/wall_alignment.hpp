#pragma once
// Which way does a new map's grid face? Its cells are square, so a wall that
// runs at a slant to the grid's axes is drawn as a staircase, and a saturated
// cell does not say where in it the wall lies. Where the walls near a robot
// are short (a lever of a metre or two), the staircase pulls the match's
// heading towards the one that puts the walls on the grid's axes: simulated
// robots parked in a stub ended up to a degree off their own map that way,
// and 2.5 cm cells halved it. Most buildings are rectilinear, so a map whose
// axes run along the walls of its first scan draws them as straight rows of
// cells, and that pull then points to the right heading. The map frame is
// then the odometry frame turned by up to 45° about the first pose (REP 105
// leaves map → odom free); a scan without a clear pair of right-angled wall
// directions keeps the odometry's heading.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "geometry/pose2.hpp"

namespace dsswarm {

struct WallAlignConfig {
  bool enabled = true;
  // The normals' agreement on one direction modulo 90° (the length of the
  // mean of their angles taken four times, 1: every normal on the two axes).
  double min_consistency = 0.9;
  double inlier_angle = 0.09;  // rad: normals this close to the axes refine it
  int min_normals = 50;        // fewer: the first scan saw too little wall to tell

  void validate() const;  // throws ConfigError naming the field
};

// The walls' normal direction modulo 90°, in (-45°, 45°] of the frame the
// normals are in, when they agree on one (see WallAlignConfig).
std::optional<double> wall_axis(const std::vector<Eigen::Vector2d>& normals, const WallAlignConfig& config);

// `start` turned about its position by the least angle that puts walls whose
// normals lie at `axis` in its base frame on the map's axes.
Pose2 turned_to_walls(const Pose2& start, double axis);

}  // namespace dsswarm
