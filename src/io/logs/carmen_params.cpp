#include "io/logs/carmen_params.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/errors.hpp"

namespace dsswarm::carmen_detail {

namespace {
// A laser's beams span at most a full turn; the slack allows for rounding in
// logs that state the increment to a few digits.
constexpr double kFullTurn = 2.0 * std::numbers::pi;
constexpr double kTurnSlack = 1e-3;  // rad
}  // namespace

void CarmenParams::parse(const Tokens& fields, std::size_t line) {
  const std::string_view key = fields[1];
  const std::pair<std::string_view, std::optional<Param>*> numeric[] = {
      {"laser_angle_min", &params_.angle_min},
      {"laser_angle_max", &params_.angle_max},
      {"laser_angle_increment", &params_.angle_increment},
      {"laser_num_beams", &params_.num_beams},
      {"laser_range_min", &params_.range_min},
      {"laser_range_max", &params_.range_max},
      {"laser_offset_x", &params_.offset_x},
      {"laser_offset_y", &params_.offset_y},
      {"laser_offset_theta", &params_.offset_theta},
  };
  const Where where{file_, line, "# PARAM"};
  if (key == "odometry") {
    if (fields.size() < 3) where.fail("odometry: missing value");
    params_.no_odometry = fields[2] == "none";
    return;
  }
  for (const auto& [name, slot] : numeric) {
    if (key != name) continue;
    double value = 0.0;
    const std::string problem = problem_of(fields, slot, value);
    if (problem.empty()) {
      *slot = Param{value, line};
    } else {
      bad_params_.push_back({std::string(name), line, problem});  // fatal only where the value is used
    }
    return;
  }
}

std::string CarmenParams::problem_of(const Tokens& fields, const std::optional<Param>* slot, double& value) const {
  if (fields.size() < 3) return "missing value";
  if (!parse_whole(fields[2], value)) return fmt::format("'{}' is not a number", shown(fields[2]));
  if (!std::isfinite(value)) return fmt::format("'{}' is not finite", shown(fields[2]));
  if (slot == &params_.num_beams && (value < 1.0 || value != std::floor(value) || value > 1e7))
    return fmt::format("'{}' is not a positive whole number", shown(fields[2]));
  if (slot == &params_.angle_increment && value == 0.0) return "must not be 0";
  return "";
}

// A broken `# PARAM` line is an error where its value would be used, else
// a warning: the records carry their own geometry (ROBOTLASER1), an option
// overrides it, or the scan poses give the laser offset instead.
void CarmenParams::check_bad(std::string_view type, bool own_geometry, std::vector<std::string>& warnings) {
  for (const BadParam& bad : bad_params_) {
    const std::string what = fmt::format("{}:{}: # PARAM {}: {}", file_, bad.line, bad.key, bad.problem);
    const std::string why_unused = unused_reason(bad.key, type, own_geometry);
    if (why_unused.empty()) throw InputError(what);
    warnings.push_back(fmt::format("{}; ignored ({})", what, why_unused));
    if (bad.key.starts_with("laser_offset")) params_.offset_x = params_.offset_y = params_.offset_theta = {};
  }
}

std::string CarmenParams::unused_reason(const std::string& key, std::string_view type, bool own_geometry) const {
  if (key.starts_with("laser_offset")) {
    if (options_.laser_offset) return "the laser offset option overrides it";
    if (!params_.no_odometry) return "the laser offset comes from the scan poses instead";
    return "";
  }
  if (key == "laser_range_min") return "";  // applies to every record
  if (own_geometry) return fmt::format("the {} records state their own beam layout and range", type);
  if (key != "laser_range_max" && options_.beams != CarmenOptions::BeamConvention::FromParams)
    return "the beam convention option overrides it";
  return "";
}

BeamGeometry CarmenParams::beam_geometry(std::size_t n, std::size_t line, std::string_view type) const {
  using Convention = CarmenOptions::BeamConvention;
  if (options_.beams == Convention::Classic) return classic_beam_geometry(n);
  if (options_.beams == Convention::Span180) return span180_beam_geometry(n);
  if (!params_.has_geometry()) return classic_beam_geometry(n);
  if (params_.num_beams && static_cast<double>(n) != params_.num_beams->value) {
    Where{file_, line, type}.fail(fmt::format("{} ranges, but '# PARAM laser_num_beams {}' (line {})", n,
                                              params_.num_beams->value, params_.num_beams->line));
  }
  const double span_steps = static_cast<double>(n > 0 ? n - 1 : 0);
  BeamGeometry geometry = classic_beam_geometry(n);
  if (params_.angle_increment) {
    geometry.angle_increment = params_.angle_increment->value;
  } else if (params_.angle_min && params_.angle_max && n > 1) {
    geometry.angle_increment = (params_.angle_max->value - params_.angle_min->value) / span_steps;
  }
  if (params_.angle_min) {
    geometry.angle_min = params_.angle_min->value;
  } else if (params_.angle_max) {
    geometry.angle_min = params_.angle_max->value - span_steps * geometry.angle_increment;
  } else {
    geometry.angle_min = -span_steps * geometry.angle_increment / 2.0;
  }
  // Each value is finite, but together they may not be (an increment of 1e308).
  const double span = span_steps * std::abs(geometry.angle_increment);
  if (!std::isfinite(geometry.angle_min) || !(span <= kFullTurn + kTurnSlack)) {
    Where{file_, line, type}.fail(fmt::format(
        "the '# PARAM laser_angle_*' lines give {} beams spanning {} rad, more than a full turn", n, span));
  }
  return geometry;
}

std::pair<double, double> CarmenParams::range_limits() const {
  const double range_min = params_.range_min ? params_.range_min->value : 0.0;
  const double range_max = params_.range_max ? params_.range_max->value : kCarmenDefaultRangeMax;
  if (range_min < 0.0) {
    Where{file_, params_.range_min->line, "# PARAM"}.fail(
        fmt::format("laser_range_min must not be negative, got {}", range_min));
  }
  if (params_.range_max && range_max <= range_min) {
    Where{file_, params_.range_max->line, "# PARAM"}.fail(
        fmt::format("laser_range_max ({}) must be above laser_range_min ({})", range_max, range_min));
  }
  return {range_min, range_max};
}

// Options override > `# PARAM` offsets > the offset implied by the first
// record's laser and robot poses. The poses of every record are checked
// against the chosen offset so a log with a moving laser is noticed.
Pose2 CarmenParams::laser_offset(const std::vector<Pose2>& implied, std::vector<std::string>& warnings) const {
  if (options_.laser_offset) return *options_.laser_offset;
  const auto differs = [](const Pose2& a, const Pose2& b, double metres, double radians) {
    return std::hypot(a.x - b.x, a.y - b.y) > metres || std::abs(normalize_angle(a.theta - b.theta)) > radians;
  };
  // Logs store poses rounded to 1e-6, so implied offsets jitter at that level.
  constexpr double kJitterMetres = 1e-3, kJitterRadians = 1e-3;
  // A stated offset that disagrees by more than this with the poses deserves a word.
  constexpr double kDisagreeMetres = 0.01, kDisagreeRadians = 0.01;
  if (params_.has_offset()) {
    const Pose2 stated(params_.offset_x ? params_.offset_x->value : 0.0,
                       params_.offset_y ? params_.offset_y->value : 0.0,
                       params_.offset_theta ? params_.offset_theta->value : 0.0);
    if (!params_.no_odometry) {
      const Pose2 first = implied.front();
      if (differs(stated, first, kDisagreeMetres, kDisagreeRadians)) {
        warnings.push_back(fmt::format(
            "{}: '# PARAM laser_offset' ({:.4f}, {:.4f}, {:.4f}) differs from the offset implied by the scan poses "
            "({:.4f}, {:.4f}, {:.4f}); using the PARAM",
            file_, stated.x, stated.y, stated.theta, first.x, first.y, first.theta));
      }
    }
    return stated;
  }
  if (params_.no_odometry) return Pose2{};
  const Pose2 offset = implied.front();
  const std::size_t varying = static_cast<std::size_t>(std::count_if(
      implied.begin(), implied.end(),
      [&](const Pose2& p) { return differs(p, offset, kJitterMetres, kJitterRadians); }));
  if (varying > 0) {
    warnings.push_back(fmt::format(
        "{}: the laser offset implied by the scan poses varies in {} of {} scans; using the first one "
        "({:.4f}, {:.4f}, {:.4f})",
        file_, varying, implied.size(), offset.x, offset.y, offset.theta));
  }
  return offset;
}

}  // namespace dsswarm::carmen_detail
