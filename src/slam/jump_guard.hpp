#pragma once
// Does a match leap sideways from a trusted prediction for almost nothing?
// On 5 cm cells a wall's evidence can fit about as well two cells over (the
// simulated swarm: one scan per run slid 0.1 m across a corridor for a score
// 0.02–0.05 better, and the robot stayed there, off its own map). Where
// odometry is good, such a leap is many times the corrections matches usually
// make from it; where it is poor (the real logs) corrections are large anyway
// and the guard, scaled by them, stays out of the way. A leap that is not
// much better than the prediction is held at the prediction, unless the
// next scans keep asking for it (then it is drift the odometry missed).
#include <cstddef>
#include <deque>
#include <vector>

#include "geometry/pose2.hpp"

namespace dsswarm {

struct JumpConfig {
  double factor = 10.0;        // a leap: this many times the recent corrections' `percentile`, or more
  double percentile = 0.9;     // of the recent corrections: the typical one, with a few large ones allowed
  double min_distance = 0.06;  // m: never a leap below this (a cell and a bit)
  double min_gain = 0.08;      // a leap scoring this much better than the prediction is believed
  int history = 200;           // recent corrections kept (trusted predictions only)
  int min_history = 50;        // no judgement before this many
  int confirm = 3;             // consecutive scans asking for a leap: believed (0: the guard is off)

  void validate() const;  // throws ConfigError naming the field
};

class JumpGuard {
 public:
  explicit JumpGuard(const JumpConfig& config) : config_(config) {}

  // A match from a trusted prediction `prior`; `gain` is its score less the
  // prior's. Returns true when the match is a leap to be held at the prior.
  bool holds_at_prior(const Pose2& prior, const Pose2& matched, double gain);
  // A scan whose prediction was not trusted: a run of leaps is broken.
  void reset() { asked_ = 0; }
  std::size_t holds() const { return holds_; }

 private:
  double typical() const;  // the recent corrections' percentile

  JumpConfig config_;
  std::deque<double> corrections_;
  mutable std::vector<double> scratch_;
  int asked_ = 0;  // consecutive leaps asked for
  std::size_t holds_ = 0;
};

}  // namespace dsswarm
