#include "slam/gap_reviser.hpp"

namespace dsswarm {

void GapReviser::note_dropped(std::size_t index, const Pose2& predicted, const Pose2& last_kept) {
  if (gap_.empty()) gap_start_ = last_kept;
  gap_.push_back({index, predicted});
}

std::vector<PoseRevision> GapReviser::revise(const Pose2& matched, const Pose2& prior) const {
  // Two estimates of each dropped pose, both pinned to the kept poses on
  // either side of the gap: the motion prediction blended from both ends
  // (forward from the pose before the gap, as predicted so far, and back from
  // this match through the same motion, match ⊕ prior⁻¹ ⊕ forward), and plain
  // interpolation between the two kept poses (the robot moves smoothly). The
  // revised pose is their midpoint. Measured on the filter-off trajectories
  // of the three logs (dropping the scans of 1-4 scan gaps after the fact):
  // odometry increments err 1-3.5 degrees per scan, so interpolation wins on
  // short gaps and the prediction on long ones; the midpoint was best or
  // within a millimetre of it everywhere. Fractions go by scan count, not
  // odometry travel: odometry that stalls and then jumps (mit-csail, intel)
  // would bunch the poses.
  const double n = static_cast<double>(gap_.size() + 1);
  std::vector<PoseRevision> revised;
  revised.reserve(gap_.size());
  for (std::size_t i = 0; i < gap_.size(); ++i) {
    const double t = static_cast<double>(i + 1) / n;
    const Pose2& forward = gap_[i].pose;
    const Pose2 backward = matched * between(prior, forward);
    const Pose2 predicted = interpolate(forward, backward, t);
    const Pose2 interpolated = interpolate(gap_start_, matched, t);
    revised.push_back({gap_[i].index, interpolate(predicted, interpolated, 0.5)});
  }
  return revised;
}

}  // namespace dsswarm
