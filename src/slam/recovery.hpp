#pragma once
// A wider, costlier search for scans whose normal match fails verification,
// and for the first scan in a given map, where only a rough start is known.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "matching/monte_carlo_matcher.hpp"

namespace dsswarm {

// How much wider and costlier than the normal match (MatcherConfig) the
// search is; it scores every point (merging trades precision for speed).
struct RecoveryConfig {
  int evaluations_factor = 4;
  double sigma_xy_factor = 3.0;
  double sigma_theta_factor = 4.0;
  int patience_factor = 2;

  void validate() const;  // throws ConfigError naming the field
};

class Recovery {
 public:
  Recovery(const MatcherConfig& normal, const RecoveryConfig& config, std::uint64_t seed)
      : matcher_(wide(normal, config), seed) {}

  // Searches from every prediction in `priors`; counts one recovery search.
  MatchResult search(const MultiResMap& map, const std::vector<ScanPoint>& points, const std::vector<Pose2>& priors);
  // The wide search from one start, not counted as a recovery.
  MatchResult locate(const MultiResMap& map, const std::vector<ScanPoint>& points, const Pose2& start) {
    return matcher_.match(map, points, start);
  }
  std::size_t searches() const { return searches_; }

 private:
  static MatcherConfig wide(const MatcherConfig& normal, const RecoveryConfig& config);

  MonteCarloMatcher matcher_;
  std::size_t searches_ = 0;
};

}  // namespace dsswarm
