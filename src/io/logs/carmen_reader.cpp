#include "io/logs/carmen_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "io/logs/carmen_fields.hpp"
#include "io/logs/carmen_params.hpp"
#include "io/logs/text_line_reader.hpp"
#include "io/trajectory/text_fields.hpp"

namespace dsswarm {

BeamGeometry classic_beam_geometry(std::size_t n) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  double increment = 0.0;
  if (n == 180) {
    increment = 1.0 * kDeg;
  } else if (n == 360 || n == 361) {
    increment = 0.5 * kDeg;
  } else if (n == 720 || n == 721) {
    increment = 0.25 * kDeg;
  } else if (n > 1) {
    increment = std::numbers::pi / static_cast<double>(n - 1);
  }
  // Centred on the laser's forward axis.
  return {-static_cast<double>(n > 0 ? n - 1 : 0) * increment / 2.0, increment};
}

BeamGeometry span180_beam_geometry(std::size_t n) {
  const double increment = n > 1 ? std::numbers::pi / static_cast<double>(n - 1) : 0.0;
  return {-std::numbers::pi / 2.0, increment};
}

namespace {

using carmen_detail::CarmenParams;
using carmen_detail::count_field;
using carmen_detail::finite_field;
using carmen_detail::number_field;
using carmen_detail::parse_whole;
using carmen_detail::pose_fields;
using carmen_detail::read_ranges;
using carmen_detail::shown;
using carmen_detail::Tokens;
using carmen_detail::Where;

// One laser record as read, before the file-wide geometry and offset are known.
struct LaserRecord {
  LaserScan scan;
  Pose2 laser_pose;  // laser in the odometry frame
  Pose2 robot_pose;  // robot base in the odometry frame
  std::size_t line = 0;
  bool has_own_geometry = false;  // ROBOTLASER1 states its beam layout
};

// Record types CARMEN defines that carry nothing we use: skipped silently.
constexpr std::array<std::string_view, 34> kKnownOtherRecords = {
    "PARAM",          "SYNC",           "TRUEPOS",        "RAWLASER1",       "RAWLASER2",
    "RAWLASER3",      "RAWLASER4",      "ROBOTLASER0",    "ROBOTLASER2",     "LASER3",
    "LASER4",         "REMISSIONFLASER", "REMISSIONRLASER", "REMISSIONLASER3", "REMISSIONLASER4",
    "POSITIONLASER",  "NMEAGGA",        "NMEARMC",        "NMEA-GGA",        "NMEA-RMC",
    "GPSNMEA",        "SONAR",          "BUMPER",         "SCANMARK",        "IMU",
    "VECTORMOVE",     "ROBOTVELOCITY",  "FOLLOWTRAJECTORY", "FOLLOW-TRAJECTORY", "BASEVELOCITY",
    "OLD",            "COMMENT",        "MARKER",         "GLOBALPOS"};

constexpr std::size_t kMaxUnknownTypeWarnings = 10;

class CarmenParser {
 public:
  CarmenParser(std::string file, const CarmenOptions& options)
      : file_(std::move(file)), params_(file_, options) {}

  void parse_line(std::string_view text, std::size_t line) {
    const std::size_t first = text.find_first_not_of(" \t");
    if (first == std::string_view::npos) return;
    text.remove_prefix(first);
    if (text.front() == '#') {
      split_fields(text.substr(1), fields_);
      if (fields_.size() >= 2 && fields_[0] == "PARAM") params_.parse(fields_, line);
      return;
    }
    split_fields(text, fields_);
    if (fields_.empty()) return;
    const std::string_view type = fields_[0];
    if (type == "FLASER") {
      parse_old_laser(line, type, flaser_);
    } else if (type == "RLASER") {
      parse_old_laser(line, type, rlaser_);
    } else if (type == "ROBOTLASER1") {
      parse_robotlaser(line);
    } else if (type == "ODOM") {
      parse_odom(line);
    } else if (std::find(kKnownOtherRecords.begin(), kKnownOtherRecords.end(), type) == kKnownOtherRecords.end()) {
      auto [it, inserted] = unknown_types_.try_emplace(std::string(type), UnknownType{line, 0});
      ++it->second.count;
      if (inserted) unknown_order_.push_back(it->first);
    }
  }

  SensorLog finish() {
    SensorLog log;
    log.source = file_;
    const auto [chosen, chosen_type] = choose_stream();
    note_ignored_streams(chosen_type, log.warnings);
    params_.check_bad(chosen_type, chosen->front().has_own_geometry, log.warnings);
    const Pose2 offset = params_.laser_offset(implied_offsets(*chosen), log.warnings);
    const ScanProblems problems = prepare_scans(*chosen, chosen_type, offset, log.scans);
    add_end_warnings(problems, log);
    return log;
  }

 private:
  struct UnknownType {
    std::size_t first_line = 0;
    std::size_t count = 0;
  };

  // Range readings and timestamps kept as they are, counted for the warnings.
  struct ScanProblems {
    std::size_t nonfinite = 0, negative = 0;
    std::size_t backwards = 0;
  };

  // Each record's laser pose in its robot's frame.
  static std::vector<Pose2> implied_offsets(const std::vector<LaserRecord>& records) {
    std::vector<Pose2> out;
    out.reserve(records.size());
    for (const LaserRecord& r : records) out.push_back(between(r.robot_pose, r.laser_pose));
    return out;
  }

  std::pair<std::vector<LaserRecord>*, std::string_view> choose_stream() {
    if (!flaser_.empty()) return {&flaser_, "FLASER"};
    if (!robotlaser_.empty()) return {&robotlaser_, "ROBOTLASER1"};
    if (!rlaser_.empty()) return {&rlaser_, "RLASER"};
    throw InputError(file_ + ": no laser scans (FLASER/RLASER/ROBOTLASER1) found" +
                     (empty_scans_ > 0 ? fmt::format(" ({} records have 0 readings)", empty_scans_) : ""));
  }

  // Gives the chosen records the file-wide geometry, range limits, odometry and
  // offset, and moves their scans to `scans` in file order.
  ScanProblems prepare_scans(std::vector<LaserRecord>& records, std::string_view type, const Pose2& offset,
                             std::vector<LaserScan>& scans) const {
    const auto [range_min, range_max] = params_.range_limits();
    ScanProblems problems;
    scans.reserve(records.size());
    for (LaserRecord& record : records) {
      LaserScan& scan = record.scan;
      if (!record.has_own_geometry) {
        const BeamGeometry geometry = params_.beam_geometry(scan.ranges.size(), record.line, type);
        scan.angle_min = geometry.angle_min;
        scan.angle_increment = geometry.angle_increment;
        scan.range_max = range_max;
      }
      scan.range_min = range_min;
      if (scan.range_max <= scan.range_min) {
        Where{file_, record.line, type}.fail(fmt::format(
            "maximum range {} m is not above the minimum range {} m", scan.range_max, scan.range_min));
      }
      if (!params_.no_odometry()) scan.odometry = record.robot_pose;
      scan.laser_offset = offset;
      problems.nonfinite += static_cast<std::size_t>(
          std::count_if(scan.ranges.begin(), scan.ranges.end(), [](float r) { return !std::isfinite(r); }));
      problems.negative += static_cast<std::size_t>(
          std::count_if(scan.ranges.begin(), scan.ranges.end(), [](float r) { return std::isfinite(r) && r < 0.0f; }));
      if (!scans.empty() && scan.timestamp < scans.back().timestamp) ++problems.backwards;
      scans.push_back(std::move(scan));
    }
    return problems;
  }

  void add_end_warnings(const ScanProblems& problems, SensorLog& log) const {
    if (problems.backwards > 0) {
      log.warnings.push_back(fmt::format("{}: {} of {} scan timestamps run backwards (kept in file order)", file_,
                                         problems.backwards, log.scans.size()));
    }
    if (odom_backwards_ > 0) {
      log.warnings.push_back(fmt::format("{}: {} of {} ODOM timestamps run backwards (kept in file order)", file_,
                                         odom_backwards_, odom_count_));
    }
    if (problems.nonfinite > 0) {
      log.warnings.push_back(fmt::format("{}: {} range readings are NaN or inf (kept; they count as invalid beams)",
                                         file_, problems.nonfinite));
    }
    if (problems.negative > 0) {
      log.warnings.push_back(fmt::format("{}: {} range readings are negative (kept; they count as invalid beams)",
                                         file_, problems.negative));
    }
    if (empty_scans_ > 0) {
      log.warnings.push_back(fmt::format("{}: skipped {} laser records with 0 readings", file_, empty_scans_));
    }
    for (std::size_t i = 0; i < unknown_order_.size(); ++i) {
      if (i == kMaxUnknownTypeWarnings) {
        log.warnings.push_back(fmt::format("{}: {} more unknown record types skipped", file_,
                                           unknown_order_.size() - kMaxUnknownTypeWarnings));
        break;
      }
      const UnknownType& u = unknown_types_.at(unknown_order_[i]);
      log.warnings.push_back(fmt::format("{}:{}: unknown record type '{}' skipped ({} line{})", file_, u.first_line,
                                         shown(unknown_order_[i]), u.count, u.count == 1 ? "" : "s"));
    }
  }

  // FLASER/RLASER n r1..rn x y theta odom_x odom_y odom_theta timestamp host logger_timestamp
  void parse_old_laser(std::size_t line, std::string_view type, std::vector<LaserRecord>& out) {
    const Where where{file_, line, type};
    if (fields_.size() < 2) where.fail("missing field 'num_readings'");
    const std::size_t n = count_field(where, fields_[1], "num_readings");
    constexpr std::size_t kTrailing = 9;  // x y theta odom_x odom_y odom_theta timestamp host logger_timestamp
    const std::size_t after = fields_.size() - 2;
    if (n > after || after - n != kTrailing) {  // not n + kTrailing: a count near 2^64 wraps
      const std::size_t found = after < n ? after : after - std::min(after, kTrailing);
      where.fail(fmt::format("expected {} ranges, found {} ({} fields after num_readings; the record needs the {} "
                             "ranges then x y theta odom_x odom_y odom_theta timestamp host logger_timestamp)",
                             n, found, after, n));
    }
    if (n == 0) {
      ++empty_scans_;
      return;
    }
    LaserRecord record;
    record.line = line;
    read_ranges(where, fields_, 2, n, record.scan.ranges);
    const std::size_t tail = 2 + n;
    record.laser_pose = pose_fields(where, fields_, tail, {"x", "y", "theta"});
    record.robot_pose = pose_fields(where, fields_, tail + 3, {"odom_x", "odom_y", "odom_theta"});
    record.scan.timestamp = finite_field(where, fields_[tail + 6], "timestamp");
    number_field(where, fields_[tail + 8], "logger_timestamp");
    out.push_back(std::move(record));
  }

  // ROBOTLASER1 laser_type start_angle fov angular_res max_range accuracy remission_mode
  //   n r1..rn k rem1..remk laser_x laser_y laser_theta robot_x robot_y robot_theta
  //   tv rv forward_safety side_safety turn_axis timestamp host logger_timestamp
  void parse_robotlaser(std::size_t line) {
    const Where where{file_, line, "ROBOTLASER1"};
    constexpr std::size_t kHeader = 9;  // type name + 7 parameters + num_readings
    if (fields_.size() < kHeader) {
      where.fail(fmt::format("expected at least {} fields before the ranges, found {}", kHeader, fields_.size()));
    }
    number_field(where, fields_[1], "laser_type");
    const double start_angle = finite_field(where, fields_[2], "start_angle");
    number_field(where, fields_[3], "field_of_view");
    const double resolution = finite_field(where, fields_[4], "angular_resolution");
    const double max_range = finite_field(where, fields_[5], "maximum_range");
    number_field(where, fields_[6], "accuracy");
    number_field(where, fields_[7], "remission_mode");
    const std::size_t n = count_field(where, fields_[8], "num_readings");
    if (n >= fields_.size() - kHeader) {  // not kHeader + n + 1: a count near 2^64 wraps
      where.fail(fmt::format("expected {} ranges then num_remissions, found {} fields after num_readings", n,
                             fields_.size() - kHeader));
    }
    const std::size_t k = count_field(where, fields_[kHeader + n], "num_remissions");
    constexpr std::size_t kTrailing = 14;  // 2 poses, tv rv forward side turn, timestamp host logger_timestamp
    const std::size_t after = fields_.size() - (kHeader + n + 1);
    if (k > after || after - k != kTrailing) {
      where.fail(fmt::format("expected {} remissions then {} fields (laser pose, robot pose, tv rv forward_safety "
                             "side_safety turn_axis timestamp host logger_timestamp), found {} fields after "
                             "num_remissions",
                             k, kTrailing, after));
    }
    if (n == 0) {
      ++empty_scans_;
      return;
    }
    if (resolution == 0.0) where.fail("field 'angular_resolution' must not be 0");
    if (!(max_range > 0.0)) where.fail(fmt::format("field 'maximum_range' must be positive, got {}", max_range));
    LaserRecord record;
    record.line = line;
    record.has_own_geometry = true;
    record.scan.angle_min = start_angle;
    record.scan.angle_increment = resolution;
    record.scan.range_max = max_range;
    read_ranges(where, fields_, kHeader, n, record.scan.ranges);
    const std::size_t first_remission = kHeader + n + 1;
    for (std::size_t i = 0; i < k; ++i) number_field(where, fields_[first_remission + i], "remission");
    const std::size_t tail = first_remission + k;
    record.laser_pose = pose_fields(where, fields_, tail, {"laser_x", "laser_y", "laser_theta"});
    record.robot_pose = pose_fields(where, fields_, tail + 3, {"robot_x", "robot_y", "robot_theta"});
    static constexpr std::array<std::string_view, 5> kMotion = {"tv", "rv", "forward_safety", "side_safety",
                                                                "turn_axis"};
    for (std::size_t i = 0; i < kMotion.size(); ++i) number_field(where, fields_[tail + 6 + i], kMotion[i]);
    record.scan.timestamp = finite_field(where, fields_[tail + 11], "timestamp");
    number_field(where, fields_[tail + 13], "logger_timestamp");
    robotlaser_.push_back(std::move(record));
  }

  // ODOM x y theta tv rv accel timestamp host logger_timestamp. Validated and
  // checked for order only: laser records carry their own odometry pose.
  void parse_odom(std::size_t line) {
    const Where where{file_, line, "ODOM"};
    constexpr std::size_t kFields = 9;
    if (fields_.size() - 1 != kFields) {
      where.fail(fmt::format("expected {} fields (x y theta tv rv accel timestamp host logger_timestamp), found {}",
                             kFields, fields_.size() - 1));
    }
    pose_fields(where, fields_, 1, {"x", "y", "theta"});
    number_field(where, fields_[4], "tv");
    number_field(where, fields_[5], "rv");
    number_field(where, fields_[6], "accel");
    const double timestamp = finite_field(where, fields_[7], "timestamp");
    number_field(where, fields_[9], "logger_timestamp");
    if (odom_count_ > 0 && timestamp < last_odom_timestamp_) ++odom_backwards_;
    last_odom_timestamp_ = timestamp;
    ++odom_count_;
  }

  void note_ignored_streams(std::string_view chosen, std::vector<std::string>& warnings) const {
    const std::pair<std::string_view, std::size_t> streams[] = {
        {"FLASER", flaser_.size()}, {"ROBOTLASER1", robotlaser_.size()}, {"RLASER", rlaser_.size()}};
    for (const auto& [type, count] : streams) {
      if (type != chosen && count > 0) {
        warnings.push_back(fmt::format("{}: ignored {} {} records (read the {} scans)", file_, count, type, chosen));
      }
    }
  }


  std::string file_;
  Tokens fields_;
  CarmenParams params_;
  std::vector<LaserRecord> flaser_, rlaser_, robotlaser_;
  std::size_t empty_scans_ = 0;
  std::size_t odom_count_ = 0;
  std::size_t odom_backwards_ = 0;
  double last_odom_timestamp_ = 0.0;
  std::map<std::string, UnknownType, std::less<>> unknown_types_;
  std::vector<std::string> unknown_order_;
};

}  // namespace

SensorLog read_carmen(const std::filesystem::path& path, const CarmenOptions& options) {
  TextLineReader reader(path);
  CarmenParser parser(reader.name(), options);
  std::string_view line;
  while (reader.next(line)) parser.parse_line(line, reader.line_number());
  return parser.finish();
}

SensorLog parse_carmen(std::string_view text, const std::string& source_name, const CarmenOptions& options) {
  CarmenParser parser(source_name, options);
  std::size_t line_number = 0;
  while (!text.empty()) {
    const std::size_t newline = std::min(text.find('\n'), text.size());
    std::string_view line = text.substr(0, newline);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    parser.parse_line(line, ++line_number);
    text.remove_prefix(std::min(newline + 1, text.size()));
  }
  return parser.finish();
}

}  // namespace dsswarm
