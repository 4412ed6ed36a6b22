#pragma once
// Nearest-timestamp lookup into a trajectory that need not be sorted by time
// (intel's timestamps run backwards in places; file order is kept).
#include <cstddef>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "io/trajectory/tum.hpp"

namespace dsswarm {

class TimestampIndex {
 public:
  // Throws InputError if a timestamp or pose of `trajectory` is not finite
  // (`what` names the trajectory in the message, e.g. "estimate").
  TimestampIndex(const Trajectory& trajectory, std::string_view what);

  // Index into the trajectory of the entry whose timestamp is nearest to `t`,
  // if it lies within `max_time_diff`. Near-duplicate timestamps are fine: the
  // nearest wins; an exact tie goes to the earlier timestamp, and among equal
  // timestamps to the entry earlier in file order.
  std::optional<std::size_t> nearest(double t, double max_time_diff) const;

  bool empty() const { return sorted_.empty(); }
  double earliest() const { return sorted_.front().first; }  // requires !empty()
  double latest() const { return sorted_.back().first; }     // requires !empty()

 private:
  std::vector<std::pair<double, std::size_t>> sorted_;  // (timestamp, index), by time then index
};

// Throws ConfigError unless `max_time_diff` is finite and >= 0.
void require_valid_max_time_diff(double max_time_diff);

}  // namespace dsswarm
