#pragma once
// A RawBag (raw_bag.hpp) as the SensorLog the pipeline reads, with the same
// semantics for ROS1 and ROS 2 bags:
//
// Scans come in bag *file* order (the order they were written), which is the
// true order even where header stamps run backwards; LaserScan::timestamp is
// header.stamp. Each scan's odometry is the robot pose interpolated at its
// stamp (linear in x, y; shortest arc in theta). Odometry records whose stamps
// are out of time order are not used, and a scan whose stamp is out of order
// is looked up at a time interpolated from its neighbours (time_order.hpp).
// The laser mounting offset is the base_link -> <scan frame_id> transform.
#include <string>

#include "io/bag_common/raw_bag.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm {

// Scans farther than this outside the odometry time span get no odometry.
inline constexpr double kBagMaxOdometryExtrapolation = 0.5;  // seconds

// The message type names of one ROS generation, which the topics must carry.
struct BagMessageTypes {
  const char* laser_scan;
  const char* odometry;
};
inline constexpr BagMessageTypes kRos1MessageTypes{"sensor_msgs/LaserScan", "nav_msgs/Odometry"};
inline constexpr BagMessageTypes kRos2MessageTypes{"sensor_msgs/msg/LaserScan",
                                                   "nav_msgs/msg/Odometry"};

// Throws InputError naming `file` for a scan topic that is absent (the
// message lists the bag's topics and types) or carries no scans, a topic of
// the wrong message type, and non-finite or degenerate scan geometry. Quirks
// handled (stamps running backwards, missing odometry or laser offset, scans
// outside the odometry span) are reported in SensorLog::warnings.
SensorLog sensor_log_from_bag(const bag::RawBag& bag, const std::string& file,
                              const BagReadOptions& options, const BagMessageTypes& types);

}  // namespace dsswarm
