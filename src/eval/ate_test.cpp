#include "eval/ate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "common/errors.hpp"
#include "eval/metrics_json.hpp"

namespace dsswarm {
namespace {

Trajectory make_ate_truth(std::size_t n) {
  Trajectory t;
  Pose2 p(1.0, 2.0, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    t.push_back({100.0 + 0.2 * static_cast<double>(i), p});
    p = p * Pose2(0.4, 0.0, 0.2 * std::sin(0.15 * static_cast<double>(i)));
  }
  return t;
}

TEST(EvaluateAte, RigidlyMovedTrajectoryHasZeroErrorAndRecoversTransform) {
  const Trajectory truth = make_ate_truth(80);
  const Pose2 frame(-4.0, 7.5, 2.2);  // estimate frame -> truth frame
  Trajectory estimate = truth;
  for (auto& s : estimate) s.pose = frame.inverse() * s.pose;
  std::mt19937 rng(3);
  std::shuffle(estimate.begin(), estimate.end(), rng);  // association is by time, not order

  const AteResult r = evaluate_ate(estimate, truth);
  EXPECT_EQ(r.matched, truth.size());
  EXPECT_NEAR(r.rmse, 0.0, 1e-9);
  EXPECT_NEAR(r.max, 0.0, 1e-9);
  EXPECT_NEAR(r.alignment.x, frame.x, 1e-9);
  EXPECT_NEAR(r.alignment.y, frame.y, 1e-9);
  EXPECT_NEAR(normalize_angle(r.alignment.theta - frame.theta), 0.0, 1e-12);
}

TEST(EvaluateAte, RadialNoiseGivesExpectedRmse) {
  // Four points on a circle, each pushed radially in or out by eps. The
  // offsets sum to zero and exert no torque about the centroid, so the best
  // alignment is still the true one and every residual is exactly eps.
  const double eps = 0.05;
  const Trajectory truth = {{1, Pose2(1, 0, 0)}, {2, Pose2(0, 1, 0)}, {3, Pose2(-1, 0, 0)}, {4, Pose2(0, -1, 0)}};
  const double radial[] = {+eps, -eps, +eps, -eps};
  const Pose2 frame(10.0, -3.0, -1.0);
  Trajectory estimate;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const Pose2& p = truth[i].pose;
    const double scale = 1.0 + radial[i];
    estimate.push_back({truth[i].timestamp + 0.004, frame * Pose2(p.x * scale, p.y * scale, 0.0)});
  }
  const AteResult r = evaluate_ate(estimate, truth);
  EXPECT_EQ(r.matched, 4u);
  EXPECT_NEAR(r.rmse, eps, 1e-12);
  EXPECT_NEAR(r.mean, eps, 1e-12);
  EXPECT_NEAR(r.median, eps, 1e-12);
  EXPECT_NEAR(r.max, eps, 1e-12);
  const Pose2 expected_alignment = frame.inverse();
  EXPECT_NEAR(r.alignment.x, expected_alignment.x, 1e-12);
  EXPECT_NEAR(r.alignment.y, expected_alignment.y, 1e-12);
}

TEST(EvaluateAte, AlignmentIsLeastSquaresOptimal) {
  const Trajectory truth = make_ate_truth(50);
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.1);
  Trajectory estimate = truth;
  for (auto& s : estimate) s.pose = Pose2(3.0, 1.0, 0.7) * Pose2(s.pose.x + noise(rng), s.pose.y + noise(rng), 0.0);
  const AteResult r = evaluate_ate(estimate, truth);
  ASSERT_GT(r.rmse, 0.05);
  // Nudging the alignment in any direction must not lower the RMSE.
  const auto rmse_with = [&](const Pose2& alignment) {
    double sum_sq = 0.0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      sum_sq += (alignment * estimate[i].pose.translation() - truth[i].pose.translation()).squaredNorm();
    }
    return std::sqrt(sum_sq / static_cast<double>(truth.size()));
  };
  EXPECT_NEAR(rmse_with(r.alignment), r.rmse, 1e-12);
  for (const Pose2& nudge : {Pose2(1e-3, 0, 0), Pose2(-1e-3, 0, 0), Pose2(0, 1e-3, 0), Pose2(0, -1e-3, 0),
                             Pose2(0, 0, 1e-3), Pose2(0, 0, -1e-3)}) {
    EXPECT_GE(rmse_with(nudge * r.alignment), r.rmse);
  }
  EXPECT_LE(r.median, r.max);
  EXPECT_LE(r.mean, r.rmse);
}

TEST(EvaluateAte, MedianOfEvenCountAveragesMiddlePair) {
  // Residuals after the (identity) alignment: 0.1, 0.1, 0.3, 0.3 (symmetric
  // offsets along x of points on the x axis keep the centroid and rotation).
  const Trajectory truth = {{0, Pose2(-2, 0, 0)}, {1, Pose2(-1, 0, 0)}, {2, Pose2(1, 0, 0)}, {3, Pose2(2, 0, 0)}};
  const Trajectory estimate = {
      {0, Pose2(-2.3, 0, 0)}, {1, Pose2(-0.9, 0, 0)}, {2, Pose2(0.9, 0, 0)}, {3, Pose2(2.3, 0, 0)}};
  const AteResult r = evaluate_ate(estimate, truth);
  EXPECT_NEAR(r.median, 0.2, 1e-12);
  EXPECT_NEAR(r.max, 0.3, 1e-12);
  EXPECT_NEAR(r.mean, 0.2, 1e-12);
  EXPECT_NEAR(r.rmse, std::sqrt(0.05), 1e-12);
}

TEST(EvaluateAte, UnmatchedPosesAreSkipped) {
  const Trajectory truth = make_ate_truth(20);
  Trajectory estimate = truth;
  estimate[3].timestamp += 0.05;   // beyond the default 10 ms
  estimate[7].pose = Pose2(99, 99, 0);
  estimate[7].timestamp = 5000.0;  // far outside the ground truth
  const AteResult r = evaluate_ate(estimate, truth);
  EXPECT_EQ(r.matched, 18u);
  EXPECT_NEAR(r.rmse, 0.0, 1e-9);
}

TEST(EvaluateAte, TooFewMatchesIsAClearInputError) {
  const Trajectory truth = make_ate_truth(10);
  Trajectory estimate = truth;
  for (auto& s : estimate) s.timestamp -= 50.0;
  estimate[0].timestamp = truth[0].timestamp;  // a single match is not enough
  try {
    evaluate_ate(estimate, truth);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("at least 2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("found 1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("100.000000"), std::string::npos) << msg;  // ground-truth span start
  }
  EXPECT_THROW(evaluate_ate({}, truth), InputError);
  EXPECT_THROW(evaluate_ate(truth, truth, -1.0), ConfigError);
}

TEST(EvaluateAte, JsonHasExactlyTheDocumentedKeys) {
  AteResult r;
  r.rmse = 0.3;
  r.mean = 0.2;
  r.median = 0.1;
  r.max = 0.9;
  r.matched = 42;
  const nlohmann::json j = to_json(r);
  EXPECT_EQ(j.size(), 5u);
  EXPECT_EQ(j.at("ate_rmse").get<double>(), 0.3);
  EXPECT_EQ(j.at("ate_mean").get<double>(), 0.2);
  EXPECT_EQ(j.at("ate_median").get<double>(), 0.1);
  EXPECT_EQ(j.at("ate_max").get<double>(), 0.9);
  EXPECT_EQ(j.at("matched").get<std::size_t>(), 42u);
}

}  // namespace
}  // namespace dsswarm
