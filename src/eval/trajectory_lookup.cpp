#include "eval/trajectory_lookup.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "common/errors.hpp"

namespace dsswarm {

TimestampIndex::TimestampIndex(const Trajectory& trajectory, std::string_view what) {
  sorted_.reserve(trajectory.size());
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    const StampedPose& s = trajectory[i];
    if (!std::isfinite(s.timestamp) || !std::isfinite(s.pose.x) || !std::isfinite(s.pose.y) ||
        !std::isfinite(s.pose.theta)) {
      throw InputError(fmt::format("{} trajectory: entry {} (timestamp {}) is not finite", what, i, s.timestamp));
    }
    sorted_.emplace_back(s.timestamp, i);
  }
  std::sort(sorted_.begin(), sorted_.end());
}

std::optional<std::size_t> TimestampIndex::nearest(double t, double max_time_diff) const {
  if (sorted_.empty() || !std::isfinite(t)) return std::nullopt;
  // First entry at or after t; the nearest is it or the one just before it.
  const auto after = std::lower_bound(sorted_.begin(), sorted_.end(), t,
                                      [](const auto& entry, double value) { return entry.first < value; });
  auto best = sorted_.end();
  if (after != sorted_.end()) best = after;
  if (after != sorted_.begin()) {
    const auto before = std::prev(after);
    // Walk back over equal timestamps so ties resolve to the earliest file position.
    auto first_equal = before;
    while (first_equal != sorted_.begin() && std::prev(first_equal)->first == before->first) --first_equal;
    if (best == sorted_.end() || t - before->first <= best->first - t) best = first_equal;
  }
  if (std::abs(best->first - t) > max_time_diff) return std::nullopt;
  return best->second;
}

void require_valid_max_time_diff(double max_time_diff) {
  if (!std::isfinite(max_time_diff) || max_time_diff < 0.0) {
    throw ConfigError(fmt::format("max_time_diff must be a finite number >= 0 (seconds), got {}", max_time_diff));
  }
}

}  // namespace dsswarm
