#pragma once
// Reader for ROS1 bags (format 2.0, any chunk compression rosbag_storage
// handles) holding sensor_msgs/LaserScan and odometry.
//
// The scans, odometry and laser offset are taken as for every bag
// (io/bag_common/bag_log.hpp): file order, odometry interpolated at the scan
// stamps from nav_msgs/Odometry on `odom_topic` or from odom -> base_link
// transforms on /tf, the laser offset from /tf_static (else /tf).
//
// Available only when built with DSSWARM_HAVE_ROSBAG defined.
#include <filesystem>
#include <string>

#include "io/bag_common/raw_bag.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm {

using RosbagOptions = BagReadOptions;

// Throws InputError naming the file for a missing file, a file that is not a
// readable ROS1 bag (corrupt, truncated, not a bag), a scan topic that is
// absent (the message lists the bag's topics and types) or carries no scans,
// a topic of the wrong message type, an odometry topic that is absent when
// `odom_topic_named`, and non-finite scan geometry or poses.
// Quirks handled (stamps running backwards, missing odometry or laser offset,
// scans outside the odometry span) are reported in SensorLog::warnings.
SensorLog read_rosbag(const std::filesystem::path& path, const RosbagOptions& options = {});

}  // namespace dsswarm
