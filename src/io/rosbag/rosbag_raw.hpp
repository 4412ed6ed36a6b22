#pragma once
// Plain data pulled out of a ROS1 bag, handed from the C++17 library that
// talks to rosbag_storage (whose headers do not compile as C++20) to the
// C++20 reader. This header must stay C++17-clean and free of ROS includes.
#include <cstddef>
#include <string>
#include <vector>

namespace dsswarm::rosbag_raw {

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
  std::string type;  // e.g. "sensor_msgs/LaserScan"
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

// Frames the reader looks for on /tf and /tf_static (leading '/' ignored).
inline constexpr const char* kOdomFrame = "odom";
inline constexpr const char* kBaseFrame = "base_link";
inline constexpr const char* kDefaultLaserFrame = "laser";

// Reads every message on `scan_topic`, the odometry (from `odom_topic`, or
// from odom -> base_link transforms on /tf when `use_tf` is set) and the
// base_link -> laser transform (/tf_static, else /tf). Does not judge the
// content beyond what decoding needs: a missing scan topic, say, is left to
// the caller, who has the topic list. Throws InputError naming `path` for a
// file that is not a readable ROS1 bag, a message that does not decode as the
// type its topic should carry, or an orientation quaternion that is zero or
// not finite.
RawBag read_raw_bag(const std::string& path, const std::string& scan_topic,
                    const std::string& odom_topic, bool use_tf);

}  // namespace dsswarm::rosbag_raw
