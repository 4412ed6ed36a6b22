#include "slam/slam.hpp"

#include <cmath>

#include "common/errors.hpp"

namespace dsswarm {

void SlamConfig::validate() const {
  map.validate();
  matcher.validate();
  if (min_points < 1) throw ConfigError("slam.min_points must be >= 1");
  if (insert_min_travel < 0.0 || insert_min_rotation < 0.0)
    throw ConfigError("slam.insert_min_travel and insert_min_rotation must be >= 0");
}

Slam::Slam(const SlamConfig& config)
    : config_(config), map_(config.map), matcher_(config.matcher, config.seed) {
  config_.validate();
}

bool Slam::odometry_stale(const LaserScan& scan) const {
  // A moving robot whose odometry repeats the previous reading exactly has a
  // stalled odometry stream, not a robot that stopped dead.
  return scan.odometry && anchor_odometry_ && odometry_moving_ && scan.odometry->x == anchor_odometry_->x &&
         scan.odometry->y == anchor_odometry_->y && scan.odometry->theta == anchor_odometry_->theta;
}

Pose2 Slam::predict(const LaserScan& scan) const {
  const bool odometry_usable = config_.use_odometry && scan.odometry && anchor_odometry_ && !odometry_stale(scan);
  if (odometry_usable) {
    // The odometry increment is expressed in the robot frame of the anchor
    // odometry pose, so it applies to our corrected pose whatever the drift
    // between the odometry frame and the map frame.
    return anchor_pose_ * between(*anchor_odometry_, *scan.odometry);
  }
  // No (usable) odometry: constant velocity from the last two poses.
  if (previous_pose_) return pose_ * between(*previous_pose_, pose_);
  return pose_;
}

SlamStep Slam::process(const LaserScan& scan) {
  SlamStep step;
  const bool first = processed_ == 0;
  if (first && config_.use_odometry && scan.odometry) pose_ = *scan.odometry;  // map frame = odometry frame
  step.prior = first ? pose_ : predict(scan);
  ++processed_;

  const std::vector<ScanPoint> points = scan_to_points(scan, config_.points);
  const bool enough_points = static_cast<int>(points.size()) >= config_.min_points;
  step.pose = step.prior;
  if (!first && enough_points) {
    // Odometry can lag and then jump (intel and mit-csail do both). When it
    // disagrees sharply with a constant-velocity prediction, search from both
    // and keep the better match. Only then: the score cannot reliably tell a
    // small true motion from none (a young map is sparse, and the last scan's
    // own viewpoint always fits it best), so an always-on alternative would
    // pull a moving robot back to where it was.
    std::vector<Pose2> priors{step.prior};
    if (previous_pose_ && config_.use_odometry) {
      const Pose2 constant_velocity = pose_ * between(*previous_pose_, pose_);
      const Pose2 d = between(step.prior, constant_velocity);
      if (std::hypot(d.x, d.y) > config_.odometry_doubt_xy || std::abs(d.theta) > config_.odometry_doubt_theta)
        priors.push_back(constant_velocity);
    }
    const MatchResult m = matcher_.match(map_, points, priors);
    step.pose = m.pose;
    step.score = m.score;
    step.matched = true;
    ++matched_;
  }

  if (enough_points) {
    bool insert = !last_insert_pose_;
    if (last_insert_pose_) {
      const Pose2 d = between(*last_insert_pose_, step.pose);
      insert = std::hypot(d.x, d.y) >= config_.insert_min_travel ||
               std::abs(d.theta) >= config_.insert_min_rotation;
    }
    if (insert) {
      map_.insert_scan(step.pose, scan.laser_offset, points);
      last_insert_pose_ = step.pose;
    }
  }

  if (scan.odometry && !odometry_stale(scan)) {
    if (anchor_odometry_) {
      const Pose2 d = between(*anchor_odometry_, *scan.odometry);
      odometry_moving_ = d.x != 0.0 || d.y != 0.0 || d.theta != 0.0;
    }
    anchor_odometry_ = scan.odometry;
    anchor_pose_ = step.pose;
  }
  previous_pose_ = pose_;
  pose_ = step.pose;
  return step;
}

}  // namespace dsswarm
