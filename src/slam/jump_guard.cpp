#include "slam/jump_guard.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"

namespace dsswarm {

void JumpConfig::validate() const {
  if (!(factor > 0.0)) throw ConfigError("slam.jump_factor must be > 0");
  if (!(percentile >= 0.0 && percentile <= 1.0)) throw ConfigError("slam.jump_percentile must be in [0, 1]");
  if (!(min_distance >= 0.0)) throw ConfigError("slam.jump_min_distance must be >= 0");
  if (!(min_gain >= 0.0)) throw ConfigError("slam.jump_min_gain must be >= 0");
  if (history < 1) throw ConfigError("slam.jump_history must be >= 1");
  if (min_history < 1 || min_history > history) throw ConfigError("slam.jump_min_history must be in [1, jump_history]");
  if (confirm < 0) throw ConfigError("slam.jump_confirm must be >= 0");
}

double JumpGuard::typical() const {
  scratch_.assign(corrections_.begin(), corrections_.end());
  const auto k = static_cast<std::size_t>(config_.percentile * static_cast<double>(scratch_.size()));
  const auto nth = scratch_.begin() + static_cast<std::ptrdiff_t>(std::min(k, scratch_.size() - 1));
  std::nth_element(scratch_.begin(), nth, scratch_.end());
  return *nth;
}

bool JumpGuard::holds_at_prior(const Pose2& prior, const Pose2& matched, double gain) {
  if (config_.confirm == 0) return false;
  const double moved = std::hypot(matched.x - prior.x, matched.y - prior.y);
  const bool judged = corrections_.size() >= static_cast<std::size_t>(config_.min_history);
  // The percentile last: most matches are ruled out by distance alone, and it sorts the history.
  const bool leap = judged && moved > config_.min_distance && gain < config_.min_gain &&
                    moved > config_.factor * typical();
  if (!leap) {
    asked_ = 0;
    corrections_.push_back(moved);
    if (corrections_.size() > static_cast<std::size_t>(config_.history)) corrections_.pop_front();
    return false;
  }
  if (++asked_ >= config_.confirm) {
    asked_ = 0;  // believed: the robot is where the matches say
    return false;
  }
  ++holds_;
  return true;
}

}  // namespace dsswarm
