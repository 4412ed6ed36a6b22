#include "slam/degeneracy.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dsswarm {
namespace {

std::vector<ScanPoint> wall_points(double y, double x0, double x1, double step) {
  std::vector<ScanPoint> out;
  for (double x = x0; x <= x1; x += step) out.push_back({static_cast<float>(x), static_cast<float>(y), 1.0f});
  return out;
}

TEST(Degeneracy, TwoParallelWallsLeaveTheDirectionAlongThem) {
  std::vector<ScanPoint> points = wall_points(-1.5, 0.0, 10.0, 0.05);
  const std::vector<ScanPoint> left = wall_points(1.5, 0.0, 10.0, 0.05);
  points.insert(points.end(), left.rbegin(), left.rend());  // a scan runs right to left
  const std::optional<Eigen::Vector2d> weak = weak_direction(points, {});
  ASSERT_TRUE(weak.has_value());
  EXPECT_NEAR(std::abs(weak->x()), 1.0, 1e-9);
  EXPECT_NEAR(weak->y(), 0.0, 1e-9);
}

TEST(Degeneracy, ACornerPinsBothDirections) {
  std::vector<ScanPoint> points = wall_points(-1.5, 0.0, 3.0, 0.05);
  for (double y = -1.5; y <= 1.5; y += 0.05) points.push_back({3.0f, static_cast<float>(y), 1.0f});
  EXPECT_FALSE(weak_direction(points, {}).has_value());
}

TEST(Degeneracy, OffOrTooFewNormalsJudgesNothing) {
  const std::vector<ScanPoint> points = wall_points(-1.5, 0.0, 10.0, 0.05);
  DegeneracyConfig off;
  off.min_ratio = 0.0;
  EXPECT_FALSE(weak_direction(points, off).has_value());
  // Points further apart than normal_radius form no surface.
  EXPECT_FALSE(weak_direction(wall_points(-1.5, 0.0, 10.0, 0.5), {}).has_value());
  EXPECT_THROW(DegeneracyConfig{.min_ratio = 1.0}.validate(), std::exception);
}

TEST(Degeneracy, HoldingKeepsThePriorAlongTheWeakDirectionOnly) {
  const Pose2 prior(2.0, 1.0, std::numbers::pi / 2);  // facing +y: the base x axis is the world's y
  const Pose2 matched = prior * Pose2(-0.06, 0.02, 0.01);
  const Pose2 held = hold_along(prior, matched, Eigen::Vector2d(1.0, 0.0));
  const Pose2 d = prior.inverse() * held;
  EXPECT_NEAR(d.x, 0.0, 1e-12);
  EXPECT_NEAR(d.y, 0.02, 1e-12);
  EXPECT_NEAR(d.theta, 0.01, 1e-12);
}

}  // namespace
}  // namespace dsswarm
