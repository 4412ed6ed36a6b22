#pragma once
// Odometry poses ordered by time, looked up by interpolation.
#include <optional>
#include <vector>

#include "geometry/pose2.hpp"

namespace dsswarm {

struct OdometrySample {
  double stamp = 0.0;
  Pose2 pose;
};

class OdometryTrack {
 public:
  // `poses` must be sorted by non-decreasing stamp.
  explicit OdometryTrack(std::vector<OdometrySample> poses);

  bool empty() const { return poses_.empty(); }
  double first_stamp() const { return poses_.front().stamp; }
  double last_stamp() const { return poses_.back().stamp; }

  // The pose at time t: linear in x, y and shortest-arc in theta between the
  // bracketing poses; the end pose for t up to `max_extrapolation` seconds
  // outside the track; nullopt farther out (or when the track is empty).
  std::optional<Pose2> at(double t, double max_extrapolation) const;

 private:
  std::vector<OdometrySample> poses_;
};

}  // namespace dsswarm
