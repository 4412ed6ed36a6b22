#pragma once
// What the ROS1 and ROS 2 bag readers pull out of a bag, whatever its format:
// scans, odometry poses and the laser mounting, as plain data. The readers
// fill it through BagCollector (bag_collector.hpp) and turn it into a
// SensorLog with sensor_log_from_bag (bag_log.hpp). This header stays
// C++17-clean: the ROS1 half that includes ROS headers is a C++17 target.
#include <cstddef>
#include <string>
#include <vector>

namespace dsswarm {

// Which messages a bag reader takes the run from.
struct BagReadOptions {
  std::string scan_topic = "/scan";
  std::string odom_topic = "/odom";
  bool use_tf_odometry = false;  // odom -> base_link on /tf instead of odom_topic
  // The user named odom_topic (a typo is likely): its absence from the bag is
  // an InputError, not a warning.
  bool odom_topic_named = false;
};

namespace bag {

// One sensor_msgs/LaserScan.
struct RawScan {
  double stamp = 0.0;  // header.stamp in seconds (the record time if the header stamp is zero)
  float angle_min = 0.0F;
  float angle_increment = 0.0F;
  float range_min = 0.0F;
  float range_max = 0.0F;
  std::vector<float> ranges;
};

// One odometry pose (nav_msgs/Odometry or an odom -> base_link transform).
struct RawOdom {
  double stamp = 0.0;  // seconds
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;  // yaw from the orientation quaternion, radians
};

// The base -> laser mounting transform (projected to the plane).
struct RawStatic {
  bool found = false;
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
};

struct RawTopic {
  std::string name;
  std::string type;  // e.g. "sensor_msgs/LaserScan" (ROS1), "sensor_msgs/msg/LaserScan" (ROS 2)
  std::size_t messages = 0;
};

struct RawBag {
  // Both streams in bag *file* order (the order the messages were written),
  // which is the true order even where header stamps run backwards.
  std::vector<RawScan> scans;
  std::vector<RawOdom> odom;
  RawStatic laser_offset;
  std::string laser_frame;       // frame_id of the scans ("laser" if they name none)
  std::vector<RawTopic> topics;  // every topic in the bag, sorted by name
  std::size_t zero_header_stamps =
      0;  // messages whose record time stood in for a zero header stamp
};

// Frames the readers look for on /tf and /tf_static (leading '/' ignored).
inline constexpr const char* kOdomFrame = "odom";
inline constexpr const char* kBaseFrame = "base_link";
inline constexpr const char* kDefaultLaserFrame = "laser";

}  // namespace bag
}  // namespace dsswarm
