#include "io/bag_common/odometry_track.hpp"

#include <algorithm>
#include <cassert>
#include <utility>

namespace dsswarm {

OdometryTrack::OdometryTrack(std::vector<OdometrySample> poses) : poses_(std::move(poses)) {
  assert(std::is_sorted(
      poses_.begin(), poses_.end(),
      [](const OdometrySample& a, const OdometrySample& b) { return a.stamp < b.stamp; }));
}

std::optional<Pose2> OdometryTrack::at(double t, double max_extrapolation) const {
  if (poses_.empty() || t < first_stamp() - max_extrapolation ||
      t > last_stamp() + max_extrapolation) {
    return std::nullopt;
  }
  const auto after =
      std::upper_bound(poses_.begin(), poses_.end(), t,
                       [](double time, const OdometrySample& p) { return time < p.stamp; });
  if (after == poses_.begin()) return poses_.front().pose;
  if (after == poses_.end()) return poses_.back().pose;
  const OdometrySample& a = *(after - 1);
  const OdometrySample& b = *after;
  // a.stamp <= t < b.stamp, so the span is positive.
  return interpolate(a.pose, b.pose, (t - a.stamp) / (b.stamp - a.stamp));
}

}  // namespace dsswarm
