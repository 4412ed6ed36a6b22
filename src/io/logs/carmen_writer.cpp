#include "io/logs/carmen_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <string_view>

#include "common/errors.hpp"
#include "io/atomic_file.hpp"

namespace dsswarm {
namespace {

// "{}" formats a double or float in the shortest form that reads back to the
// same value, so a write/read round trip is exact.
void check_scans(const std::filesystem::path& path, const std::vector<LaserScan>& scans) {
  const auto finite = [](const Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); };
  const LaserScan& first = scans.front();
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const LaserScan& s = scans[i];
    const char* problem = nullptr;
    if (s.ranges.empty()) problem = "has no range readings";
    else if (!std::isfinite(s.timestamp)) problem = "has a non-finite timestamp";
    else if (s.odometry && !finite(*s.odometry)) problem = "has a non-finite odometry pose";
    else if (!finite(s.laser_offset)) problem = "has a non-finite laser offset";
    else if (!std::isfinite(s.angle_min) || !std::isfinite(s.angle_increment) || !std::isfinite(s.range_min) ||
             !std::isfinite(s.range_max))
      problem = "has a non-finite beam geometry";
    if (problem != nullptr) throw InputError(fmt::format("cannot write {}: scan {} {}", path.string(), i, problem));
    const char* field = nullptr;
    if (s.angle_min != first.angle_min) field = "angle_min";
    else if (s.angle_increment != first.angle_increment) field = "angle_increment";
    else if (s.range_min != first.range_min) field = "range_min";
    else if (s.range_max != first.range_max) field = "range_max";
    else if (s.laser_offset.x != first.laser_offset.x || s.laser_offset.y != first.laser_offset.y ||
             s.laser_offset.theta != first.laser_offset.theta)
      field = "laser_offset";
    if (field != nullptr) {
      throw InputError(fmt::format("cannot write {} as CARMEN FLASER: scan {} has a different {} than scan 0 "
                                   "(the format holds one beam layout per file)",
                                   path.string(), i, field));
    }
  }
}

void write_header(std::string& out, const std::vector<LaserScan>& scans, const std::string& comment) {
  auto line = std::back_inserter(out);
  fmt::format_to(line, "# CARMEN log written by dsswarm\n");
  std::istringstream comment_lines(comment);
  for (std::string text; std::getline(comment_lines, text);) {
    // A comment that itself reads "PARAM ..." must not be taken for one.
    const bool looks_like_param = text.find_first_not_of(" \t") != std::string::npos &&
                                  text.substr(text.find_first_not_of(" \t")).rfind("PARAM", 0) == 0;
    fmt::format_to(line, "# {}{}\n", looks_like_param ? "comment: " : "", text);
  }
  fmt::format_to(line,
                 "# message formats: FLASER num_readings [range_readings] x y theta odom_x odom_y odom_theta "
                 "timestamp hostname logger_timestamp\n");
  fmt::format_to(line, "# (x y theta = laser pose by odometry = odometry (+) laser offset)\n");

  const LaserScan& first = scans.front();
  const bool same_beam_count = std::all_of(scans.begin(), scans.end(), [&](const LaserScan& s) {
    return s.ranges.size() == first.ranges.size();
  });
  fmt::format_to(line, "# PARAM laser_format FLASER\n");
  fmt::format_to(line, "# PARAM laser_angle_min {}\n", first.angle_min);
  if (same_beam_count) {
    fmt::format_to(line, "# PARAM laser_angle_max {}\n",
                   first.beam_angle(first.ranges.empty() ? 0 : first.ranges.size() - 1));
  }
  fmt::format_to(line, "# PARAM laser_angle_increment {}\n", first.angle_increment);
  if (same_beam_count) fmt::format_to(line, "# PARAM laser_num_beams {}\n", first.ranges.size());
  fmt::format_to(line, "# PARAM laser_range_min {}\n", first.range_min);
  fmt::format_to(line, "# PARAM laser_range_max {}\n", first.range_max);
  fmt::format_to(line, "# PARAM laser_offset_x {}\n", first.laser_offset.x);
  fmt::format_to(line, "# PARAM laser_offset_y {}\n", first.laser_offset.y);
  fmt::format_to(line, "# PARAM laser_offset_theta {}\n", first.laser_offset.theta);
  const bool any_odometry =
      std::any_of(scans.begin(), scans.end(), [](const LaserScan& s) { return s.odometry.has_value(); });
  if (!any_odometry) fmt::format_to(line, "# PARAM odometry none\n");
}

void write_flaser(std::string& out, const LaserScan& scan, double first_timestamp) {
  auto line = std::back_inserter(out);
  fmt::format_to(line, "FLASER {}", scan.ranges.size());
  for (float r : scan.ranges) fmt::format_to(line, " {}", r);
  const Pose2 odometry = scan.odometry.value_or(Pose2{});
  const Pose2 laser = scan.odometry ? odometry * scan.laser_offset : Pose2{};
  fmt::format_to(line, " {} {} {} {} {} {} {} dsswarm {}\n", laser.x, laser.y, laser.theta, odometry.x, odometry.y,
                 odometry.theta, scan.timestamp, scan.timestamp - first_timestamp);
}

}  // namespace

std::string format_carmen(const std::filesystem::path& path, const std::vector<LaserScan>& scans,
                          const std::string& comment) {
  if (scans.empty()) throw InputError("cannot write " + path.string() + ": no scans to write");
  check_scans(path, scans);
  std::string text;
  write_header(text, scans, comment);
  for (const LaserScan& scan : scans) write_flaser(text, scan, scans.front().timestamp);
  return text;
}

void write_carmen(const std::filesystem::path& path, const std::vector<LaserScan>& scans,
                  const std::string& comment) {
  write_file_atomically(path, format_carmen(path, scans, comment));
}

}  // namespace dsswarm
