#pragma once
// Absolute trajectory error (Sturm et al. 2012, TUM RGB-D benchmark), planar:
// poses are associated by timestamp, the estimate is rigidly aligned to the
// ground truth in the least-squares sense (no scale), and the remaining
// position differences are summarised.
#include <cstddef>

#include <Eigen/Core>

#include "geometry/pose2.hpp"
#include "io/trajectory/tum.hpp"

namespace dsswarm {

struct AteResult {
  double rmse = 0.0;    // metres
  double mean = 0.0;    // metres
  double median = 0.0;  // metres
  double max = 0.0;     // metres
  std::size_t matched = 0;  // estimate poses with a ground-truth pose within max_time_diff
  Pose2 alignment;          // maps estimate coordinates into ground-truth coordinates
};

// Least-squares rigid transform T (no scale) minimising Σ‖T·from_i − to_i‖²
// (Horn / Umeyama); the columns of `from` and `to` are paired points.
Pose2 fit_rigid_transform(const Eigen::Matrix2Xd& from, const Eigen::Matrix2Xd& to);

// Each estimate pose is paired with the ground-truth pose nearest in time, if
// within `max_time_diff` seconds (neither trajectory needs to be sorted).
// Throws InputError if fewer than 2 poses pair up (the message gives both time
// spans), ConfigError for a negative/non-finite max_time_diff.
AteResult evaluate_ate(const Trajectory& estimate, const Trajectory& ground_truth, double max_time_diff = 0.01);

}  // namespace dsswarm
