#include "geometry/pose2.hpp"

#include <gtest/gtest.h>

namespace dsswarm {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_pose_near(const Pose2& a, const Pose2& b, double tol = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(normalize_angle(a.theta - b.theta), 0.0, tol);
}

TEST(NormalizeAngle, WrapsIntoHalfOpenInterval) {
  EXPECT_NEAR(normalize_angle(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(normalize_angle(-kPi), kPi, 1e-12);
  EXPECT_NEAR(normalize_angle(2 * kPi + 0.5), 0.5, 1e-12);
  EXPECT_NEAR(normalize_angle(-2 * kPi - 0.5), -0.5, 1e-12);
  EXPECT_NEAR(normalize_angle(0.0), 0.0, 1e-15);
}

TEST(Pose2, ComposeMatchesHandComputedValue) {
  const Pose2 a(1.0, 2.0, kPi / 2);
  const Pose2 b(1.0, 0.0, kPi / 2);
  // b's x axis is a's y axis: one metre forward from a facing +y lands at (1, 3).
  expect_pose_near(a * b, Pose2(1.0, 3.0, kPi));
}

TEST(Pose2, InverseComposesToIdentity) {
  const Pose2 a(-3.2, 0.7, 2.9);
  expect_pose_near(a * a.inverse(), Pose2());
  expect_pose_near(a.inverse() * a, Pose2());
}

TEST(Pose2, CompositionIsAssociative) {
  const Pose2 a(1, 2, 0.3), b(-0.5, 4, -2.0), c(3, -1, 3.0);
  expect_pose_near((a * b) * c, a * (b * c));
}

TEST(Pose2, TransformsPoints) {
  const Pose2 a(1.0, 1.0, kPi / 2);
  const Eigen::Vector2d p = a * Eigen::Vector2d(2.0, 0.0);
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
}

TEST(Pose2, BetweenRecoversRelativeMotion) {
  const Pose2 a(2, -1, 1.0), delta(0.3, 0.1, -0.2);
  expect_pose_near(between(a, a * delta), delta);
}

TEST(Pose2, InterpolateTakesShortestArc) {
  const Pose2 a(0, 0, kPi - 0.1), b(2, 4, -kPi + 0.1);
  const Pose2 mid = interpolate(a, b, 0.5);
  EXPECT_NEAR(mid.x, 1.0, 1e-12);
  EXPECT_NEAR(mid.y, 2.0, 1e-12);
  EXPECT_NEAR(std::abs(mid.theta), kPi, 1e-12);
  expect_pose_near(interpolate(a, b, 0.0), a);
  expect_pose_near(interpolate(a, b, 1.0), b);
}

}  // namespace
}  // namespace dsswarm
