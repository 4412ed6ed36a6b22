#pragma once
// Test support: writes ROS 2 bags as rosbag2 lays them out (a folder with
// metadata.yaml and .db3 or .mcap storage files), so the reader's tests and
// the real-data conversions need no ROS installation.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "io/rosbag2/bag_metadata.hpp"
#include "ros2/codec.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm::rosbag2_test {

struct BagMessage {
  std::string topic;
  std::string type;  // e.g. "sensor_msgs/msg/LaserScan"
  std::int64_t log_time_ns = 0;
  std::vector<std::uint8_t> cdr;
};

// Nanoseconds since the epoch of `t`.
inline std::int64_t nanoseconds(const ros2::Time& t) {
  return std::int64_t{t.sec} * 1'000'000'000 + t.nanosec;
}

// `message` on `topic`, recorded at `log_time` (seconds).
template <typename T>
BagMessage bag_message(std::string topic, double log_time, const T& message) {
  return {std::move(topic), std::string(T::kTypeName),
          nanoseconds(ros2::time_from_seconds(log_time)), ros2::encode(message)};
}

enum class Format { Db3, McapUnchunked, McapChunked, McapZstd, McapLz4 };
const char* format_name(Format format);
inline constexpr Format kAllFormats[] = {Format::Db3, Format::McapUnchunked, Format::McapChunked,
                                         Format::McapZstd, Format::McapLz4};

struct WriteOptions {
  Format format = Format::McapZstd;
  std::size_t chunk_bytes = 4096;  // MCAP: small, so that the tests see several chunks
  std::size_t files = 1;           // split the messages evenly over this many storage files
  rosbag2::Compression compression = rosbag2::Compression::None;  // rosbag2's own (zstd)
  bool metadata = true;            // write metadata.yaml
};

// Writes the bag folder `dir` (emptied first); returns its storage files in order.
std::vector<std::filesystem::path> write_bag(const std::filesystem::path& dir,
                                             const std::vector<BagMessage>& messages,
                                             const WriteOptions& options);

// Messages as the tests need them: a scan in frame "laser" with beams at
// -pi/2, 0, pi/2 (as many as `ranges`), range limits 0.1 .. 30 m; odometry
// (odom -> base_link); one transform `parent` -> `child` in a TFMessage.
ros2::LaserScan laser_scan(double stamp, std::vector<float> ranges);
ros2::Odometry odometry(double stamp, double x, double y, double theta);
ros2::TFMessage transform(double stamp, const std::string& parent, const std::string& child,
                          double x, double y, double theta);

// A SensorLog as a ROS 2 recording: each scan on /scan; its odometry on
// /odom and as odom -> base_link on /tf, stamped at the time the bag reader
// looks that scan up (time_order.hpp), so that it reads back unchanged; the
// first scan's laser offset as base_link -> laser on /tf_static. Geometry
// becomes float32, as LaserScan has it.
std::vector<BagMessage> messages_from_log(const SensorLog& log);

}  // namespace dsswarm::rosbag2_test
