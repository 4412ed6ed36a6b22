#pragma once
// Is local SLAM stuck while the robot drives? A young map holds only what the
// first scans saw from where they were taken: a sparse, grazing view of the
// side walls that fits the next scans best at that same viewpoint. Scan after
// scan the match then pulls a moving robot back to where the map began, and
// every scan it inserts there makes the pull stronger (a simulated robot
// "stood" for 3.8 m of a corridor whose end was in sight, so the degeneracy
// check did not apply). The guard compares, over the last stretch of
// odometry travel, how far the matches moved the robot along the odometry's
// direction: when they cover too little of it, the position along that
// direction follows the odometry, as the degeneracy check holds it along a
// corridor, until the matches keep up again. When it steps in, the robot is
// also moved on by what the window's matches fell short (catch_up), so the
// stall leaves no lasting offset behind the first scans.
#include <cstddef>
#include <deque>

#include <Eigen/Core>

#include "geometry/pose2.hpp"

namespace dsswarm {

struct StallConfig {
  double window = 0.2;         // m of odometry travel judged together (0: never)
  double min_progress = 0.25;  // share of that travel the matches must cover too
  double min_step = 0.001;     // m: odometry steps shorter than this say nothing (turning in place)
  // Only while the map is young: over the robot's first this many metres of
  // odometry travel (0: always). Later the map holds many viewpoints, and
  // real odometry that disagrees with the matches is usually the odometry's fault.
  double young_travel = 5.0;
  bool catch_up = true;  // on stepping in, also make up what the matches fell short since the last time

  void validate() const;  // throws ConfigError naming the field
};

class StallGuard {
 public:
  explicit StallGuard(const StallConfig& config) : config_(config) {}

  // A match from a trusted odometry prediction: `last` is the previous scan's
  // pose, `prior` the odometry's prediction, `raw` the match as found and
  // `matched` as it stands after the other checks. Returns `matched`, or it
  // with its position along the odometry's motion put back to the prior's
  // when the raw matches have stalled.
  Pose2 check(const Pose2& last, const Pose2& prior, const Pose2& raw, const Pose2& matched);
  // A scan whose prediction was not trusted: the history no longer compares like with like.
  void reset();
  // How many matches check() has put back to the odometry so far.
  std::size_t holds() const { return holds_; }

 private:
  struct Step {
    double travel, progress;
    Eigen::Vector2d behind;  // map frame: how far this step's match fell short, not yet made up
  };
  StallConfig config_;
  std::deque<Step> steps_;
  double travel_ = 0.0, progress_ = 0.0;
  Eigen::Vector2d behind_ = Eigen::Vector2d::Zero();  // sum over steps_
  double total_travel_ = 0.0;  // since the first scan, never reset
  std::size_t holds_ = 0;
};

}  // namespace dsswarm
