#pragma once
// The one sensor record the pipeline consumes: a planar laser scan with the
// robot's odometry pose at the scan time (if the platform has odometry).
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "geometry/pose2.hpp"

namespace dsswarm {

struct LaserScan {
  double timestamp = 0.0;       // seconds, as recorded in the log (never re-sorted)
  double angle_min = 0.0;       // angle of beam 0 in the laser frame, rad
  double angle_increment = 0.0; // rad between consecutive beams
  double range_min = 0.0;       // readings <= range_min are invalid
  double range_max = 0.0;       // readings >= range_max mean "no return"
  std::vector<float> ranges;    // metres
  std::optional<Pose2> odometry;  // robot base pose by odometry at the scan time
  Pose2 laser_offset;             // laser pose in the robot base frame (mounting)

  double beam_angle(std::size_t i) const { return angle_min + static_cast<double>(i) * angle_increment; }

  // NaN, inf, <= range_min and >= range_max are not hits (max range = no return).
  bool is_valid(float r) const {
    return std::isfinite(r) && r > range_min && r < range_max;
  }

  std::size_t valid_count() const {
    std::size_t n = 0;
    for (float r : ranges) n += is_valid(r) ? 1 : 0;
    return n;
  }
};

// A whole recorded run: scans in file order, plus what the reader noticed.
struct SensorLog {
  std::string source;              // file name, for messages
  std::vector<LaserScan> scans;    // file order (the true order, even if timestamps run backwards)
  std::vector<std::string> warnings;  // quirks handled (e.g. backwards timestamps), one line each
};

}  // namespace dsswarm
