#pragma once
// Test support: writes small ROS1 bags with rosbag::Bag in write mode, so the
// reader's tests need no real data. C++17-clean and free of ROS includes (the
// implementation is in the C++17 target dsswarm_rosbag_test_writer).
#include <string>
#include <vector>

#include "io/rosbag/rosbag_raw.hpp"

namespace dsswarm::rosbag_raw {

struct TestBagMessage {
  enum class Kind {
    Scan,         // sensor_msgs/LaserScan on scan_topic, frame "laser"
    Odometry,     // nav_msgs/Odometry on odom_topic and/or odom -> base_link on /tf
    LaserOffset,  // base_link -> laser on /tf_static
  };
  Kind kind = Kind::Scan;
  RawScan scan;      // for Scan
  RawOdom odom;      // for Odometry
  RawStatic offset;  // for LaserOffset (x, y, theta)
};

struct TestBagSpec {
  std::string scan_topic = "/scan";
  std::string odom_topic = "/odom";  // empty: no nav_msgs/Odometry messages
  bool odometry_on_tf = true;        // also publish each odometry pose on /tf
  enum class Compression { None, Bz2, Lz4 };
  Compression compression = Compression::None;  // of the chunks
  // Written in this order; each message's record time is its stamp (as the
  // data sets were converted), so the bag index order can differ from it.
  std::vector<TestBagMessage> messages;
};

// Throws whatever rosbag throws (a test helper: no translation to InputError).
void write_test_bag(const std::string& path, const TestBagSpec& spec);

}  // namespace dsswarm::rosbag_raw
