#include "io/trajectory/tum.hpp"

#include <array>
#include <cmath>
#include <iterator>
#include <string_view>

#include <fmt/format.h>

#include "common/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/trajectory/text_fields.hpp"

namespace dsswarm {

namespace {

constexpr std::array<std::string_view, 8> kFieldNames = {"timestamp", "x", "y", "z", "qx", "qy", "qz", "qw"};

// A TUM quaternion must be a rotation. Writers round to a few decimals, so
// allow a little slack; anything further off is a different format, not noise.
constexpr double kQuaternionNormTolerance = 1e-2;

// Yaw (rotation about z) of a possibly 3D rotation, ZYX convention. The
// ratio form is independent of the quaternion's scale, so slightly
// unnormalised quaternions from other tools give the right angle.
double yaw_from_quaternion(double qx, double qy, double qz, double qw) {
  return std::atan2(2.0 * (qw * qz + qx * qy), qw * qw + qx * qx - qy * qy - qz * qz);
}

StampedPose parse_tum_line(std::string_view line, const std::string& where) {
  const auto fields = split_fields(line);
  if (fields.size() != kFieldNames.size()) {
    throw InputError(fmt::format("{}: expected 8 fields (timestamp x y z qx qy qz qw), found {}", where,
                                 fields.size()));
  }
  std::array<double, 8> v{};
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = parse_finite_field(fields[i], where, kFieldNames[i]);
  const double qx = v[4], qy = v[5], qz = v[6], qw = v[7];
  const double norm = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
  if (!(std::abs(norm - 1.0) <= kQuaternionNormTolerance)) {
    throw InputError(fmt::format("{}: quaternion (qx qy qz qw) has norm {:.6g}, expected 1", where, norm));
  }
  return {v[0], Pose2(v[1], v[2], yaw_from_quaternion(qx, qy, qz, qw))};
}

}  // namespace

std::string format_tum(const std::filesystem::path& path, const Trajectory& trajectory) {
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    const StampedPose& s = trajectory[i];
    if (!std::isfinite(s.timestamp) || !std::isfinite(s.pose.x) || !std::isfinite(s.pose.y) ||
        !std::isfinite(s.pose.theta)) {
      throw InputError(fmt::format("refusing to write {}: trajectory entry {} (timestamp {}) is not finite",
                                   path.string(), i, s.timestamp));
    }
  }
  std::string text = "# timestamp x y z qx qy qz qw\n";
  for (const StampedPose& s : trajectory) {
    const double half = 0.5 * s.pose.theta;  // theta in (-pi, pi], so qw >= 0
    fmt::format_to(std::back_inserter(text), "{:.6f} {:.9f} {:.9f} 0.000000 0.000000000 0.000000000 {:.9f} {:.9f}\n",
                   s.timestamp, s.pose.x, s.pose.y, std::sin(half), std::cos(half));
  }
  return text;
}

void write_tum(const std::filesystem::path& path, const Trajectory& trajectory) {
  write_file_atomically(path, format_tum(path, trajectory));
}

Trajectory read_tum(std::istream& in, const std::string& source_name) {
  Trajectory trajectory;
  for_each_data_line(in, source_name, [&](std::string_view line, const std::string& where) {
    trajectory.push_back(parse_tum_line(line, where));
  });
  return trajectory;
}

Trajectory read_tum(const std::filesystem::path& path) {
  std::ifstream in = open_text_input(path, "trajectory");
  return read_tum(in, path.string());
}

}  // namespace dsswarm
