#include "eval/cross_frame.hpp"

#include <Eigen/Core>

#include "eval/ate.hpp"
#include "eval/trajectory_lookup.hpp"

namespace dsswarm {

std::optional<Pose2> fit_cross_frame(const Trajectory& x, const Trajectory& y, const std::vector<Relation>& relations,
                                     double max_time_diff) {
  require_valid_max_time_diff(max_time_diff);
  const TimestampIndex xi(x, "cross-frame X"), yi(y, "cross-frame Y");
  std::vector<Eigen::Vector2d> on_x, on_y;  // paired: the same point in X's frame and in Y's
  for (const Relation& r : relations) {
    const auto x1 = xi.nearest(r.t1, max_time_diff), y2 = yi.nearest(r.t2, max_time_diff);
    const auto y1 = yi.nearest(r.t1, max_time_diff), x2 = xi.nearest(r.t2, max_time_diff);
    if (x1 && y2) {
      on_x.push_back((x[*x1].pose * r.motion).translation());
      on_y.push_back(y[*y2].pose.translation());
    } else if (y1 && x2) {
      on_x.push_back(x[*x2].pose.translation());
      on_y.push_back((y[*y1].pose * r.motion).translation());
    }
  }
  if (on_x.size() < 2) return std::nullopt;
  const auto n = static_cast<Eigen::Index>(on_x.size());
  Eigen::Matrix2Xd from(2, n), to(2, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    from.col(k) = on_y[static_cast<std::size_t>(k)];
    to.col(k) = on_x[static_cast<std::size_t>(k)];
  }
  return fit_rigid_transform(from, to);
}

}  // namespace dsswarm
