#include "eval/ate.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <fmt/format.h>

#include "common/median.hpp"

#include "common/errors.hpp"
#include "eval/trajectory_lookup.hpp"

namespace dsswarm {

namespace {

std::string span_of(const TimestampIndex& index) {
  return index.empty() ? std::string("empty") : fmt::format("[{:.6f}, {:.6f}]", index.earliest(), index.latest());
}

}  // namespace

// In 2D the rotation has a closed form: with centred points a_i, b_i the
// objective is maximised at θ = atan2(Σ a_i×b_i, Σ a_i·b_i), which never
// yields a reflection and needs no SVD.
Pose2 fit_rigid_transform(const Eigen::Matrix2Xd& from, const Eigen::Matrix2Xd& to) {
  const Eigen::Vector2d from_centroid = from.rowwise().mean();
  const Eigen::Vector2d to_centroid = to.rowwise().mean();
  const Eigen::Matrix2d cross =
      (from.colwise() - from_centroid) * (to.colwise() - to_centroid).transpose();  // Σ a_i b_iᵀ
  const double theta = std::atan2(cross(0, 1) - cross(1, 0), cross(0, 0) + cross(1, 1));
  const Pose2 rotation(0.0, 0.0, theta);
  const Eigen::Vector2d t = to_centroid - (rotation * from_centroid);
  return {t.x(), t.y(), theta};
}

AteResult evaluate_ate(const Trajectory& estimate, const Trajectory& ground_truth, double max_time_diff) {
  require_valid_max_time_diff(max_time_diff);
  const TimestampIndex truth_index(ground_truth, "ground-truth");
  const TimestampIndex estimate_index(estimate, "estimated");  // validates the estimate; gives its span

  std::vector<std::pair<std::size_t, std::size_t>> pairs;  // (estimate index, ground-truth index)
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    if (const auto j = truth_index.nearest(estimate[i].timestamp, max_time_diff)) pairs.emplace_back(i, *j);
  }
  if (pairs.size() < 2) {
    throw InputError(fmt::format(
        "ATE needs at least 2 estimated poses with a ground-truth pose within {} s, found {} "
        "(estimate: {} poses spanning {}; ground truth: {} poses spanning {})",
        max_time_diff, pairs.size(), estimate.size(), span_of(estimate_index), ground_truth.size(),
        span_of(truth_index)));
  }

  const auto n = static_cast<Eigen::Index>(pairs.size());
  Eigen::Matrix2Xd from(2, n), to(2, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto [i, j] = pairs[static_cast<std::size_t>(k)];
    from.col(k) = estimate[i].pose.translation();
    to.col(k) = ground_truth[j].pose.translation();
  }

  AteResult result;
  result.matched = pairs.size();
  result.alignment = fit_rigid_transform(from, to);
  std::vector<double> errors(pairs.size());
  double sum = 0.0, sum_sq = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double e = (result.alignment * Eigen::Vector2d(from.col(k)) - to.col(k)).norm();
    errors[static_cast<std::size_t>(k)] = e;
    sum += e;
    sum_sq += e * e;
    result.max = std::max(result.max, e);
  }
  const double count = static_cast<double>(errors.size());
  result.mean = sum / count;
  result.rmse = std::sqrt(sum_sq / count);
  result.median = median_in_place(errors);
  return result;
}

}  // namespace dsswarm
