#include "slam/recovery.hpp"

namespace dsswarm {

MatcherConfig Recovery::wide(const MatcherConfig& normal) {
  MatcherConfig c = normal;
  c.evaluations = normal.evaluations * 4;
  c.sigma_xy = normal.sigma_xy * 3;
  c.sigma_theta = normal.sigma_theta * 4;
  c.patience = normal.patience * 2;
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
