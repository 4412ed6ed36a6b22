#pragma once
// Shared by the ROS 2 bag targets: a small recording (the shape of the unit
// tests' small_recording in src/io/rosbag2/rosbag2_test_util.hpp: laser
// offset, odometry on /odom and /tf, scans) written by the tests' writer in
// each storage format, and the tokens of the formats.
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "io/rosbag2/rosbag2_test_writer.hpp"

namespace dsswarm::fuzz {

inline std::vector<rosbag2_test::BagMessage> rosbag2_seed_recording() {
  using rosbag2_test::bag_message;
  std::vector<rosbag2_test::BagMessage> out = {
      bag_message("/tf_static", 10.0, rosbag2_test::transform(10.0, "base_link", "laser", 0.25, -0.1, 0.05))};
  for (int i = 0; i < 2; ++i) {
    const double t = 10.0 + i;
    out.push_back(bag_message("/odom", t, rosbag2_test::odometry(t, 0.5 * i, 0.0, 0.1 * i)));
    out.push_back(bag_message("/tf", t, rosbag2_test::transform(t, "odom", "base_link", 0.5 * i, 0.0, 0.1 * i)));
    out.push_back(bag_message("/scan", t + 0.2, rosbag2_test::laser_scan(t + 0.2, {1.0F, 2.0F, 3.0F})));
  }
  return out;
}

// The bag folder's files in `format`: metadata.yaml's text and the storage file's bytes.
struct SeedBag {
  std::string metadata;
  std::string storage;
};

inline SeedBag rosbag2_seed_bag(rosbag2_test::Format format) {
  rosbag2_test::WriteOptions options;
  options.format = format;
  options.chunk_bytes = 100000;  // one chunk
  const auto dir = scratch_dir() / "seed-bag";
  const auto files = rosbag2_test::write_bag(dir, rosbag2_seed_recording(), options);
  const auto bytes = [](const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  return {bytes(dir / "metadata.yaml"), bytes(files.front())};
}

// MCAP magic and opcodes (0x01 header .. 0x0f data end), compressions, the
// topics and types the reader wants.
inline std::vector<std::string> rosbag2_dictionary() {
  std::vector<std::string> tokens = {std::string("\x89MCAP0\r\n", 8), "zstd", "lz4", "cdr", "ros2msg", "/scan",
                                     "/odom", "/tf", "/tf_static", "sensor_msgs/msg/LaserScan",
                                     "nav_msgs/msg/Odometry", "tf2_msgs/msg/TFMessage", "base_link", "odom", "laser"};
  for (char op = 1; op <= 0x0f; ++op) tokens.push_back(std::string(1, op));
  return tokens;
}

}  // namespace dsswarm::fuzz
