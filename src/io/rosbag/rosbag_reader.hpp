#pragma once
// Reader for ROS1 bags (format 2.0, any chunk compression rosbag_storage
// handles) holding sensor_msgs/LaserScan and odometry.
//
// Scans come in bag *file* order (the order they were written), which is the
// true order even where header stamps run backwards; LaserScan::timestamp is
// header.stamp. Each scan's odometry is the robot pose interpolated at its
// stamp (linear in x, y; shortest arc in theta), from nav_msgs/Odometry on
// `odom_topic` or from odom -> base_link transforms on /tf. Odometry records
// whose stamps are out of time order are not used, and a scan whose stamp is
// out of order is looked up at a time interpolated from its neighbours (see
// time_order.hpp). The laser mounting offset is the base_link -> <scan
// frame_id> transform on /tf_static (else /tf).
//
// Available only when built with DSSWARM_HAVE_ROSBAG defined.
#include <filesystem>
#include <string>

#include "sensor/laser_scan.hpp"

namespace dsswarm {

struct RosbagOptions {
  std::string scan_topic = "/scan";
  std::string odom_topic = "/odom";
  bool use_tf_odometry = false;  // odom -> base_link on /tf instead of odom_topic
  // The user named odom_topic (a typo is likely): its absence from the bag is
  // an InputError, not a warning.
  bool odom_topic_named = false;
};

// Scans farther than this outside the odometry time span get no odometry.
inline constexpr double kRosbagMaxOdometryExtrapolation = 0.5;  // seconds

// Throws InputError naming the file for a missing file, a file that is not a
// readable ROS1 bag (corrupt, truncated, not a bag), a scan topic that is
// absent (the message lists the bag's topics and types) or carries no scans,
// a topic of the wrong message type, an odometry topic that is absent when
// `odom_topic_named`, and non-finite scan geometry or poses.
// Quirks handled (stamps running backwards, missing odometry or laser offset,
// scans outside the odometry span) are reported in SensorLog::warnings.
SensorLog read_rosbag(const std::filesystem::path& path, const RosbagOptions& options = {});

}  // namespace dsswarm
