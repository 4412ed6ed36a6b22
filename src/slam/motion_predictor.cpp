#include "slam/motion_predictor.hpp"

#include <cmath>

#include "common/errors.hpp"

namespace dsswarm {

void MotionConfig::validate() const {
  if (!(odometry_doubt_xy > 0.0) || !(odometry_doubt_theta > 0.0))
    throw ConfigError("slam.odometry_doubt_xy and odometry_doubt_theta must be > 0");
}

bool MotionPredictor::odometry_stale(const LaserScan& scan) const {
  return scan.odometry && anchor_odometry_ && odometry_moving_ && scan.odometry->x == anchor_odometry_->x &&
         scan.odometry->y == anchor_odometry_->y && scan.odometry->theta == anchor_odometry_->theta;
}

bool MotionPredictor::from_odometry(const LaserScan& scan) const {
  return use_odometry_ && scan.odometry && anchor_odometry_ && !odometry_stale(scan);
}

Pose2 MotionPredictor::predict(const LaserScan& scan) const {
  if (from_odometry(scan)) {
    // The odometry increment is expressed in the robot frame of the anchor
    // odometry pose, so it applies to our corrected pose whatever the drift
    // between the odometry frame and the map frame.
    return anchor_pose_ * between(*anchor_odometry_, *scan.odometry);
  }
  if (previous_pose_) return pose_ * between(*previous_pose_, pose_);
  return pose_;
}

std::optional<Pose2> MotionPredictor::doubt(const Pose2& prediction) const {
  if (!previous_pose_ || !use_odometry_) return std::nullopt;
  const Pose2 constant_velocity = pose_ * between(*previous_pose_, pose_);
  const Pose2 d = between(prediction, constant_velocity);
  if (std::hypot(d.x, d.y) > config_.odometry_doubt_xy || std::abs(d.theta) > config_.odometry_doubt_theta)
    return constant_velocity;
  return std::nullopt;
}

void MotionPredictor::advance(const LaserScan& scan, const Pose2& pose) {
  if (scan.odometry && !odometry_stale(scan)) {
    if (anchor_odometry_) {
      const Pose2 d = between(*anchor_odometry_, *scan.odometry);
      odometry_moving_ = d.x != 0.0 || d.y != 0.0 || d.theta != 0.0;
    }
    anchor_odometry_ = scan.odometry;
    anchor_pose_ = pose;
  }
  previous_pose_ = pose_;
  pose_ = pose;
}

}  // namespace dsswarm
