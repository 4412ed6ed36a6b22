#pragma once
// Reader for ROS 2 bags: a folder with metadata.yaml and its storage files,
// SQLite (.db3, the default up to Humble) or MCAP (.mcap, the default since
// Iron; chunks uncompressed, zstd or lz4), optionally zstd-compressed by
// rosbag2 per file or per message. Messages are CDR: sensor_msgs/msg/LaserScan
// on the scan topic, nav_msgs/msg/Odometry on the odometry topic (or odom ->
// base_link on /tf), tf2_msgs/msg/TFMessage on /tf and /tf_static.
//
// The SensorLog is built exactly as for ROS1 bags (io/bag_common/bag_log.hpp):
// file order across the storage files in the order metadata.yaml lists them,
// odometry interpolated at the scan stamps, the laser offset from /tf_static.
//
// Accepted paths: the bag folder; one .db3/.mcap file (only that file is
// read, with a warning if metadata.yaml lists more); a folder without
// metadata.yaml holding exactly one storage file (read with a warning: a
// recording that was cut short has no metadata.yaml; `ros2 bag reindex`
// writes one).
#include <filesystem>

#include "io/bag_common/raw_bag.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm {

// A folder (the bag, or not a log at all: read_rosbag2 says which), or a
// file named *.db3 or *.mcap (any case).
bool is_rosbag2_path(const std::filesystem::path& path);

// Throws InputError naming the file for a missing path, no metadata.yaml
// where one is needed, a damaged or truncated storage file, a message that
// does not decode, a scan topic that is absent (the message lists the bag's
// topics and types) or of the wrong type, and non-finite scan geometry or
// poses. Quirks handled are reported in SensorLog::warnings.
SensorLog read_rosbag2(const std::filesystem::path& path, const BagReadOptions& options = {});

}  // namespace dsswarm
