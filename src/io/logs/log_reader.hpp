#pragma once
// One entry point for every log format the CLI accepts: ROS 2 bags (a folder,
// `.db3`, `.mcap`), ROS1 bags (`.bag`) and CARMEN text logs (anything else:
// .log, .clf, .gz, .txt...).
#include <filesystem>
#include <string>

#include "io/logs/carmen_reader.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm {

struct LogReadOptions {
  CarmenOptions carmen;              // CARMEN logs only
  std::string scan_topic = "/scan";  // ROS bags only
  std::string odom_topic = "/odom";  // ROS bags only
  bool use_tf_odometry = false;      // ROS bags only: odometry from /tf instead of the odom topic
  bool odom_topic_named = false;     // ROS bags only: the user named odom_topic (absent = error)
};

// Dispatches on the path: a folder or `.db3`/`.mcap` is a ROS 2 bag, `.bag`
// a ROS1 bag (extensions in any case). Throws
// InputError naming the file for unreadable input, and for a bag when the
// build has no ROS bag support.
SensorLog read_log(const std::filesystem::path& path, const LogReadOptions& options = {});

}  // namespace dsswarm
