#pragma once
// Is a match to be trusted? A failure shows as a sudden drop of the inlier
// ratio (match_quality) below what recent matches achieved; an absolute bar
// would reject whole regions whose map is merely fuzzy (walls first seen from
// far away). After a few rejections in a row the map, not the match, is
// likely what changed: accept again rather than drift on odometry forever.
#include "matching/scan_scorer.hpp"

namespace dsswarm {

struct VerifyConfig {
  // A match is rejected when at least `min_known` of its points land on known
  // cells and its inlier ratio is below max(min_inliers, relative × the
  // running average of accepted matches); never more than `max_consecutive`
  // in a row.
  double min_known = 0.3;
  double min_inliers = 0.3;
  double relative = 0.75;
  int max_consecutive = 10;
  // Weight of each accepted match in the running average (exponential).
  double average_weight = 0.1;

  void validate() const;  // throws ConfigError naming the field
};

class MatchVerifier {
 public:
  explicit MatchVerifier(const VerifyConfig& config) : config_(config) {}

  bool rejects(const MatchQuality& q) const;
  void note_rejected() { ++consecutive_rejections_; }
  // `first`: the robot's first accepted match, which starts the running average.
  void note_accepted(const MatchQuality& q, bool first);

 private:
  VerifyConfig config_;
  int consecutive_rejections_ = 0;
  double inlier_average_ = 0.0;  // running average inlier ratio of accepted matches
};

}  // namespace dsswarm
