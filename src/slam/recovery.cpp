#include "slam/recovery.hpp"

#include "common/errors.hpp"

namespace dsswarm {

void RecoveryConfig::validate() const {
  if (evaluations_factor < 1 || patience_factor < 1)
    throw ConfigError("slam.recovery_evaluations_factor and recovery_patience_factor must be >= 1");
  if (!(sigma_xy_factor > 0.0) || !(sigma_theta_factor > 0.0))
    throw ConfigError("slam.recovery_sigma_xy_factor and recovery_sigma_theta_factor must be > 0");
}

MatcherConfig Recovery::wide(const MatcherConfig& normal, const RecoveryConfig& config) {
  MatcherConfig c = normal;
  c.evaluations = normal.evaluations * config.evaluations_factor;
  c.sigma_xy = normal.sigma_xy * config.sigma_xy_factor;
  c.sigma_theta = normal.sigma_theta * config.sigma_theta_factor;
  c.patience = normal.patience * config.patience_factor;
  // The rare hard case: every point scores (merging trades precision for speed).
  c.fine_merge_cells = 0.0;
  c.coarse_merge_cells = 0.0;
  return c;
}

MatchResult Recovery::search(const MultiResMap& map, const std::vector<ScanPoint>& points,
                             const std::vector<Pose2>& priors) {
  ++searches_;
  return matcher_.match(map, points, priors);
}

}  // namespace dsswarm
