#pragma once
// Gathers the decoded messages of a bag, in file order, into a RawBag: the
// scans, the odometry (nav_msgs/Odometry, or odom -> base_link on /tf) and the
// base_link -> laser mounting (/tf_static, else /tf). The same for ROS1 and
// ROS 2 bags; the readers only decode. C++17-clean (see raw_bag.hpp).
#include <map>
#include <string>
#include <vector>

#include "io/bag_common/raw_bag.hpp"

namespace dsswarm::bag {

struct RawQuaternion {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  double w = 1.0;
};

// Yaw of a quaternion that need not be normalised. Throws InputError naming
// `where` for a zero or non-finite quaternion (it has no heading).
double yaw_of(const RawQuaternion& q, const std::string& where);

class BagCollector {
 public:
  // `path` names the bag in errors.
  BagCollector(std::string path, BagReadOptions options);

  // What a topic's messages are to the collector.
  enum class Role { Ignored, Scan, Odometry, Transforms, StaticTransforms };
  Role role_of(const std::string& topic) const;

  // The add_* calls come in file order. Stamps are in seconds; a header stamp
  // of exactly 0 (unset) is replaced by `record_time`, the time the message
  // was written to the bag. Throws InputError naming the bag, the topic and
  // the record time for non-finite positions or unusable orientations.
  void add_scan(double header_stamp, double record_time, const std::string& frame_id,
                RawScan scan);
  void add_odometry(double header_stamp, double record_time, double x, double y,
                    const RawQuaternion& orientation);
  // One transform of a tf2_msgs/TFMessage on /tf or (`is_static`) /tf_static.
  void add_transform(bool is_static, double header_stamp, double record_time,
                     const std::string& parent, const std::string& child, double x, double y,
                     const RawQuaternion& rotation);

  // `topics`: every topic of the bag, sorted by name.
  RawBag finish(std::vector<RawTopic> topics) &&;

 private:
  double stamp_of(double header_stamp, double record_time);
  std::string where(const std::string& topic, double record_time) const;
  RawStatic laser_offset(const std::string& laser_frame) const;

  std::string path_;
  BagReadOptions options_;
  std::vector<RawScan> scans_;
  std::vector<RawOdom> odom_;
  std::map<std::string, RawStatic> static_from_base_;   // /tf_static: base_link -> child
  std::map<std::string, RawStatic> dynamic_from_base_;  // /tf: base_link -> child (older bags)
  std::string laser_frame_;
  std::size_t zero_header_stamps_ = 0;
};

}  // namespace dsswarm::bag
