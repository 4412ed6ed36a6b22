#include "net/ros2_validate.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <numbers>
#include <utility>

namespace dsswarm::net {
namespace {

constexpr std::uint32_t kNanosecondsPerSecond = 1'000'000'000;
// A rotation quaternion's squared norm must be near 1; far off it is garbage.
constexpr double kMinQuaternionNorm2 = 0.25;
constexpr double kMaxQuaternionNorm2 = 4.0;
constexpr double kFullTurn = 2.0 * std::numbers::pi;

using Field = std::pair<const char*, double>;

std::string first_non_finite(std::initializer_list<Field> fields) {
  for (const auto& [name, value] : fields) {
    if (!std::isfinite(value)) return fmt::format("{} is {}", name, value);
  }
  return "";
}

std::string check_header(const ros::Header& header, const SampleLimits& limits) {
  if (header.stamp.nanosec >= kNanosecondsPerSecond) {
    return fmt::format("header.stamp.nanosec {} is not below 1e9", header.stamp.nanosec);
  }
  const std::size_t length = header.frame_id == nullptr ? 0 : std::strlen(header.frame_id);
  if (length > limits.max_frame_id) return fmt::format("header.frame_id has {} characters", length);
  return "";
}

std::string check_frame(const char* frame, const char* name, const SampleLimits& limits) {
  const std::size_t length = frame == nullptr ? 0 : std::strlen(frame);
  if (length == 0) return fmt::format("{} is empty", name);
  if (length > limits.max_frame_id) return fmt::format("{} has {} characters", name, length);
  return "";
}

std::string check_rotation(const ros::Quaternion& q, const char* name) {
  std::string bad = first_non_finite({{"x", q.x}, {"y", q.y}, {"z", q.z}, {"w", q.w}});
  if (!bad.empty()) return fmt::format("{}.{}", name, bad);
  const double norm2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  if (norm2 < kMinQuaternionNorm2 || norm2 > kMaxQuaternionNorm2) {
    return fmt::format("{} has norm {} (not a rotation)", name, std::sqrt(norm2));
  }
  return "";
}

}  // namespace

std::string check_scan(const ros::LaserScan& s, const SampleLimits& limits) {
  if (std::string bad = check_header(s.header, limits); !bad.empty()) return bad;
  if (std::string bad = first_non_finite({{"angle_min", s.angle_min},
                                          {"angle_max", s.angle_max},
                                          {"angle_increment", s.angle_increment},
                                          {"time_increment", s.time_increment},
                                          {"scan_time", s.scan_time},
                                          {"range_min", s.range_min},
                                          {"range_max", s.range_max}});
      !bad.empty()) {
    return bad;
  }
  const std::size_t n = s.ranges._length;
  if (n == 0 || n > limits.max_beams) return fmt::format("{} ranges (need 1..{})", n, limits.max_beams);
  if (s.intensities._length > limits.max_beams) return fmt::format("{} intensities", s.intensities._length);
  if (s.angle_increment == 0.0f) return "angle_increment is 0";
  const double span = std::abs(static_cast<double>(s.angle_increment)) * static_cast<double>(n - 1);
  if (std::abs(s.angle_min) > kFullTurn || span > kFullTurn + 1e-3) {
    return fmt::format("beams span {} rad from angle_min {} (more than a turn)", span, s.angle_min);
  }
  if (!(s.range_min >= 0.0f && s.range_min < s.range_max && s.range_max <= limits.max_range)) {
    return fmt::format("range_min {} / range_max {} (need 0 <= min < max <= {})", s.range_min, s.range_max,
                       limits.max_range);
  }
  return "";
}

std::string check_odometry(const ros::Odometry& o, const SampleLimits& limits) {
  if (std::string bad = check_header(o.header, limits); !bad.empty()) return bad;
  const std::size_t child = o.child_frame_id == nullptr ? 0 : std::strlen(o.child_frame_id);
  if (child > limits.max_frame_id) return fmt::format("child_frame_id has {} characters", child);
  const auto& p = o.pose.pose.position;
  if (std::string bad =
          first_non_finite({{"pose.position.x", p.x}, {"pose.position.y", p.y}, {"pose.position.z", p.z}});
      !bad.empty()) {
    return bad;
  }
  return check_rotation(o.pose.pose.orientation, "pose.orientation");
}

std::string check_transform(const ros::TransformStamped& t, const SampleLimits& limits) {
  if (std::string bad = check_header(t.header, limits); !bad.empty()) return bad;
  if (std::string bad = check_frame(t.header.frame_id, "header.frame_id", limits); !bad.empty()) return bad;
  if (std::string bad = check_frame(t.child_frame_id, "child_frame_id", limits); !bad.empty()) return bad;
  const auto& v = t.transform.translation;
  if (std::string bad = first_non_finite({{"translation.x", v.x}, {"translation.y", v.y}, {"translation.z", v.z}});
      !bad.empty()) {
    return bad;
  }
  return check_rotation(t.transform.rotation, "rotation");
}

LaserScan to_laser_scan(const ros::LaserScan& s) {
  LaserScan scan;
  scan.timestamp = to_seconds(s.header.stamp);
  scan.angle_min = s.angle_min;
  scan.angle_increment = s.angle_increment;
  scan.range_min = s.range_min;
  scan.range_max = s.range_max;
  scan.ranges.assign(s.ranges._buffer, s.ranges._buffer + s.ranges._length);
  return scan;
}

}  // namespace dsswarm::net
