#pragma once
// Is the robot parked? Once its odometry has not changed for a number of
// scans (after it first moved), it is standing still: the pipeline holds its
// pose and neither matches nor inserts its scans until the odometry changes.
// Matching the same view over and over only lets the pose random-walk, and
// adding evidence would pile up one viewpoint's noise until the map, and then
// the pose, creep too (simulated robots waiting at a rendezvous crept 0.25 m
// and 1.3 degrees in 80 s). Odometry that stalls while the robot moves (real
// logs do) freezes for fewer scans.
#include <optional>

#include "geometry/pose2.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm {

class StandingStill {
 public:
  // `pause_after_still_scans` 0: never; without odometry: never.
  StandingStill(int pause_after_still_scans, bool use_odometry)
      : pause_after_(pause_after_still_scans), use_odometry_(use_odometry) {}

  // Notes the scan's odometry; true once the robot stands still.
  bool update(const LaserScan& scan);

 private:
  int pause_after_;
  bool use_odometry_;
  std::optional<Pose2> last_odometry_;  // the previous scan's reading
  int still_scans_ = 0;                 // consecutive scans with the same odometry reading
  bool has_moved_ = false;              // has the odometry ever changed?
};

}  // namespace dsswarm
