#include "slam/wall_alignment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/errors.hpp"
#include "common/rng.hpp"

namespace dsswarm {
namespace {

constexpr double kPi = std::numbers::pi;

// `count` normals of walls whose normals lie at `angle` or at right angles to
// it (either sign), each off by Gaussian noise of `noise` rad.
std::vector<Eigen::Vector2d> wall_normals(double angle, int count, double noise, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Eigen::Vector2d> normals;
  for (int i = 0; i < count; ++i) {
    const double a = angle + (i % 4) * kPi / 2.0 + rng.normal(0.0, noise);
    normals.emplace_back(std::cos(a), std::sin(a));
  }
  return normals;
}

TEST(WallAlignment, FindsTheWallsAxisModuloARightAngle) {
  for (const double angle : {0.3, -0.6, 1.2, 0.0}) {
    const std::optional<double> axis = wall_axis(wall_normals(angle, 400, 0.03, 7), WallAlignConfig{});
    ASSERT_TRUE(axis) << angle;
    // 1.2 rad is -0.37 rad modulo 90°.
    const double expected = std::remainder(angle, kPi / 2.0);
    EXPECT_NEAR(*axis, expected, 0.005) << angle;
  }
}

TEST(WallAlignment, WallsAtOtherAnglesDoNotBiasTheAxis) {
  std::vector<Eigen::Vector2d> normals = wall_normals(0.1, 300, 0.02, 3);
  // Enough to pull the mean of the angles taken four times by a degree.
  const std::vector<Eigen::Vector2d> slanted = wall_normals(0.1 + kPi / 8.0, 25, 0.02, 4);
  normals.insert(normals.end(), slanted.begin(), slanted.end());
  const std::optional<double> axis = wall_axis(normals, WallAlignConfig{});
  ASSERT_TRUE(axis);
  EXPECT_NEAR(*axis, 0.1, 0.003);
}

TEST(WallAlignment, NoAxisWithoutAgreementEnoughNormalsOrWhenOff) {
  Rng rng(5);
  std::vector<Eigen::Vector2d> scattered;
  for (int i = 0; i < 400; ++i) {
    const double a = rng.uniform(-kPi, kPi);
    scattered.emplace_back(std::cos(a), std::sin(a));
  }
  EXPECT_FALSE(wall_axis(scattered, WallAlignConfig{}));
  EXPECT_FALSE(wall_axis(wall_normals(0.2, 30, 0.02, 1), WallAlignConfig{}));  // under min_normals
  WallAlignConfig off;
  off.enabled = false;
  EXPECT_FALSE(wall_axis(wall_normals(0.2, 400, 0.02, 1), off));
}

TEST(WallAlignment, TheStartTurnsByTheLeastAngleThatPutsTheWallsOnTheAxes) {
  const Pose2 start(1.0, -2.0, 0.5);
  for (const double axis : {0.3, -0.7, 0.0, 0.785}) {
    const Pose2 turned = turned_to_walls(start, axis);
    EXPECT_DOUBLE_EQ(turned.x, 1.0);
    EXPECT_DOUBLE_EQ(turned.y, -2.0);
    EXPECT_LE(std::abs(normalize_angle(turned.theta - start.theta)), kPi / 4.0 + 1e-9) << axis;
    // The walls' normals, seen in the map: on an axis.
    EXPECT_NEAR(std::remainder(axis + turned.theta, kPi / 2.0), 0.0, 1e-9) << axis;
  }
}

TEST(WallAlignment, ABadConfigNamesTheField) {
  WallAlignConfig config;
  config.min_consistency = 1.5;
  try {
    config.validate();
    FAIL() << "accepted a consistency above 1";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("slam.align_min_consistency"), std::string::npos) << e.what();
  }
  config = WallAlignConfig{};
  config.inlier_angle = 0.0;
  EXPECT_THROW(config.validate(), ConfigError);
  config = WallAlignConfig{};
  config.min_normals = 1;
  EXPECT_THROW(config.validate(), ConfigError);
}

}  // namespace
}  // namespace dsswarm
