#include "slam/stall_guard.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "slam/degeneracy.hpp"

namespace dsswarm {

void StallConfig::validate() const {
  if (!(window >= 0.0)) throw ConfigError("slam.stall_window must be >= 0");
  if (!(min_progress >= 0.0 && min_progress <= 1.0)) throw ConfigError("slam.stall_min_progress must be in [0, 1]");
  if (!(min_step > 0.0)) throw ConfigError("slam.stall_min_step must be > 0");
  if (!(young_travel >= 0.0)) throw ConfigError("slam.stall_young_travel must be >= 0");
}

Pose2 StallGuard::check(const Pose2& last, const Pose2& prior, const Pose2& raw, const Pose2& matched) {
  if (config_.window <= 0.0) return matched;
  const Pose2 odometry = between(last, prior);
  const double travel = std::hypot(odometry.x, odometry.y);
  if (travel < config_.min_step) return matched;
  total_travel_ += travel;
  if (config_.young_travel > 0.0 && total_travel_ > config_.young_travel) return matched;
  const Eigen::Vector2d direction = Eigen::Vector2d(odometry.x, odometry.y) / travel;  // in last's frame
  const Pose2 moved = between(last, raw);
  const double progress = Eigen::Vector2d(moved.x, moved.y).dot(direction);
  // What the pose as it stands (after the other checks) fell short, should the guard not step in.
  const Pose2 kept = between(last, matched);
  const Eigen::Vector2d in_map = PointTransform::rotation(last.theta)(direction.x(), direction.y());
  steps_.push_back({travel, progress, (travel - Eigen::Vector2d(kept.x, kept.y).dot(direction)) * in_map});
  travel_ += travel;
  progress_ += progress;
  behind_ += steps_.back().behind;
  // Keep the newest steps that make up the window, no more.
  while (steps_.size() > 1 && travel_ - steps_.front().travel >= config_.window) {
    travel_ -= steps_.front().travel;
    progress_ -= steps_.front().progress;
    behind_ -= steps_.front().behind;
    steps_.pop_front();
  }
  if (travel_ < config_.window || progress_ >= config_.min_progress * travel_) return matched;
  ++holds_;
  // hold_along wants the direction in the prior's frame.
  const Eigen::Vector2d in_prior = PointTransform::rotation(-odometry.theta)(direction.x(), direction.y());
  Pose2 held = hold_along(prior, matched, in_prior);
  // This step now follows the odometry; the earlier ones fell short by behind_
  // (less what this step's own shortfall was).
  const Eigen::Vector2d catch_up = behind_ - steps_.back().behind;
  for (Step& s : steps_) s.behind.setZero();
  behind_.setZero();
  if (config_.catch_up && catch_up.dot(in_map) > 0.0) {
    held.x += catch_up.x();
    held.y += catch_up.y();
  }
  return held;
}

void StallGuard::reset() {
  steps_.clear();
  travel_ = progress_ = 0.0;
  behind_.setZero();
}

}  // namespace dsswarm
