#pragma once
// Helpers shared by the CARMEN reader's tests: log records as text, and what
// reading a file gives (its error, its warnings).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "io/logs/carmen_reader.hpp"
#include "sensor/sensor_log_test_util.hpp"

namespace dsswarm::test {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = kPi / 180.0;

inline std::string flaser(const std::vector<std::string>& ranges, const Pose2& laser, const Pose2& odom, double stamp,
                          const char* type = "FLASER") {
  return fmt::format("{} {} {} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} host {:.6f}\n", type, ranges.size(),
                     fmt::join(ranges, " "), laser.x, laser.y, laser.theta, odom.x, odom.y, odom.theta, stamp,
                     stamp - 100.0);
}

// A record whose laser pose equals the robot pose (zero mounting offset).
inline std::string flaser(const std::vector<std::string>& ranges, double stamp, const Pose2& odom = {}) {
  return flaser(ranges, odom, odom, stamp);
}

inline std::vector<std::string> beams(std::size_t n, const std::string& value = "1.5") {
  return std::vector<std::string>(n, value);
}

inline std::string odom(double stamp) { return fmt::format("ODOM 0 0 0 0 0 0 {:.6f} host {:.6f}\n", stamp, stamp); }

// Runs read_carmen and returns the InputError message ("" if nothing was thrown).
inline std::string error_of(const std::filesystem::path& path, const CarmenOptions& options = {}) {
  try {
    read_carmen(path, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

inline std::string all_warnings(const SensorLog& log) { return fmt::format("{}", fmt::join(log.warnings, "\n")); }

}  // namespace dsswarm::test
