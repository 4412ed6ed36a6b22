#pragma once
// Shared by the ROS 2 bag tests: the small recording they write in every
// format, and helpers to look at what the reader says.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/test_files.hpp"
#include "io/rosbag2/rosbag2_reader.hpp"
#include "io/rosbag2/rosbag2_test_writer.hpp"
#include "sensor/sensor_log_test_util.hpp"

namespace dsswarm::rosbag2_test {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;
using test::has_warning;
using test::joined;

inline BagMessage scan_at(double stamp, std::vector<float> ranges) {
  return bag_message("/scan", stamp, laser_scan(stamp, std::move(ranges)));
}

// Odometry on /odom and the same pose as odom -> base_link on /tf.
inline std::vector<BagMessage> odom_at(double stamp, double x, double y, double theta) {
  return {bag_message("/odom", stamp, odometry(stamp, x, y, theta)),
          bag_message("/tf", stamp, transform(stamp, "odom", "base_link", x, y, theta))};
}

// What the ROS1 reader's tests record, as a ROS 2 robot would: the laser
// offset on /tf_static, odometry at 10, 11, 12 s (one glitched record in
// between, stamped 13.5), five scans of which the third is stamped 0.4 s
// ahead of its true time.
inline std::vector<BagMessage> small_recording(bool with_odom_topic = true) {
  std::vector<std::vector<BagMessage>> parts = {
      {bag_message("/tf_static", 10.0, transform(10.0, "base_link", "laser", 0.25, -0.1, 0.05))},
      odom_at(10.0, 0.0, 0.0, 0.0),
      {scan_at(10.2, {1.0F, 2.0F, 3.0F})},
      {scan_at(10.4, {1.5F, 2.5F, 3.5F})},
      odom_at(11.0, 1.0, 2.0, kPi / 2),
      {scan_at(10.9, {4.0F, 40.0F, 0.0F})},  // stamp jumps ahead of the true 10.5 s
      odom_at(13.5, 50.0, 50.0, -1.0),       // glitch: must not be interpolated through
      {scan_at(10.6, {5.0F, 5.0F, 5.0F})},
      odom_at(12.0, 1.0, 4.0, kPi),
      {scan_at(11.5, {6.0F, 6.0F, 6.0F})},
  };
  std::vector<BagMessage> out;
  for (auto& part : parts) {
    for (auto& m : part) {
      if (with_odom_topic || m.topic != "/odom") out.push_back(std::move(m));
    }
  }
  return out;
}

// Writes `messages` as the bag folder DSSWARM_TEST_TMP/rosbag2/`name`.
inline fs::path write_test_bag(const std::string& name, const std::vector<BagMessage>& messages,
                               const WriteOptions& options) {
  const fs::path dir = fs::path(DSSWARM_TEST_TMP) / "rosbag2" / name;
  write_bag(dir, messages, options);
  return dir;
}

inline std::string input_error_of(const fs::path& path, const BagReadOptions& options = {}) {
  try {
    read_rosbag2(path, options);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return {};
}

inline std::string read_file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_file_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace dsswarm::rosbag2_test
