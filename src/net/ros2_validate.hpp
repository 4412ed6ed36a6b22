#pragma once
// Checks of ROS 2 samples received from the network before anything uses
// them, and the conversion of a checked LaserScan into ours. A sample that
// fails is rejected whole (counted by the caller), never partly used.
#include <cstddef>
#include <string>

#include "net/ros2_types.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm::net {

struct SampleLimits {
  std::size_t max_beams = 16384;     // no planar lidar has more
  double max_range = 1000.0;         // m, largest range_max accepted
  std::size_t max_frame_id = 256;    // characters of a frame id
  std::size_t max_transforms = 256;  // transforms in one TFMessage
};

// Each returns why the sample cannot be used, or "" when it can. NaN and inf
// readings in `ranges` are legal (ROS: no return / invalid); everything else
// must be finite, angle_increment non-zero, 0 <= range_min < range_max, the
// beam count within 1..max_beams and the quaternions non-degenerate.
std::string check_scan(const ros::LaserScan& scan, const SampleLimits& limits);
std::string check_odometry(const ros::Odometry& odometry, const SampleLimits& limits);
std::string check_transform(const ros::TransformStamped& transform, const SampleLimits& limits);

// A checked scan as ours: timestamp = header stamp, the beam layout, the
// readings bit for bit; no odometry and no laser offset yet.
LaserScan to_laser_scan(const ros::LaserScan& scan);

}  // namespace dsswarm::net
