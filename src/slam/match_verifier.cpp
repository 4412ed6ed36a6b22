#include "slam/match_verifier.hpp"

#include <algorithm>

#include "common/errors.hpp"

namespace dsswarm {

void VerifyConfig::validate() const {
  auto unit = [](double v) { return v >= 0.0 && v <= 1.0; };
  if (!unit(min_known) || !unit(min_inliers) || !unit(relative))
    throw ConfigError("slam.verify_min_known, verify_min_inliers and verify_relative must be in [0, 1]");
  if (max_consecutive < 0) throw ConfigError("slam.verify_max_consecutive must be >= 0");
  if (!(average_weight > 0.0 && average_weight <= 1.0))
    throw ConfigError("slam.verify_average_weight must be in (0, 1]");
}

bool MatchVerifier::rejects(const MatchQuality& q) const {
  const double bar = std::max(config_.min_inliers, config_.relative * inlier_average_);
  return consecutive_rejections_ < config_.max_consecutive && q.known_fraction >= config_.min_known &&
         q.inlier_ratio < bar;
}

void MatchVerifier::note_accepted(const MatchQuality& q, bool first) {
  consecutive_rejections_ = 0;
  if (q.known_fraction >= config_.min_known)
    inlier_average_ = first ? q.inlier_ratio
                             : (1.0 - config_.average_weight) * inlier_average_ + config_.average_weight * q.inlier_ratio;
}

}  // namespace dsswarm
