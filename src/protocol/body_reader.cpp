#include "protocol/body_reader.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/agent_name.hpp"

namespace dsswarm::protocol::wire_detail {

double BodyReader::finite(const char* field) {
  const double v = r_.f64(field);
  if (!std::isfinite(v)) fail(fmt::format("{} is not finite", field));
  return v;
}

double BodyReader::in_range(const char* field, double lo, double hi) {
  const double v = finite(field);
  if (v < lo || v > hi) fail(fmt::format("{} = {} is outside [{}, {}]", field, v, lo, hi));
  return v;
}

double BodyReader::stamp(const char* field) {
  const double v = r_.f64(field);
  if (std::isinf(v)) fail(fmt::format("{} is infinite", field));
  return v;
}

bool BodyReader::flag(const char* field) {
  const std::uint8_t v = r_.u8(field);
  if (v > 1) fail(fmt::format("{} flag is {}, not 0 or 1", field, v));
  return v == 1;
}

std::uint32_t BodyReader::count(const char* field, std::size_t max, std::size_t min_bytes_each) {
  const std::uint32_t n = r_.u32(field);
  if (n > max) fail(fmt::format("{}: {} entries, at most {} allowed", field, n, max));
  if (static_cast<std::size_t>(n) * min_bytes_each > r_.remaining())
    fail(fmt::format("{}: {} entries cannot fit in the {} bytes left", field, n, r_.remaining()));
  return n;
}

std::string BodyReader::name(const char* field, bool may_be_empty) {
  std::string s = text(field, kMaxAgentNameLength);
  if (!(may_be_empty && s.empty()) && !is_valid_agent_name(s))
    fail(fmt::format("{} '{}' is not a valid agent name", field, s));
  return s;
}

std::string BodyReader::text(const char* field, std::size_t max) {
  const std::uint32_t n = r_.u32(field);
  if (n > max) fail(fmt::format("{}: {} bytes, at most {} allowed", field, n, max));
  const auto s = r_.take(n, field);
  return {reinterpret_cast<const char*>(s.data()), s.size()};
}

Pose2 BodyReader::pose(const char* field) {
  const double x = r_.f64(field), y = r_.f64(field), theta = r_.f64(field);
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(theta)) fail(fmt::format("{} is not finite", field));
  if (std::abs(x) > limits_.max_coordinate || std::abs(y) > limits_.max_coordinate)
    fail(fmt::format("{} ({}, {}) lies more than {} m from its frame's origin", field, x, y, limits_.max_coordinate));
  return {x, y, theta};
}

std::vector<ScanPoint> BodyReader::points(const char* field) {
  const std::uint32_t n = count(field, limits_.max_points, 12);
  std::vector<ScanPoint> out(n);
  for (ScanPoint& p : out) {
    p.x = r_.f32(field);
    p.y = r_.f32(field);
    p.weight = r_.f32(field);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.weight) || p.weight < 0.0f)
      fail(fmt::format("{}: a point is not finite or has a negative weight", field));
    if (std::abs(p.x) > limits_.max_point_distance || std::abs(p.y) > limits_.max_point_distance)
      fail(fmt::format("{}: a point ({}, {}) lies more than {} m from the robot", field, p.x, p.y,
                       limits_.max_point_distance));
  }
  return out;
}

PoseHypothesis BodyReader::hypothesis() {
  PoseHypothesis h;
  h.pose = pose("placement pose");
  h.score = in_range("score", 0.0, 1.0);
  h.surroundings_score = in_range("surroundings score", -1.0, 1.0);
  h.inlier_ratio = in_range("inlier ratio", 0.0, 1.0);
  h.known_fraction = in_range("known fraction", 0.0, 1.0);
  h.same_side_ratio = in_range("same-side ratio", 0.0, 1.0);
  return h;
}

}  // namespace dsswarm::protocol::wire_detail
