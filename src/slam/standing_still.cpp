#include "slam/standing_still.hpp"

#include <cmath>

namespace dsswarm {

bool StandingStill::update(const LaserScan& scan) {
  if (!use_odometry_ || !scan.odometry) return false;
  // Unchanged within a micrometre / microradian: odometry integrated in
  // floating point can move by rounding alone (simulated parked robots did).
  constexpr double kSame = 1e-6;
  const bool same = last_odometry_ && std::abs(scan.odometry->x - last_odometry_->x) < kSame &&
                    std::abs(scan.odometry->y - last_odometry_->y) < kSame &&
                    std::abs(normalize_angle(scan.odometry->theta - last_odometry_->theta)) < kSame;
  still_scans_ = same ? still_scans_ + 1 : 0;
  has_moved_ = has_moved_ || (last_odometry_ && !same);
  last_odometry_ = scan.odometry;
  // Not before the robot first moves: a young map needs its first views.
  return has_moved_ && pause_after_ > 0 && still_scans_ >= pause_after_;
}

}  // namespace dsswarm
