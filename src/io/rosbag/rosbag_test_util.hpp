#pragma once
// Helpers shared by the ROS1 bag reader's tests (rosbag_reader_test.cpp,
// rosbag_real_data_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "io/rosbag/rosbag_reader.hpp"
#include "sensor/sensor_log_test_util.hpp"

namespace dsswarm::rosbag_test {

inline constexpr double kPi = std::numbers::pi;
using test::has_warning;
using test::joined;

inline void expect_pose_near(const std::optional<Pose2>& actual, const Pose2& expected, double tol) {
  ASSERT_TRUE(actual.has_value());
  EXPECT_NEAR(actual->x, expected.x, tol);
  EXPECT_NEAR(actual->y, expected.y, tol);
  EXPECT_NEAR(normalize_angle(actual->theta - expected.theta), 0.0, tol);
}

inline std::string input_error_of(const std::filesystem::path& path, const RosbagOptions& options = {}) {
  try {
    read_rosbag(path, options);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return {};
}

inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace dsswarm::rosbag_test
