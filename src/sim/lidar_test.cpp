#include "sim/lidar.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

constexpr double kHalfTurn = std::numbers::pi;

World wall_at_x5() { return World({Segment{{5, -100}, {5, 100}}}); }

LidarConfig noiseless() {
  LidarConfig c;
  c.noise_std = 0.0;
  return c;
}

TEST(Lidar, BeamGeometryFollowsConfig) {
  Rng rng(1);
  const LaserScan scan = simulate_scan(wall_at_x5(), Pose2(), noiseless(), rng);
  ASSERT_EQ(scan.ranges.size(), 361u);
  EXPECT_NEAR(scan.angle_min, -kHalfTurn / 2, 1e-12);
  EXPECT_NEAR(scan.beam_angle(360), kHalfTurn / 2, 1e-12);
  EXPECT_EQ(scan.range_max, 30.0);
  EXPECT_EQ(scan.range_min, 0.05);

  LidarConfig full = noiseless();
  full.fov = 2 * kHalfTurn;
  full.beams = 360;
  const LaserScan ring = simulate_scan(wall_at_x5(), Pose2(), full, rng);
  EXPECT_NEAR(ring.angle_increment, kHalfTurn / 180, 1e-12);  // no duplicate beam at +-pi
}

TEST(Lidar, NoiselessRangesAreExact) {
  Rng rng(1);
  const LaserScan scan = simulate_scan(wall_at_x5(), Pose2(), noiseless(), rng);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double a = scan.beam_angle(i);
    const double expected = 5.0 / std::cos(a);
    if (std::cos(a) > 0 && expected < 30.0) {
      EXPECT_NEAR(scan.ranges[i], expected, 1e-5) << "beam " << i;
    } else {
      EXPECT_EQ(scan.ranges[i], 30.0f) << "beam " << i;  // no return reads exactly range_max
      EXPECT_FALSE(scan.is_valid(scan.ranges[i]));
    }
  }
}

TEST(Lidar, LaserPoseIsApplied) {
  Rng rng(1);
  // Laser at (8, 1) looking back at the wall (-x): the centre beam reads 3 m.
  const LaserScan scan = simulate_scan(wall_at_x5(), Pose2(8, 1, kHalfTurn), noiseless(), rng);
  EXPECT_NEAR(scan.ranges[180], 3.0, 1e-6);
  // Beam 0 (angle -pi/2 in the laser frame) points to world +y: no hit.
  EXPECT_EQ(scan.ranges[0], 30.0f);
}

TEST(Lidar, NoHitBeamsReadRangeMaxEvenWithNoise) {
  Rng rng(2);
  LidarConfig config;
  config.noise_std = 0.5;
  const LaserScan scan = simulate_scan(World({}), Pose2(), config, rng);  // empty world
  for (float r : scan.ranges) EXPECT_EQ(r, 30.0f);
  EXPECT_EQ(scan.valid_count(), 0u);
}

TEST(Lidar, NoiseHasTheConfiguredSpread) {
  LidarConfig config;
  config.noise_std = 0.05;
  config.beams = 101;
  config.fov = 0.2;  // all beams close to 5 m
  Rng rng(3);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int k = 0; k < 100; ++k) {
    const LaserScan scan = simulate_scan(wall_at_x5(), Pose2(), config, rng);
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      const double error = scan.ranges[i] - 5.0 / std::cos(scan.beam_angle(i));
      sum += error;
      sum2 += error * error;
      ++n;
    }
  }
  const double mean = sum / n, stddev = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.003);
  EXPECT_NEAR(stddev, 0.05, 0.003);
}

TEST(Lidar, DropoutGivesMaxRangeAtTheConfiguredRate) {
  LidarConfig config = noiseless();
  config.max_range_dropout = 0.3;
  config.fov = 1.0;  // every beam would hit the wall
  Rng rng(4);
  int dropped = 0, total = 0;
  for (int k = 0; k < 50; ++k) {
    const LaserScan scan = simulate_scan(wall_at_x5(), Pose2(), config, rng);
    for (float r : scan.ranges) {
      dropped += r == 30.0f ? 1 : 0;
      ++total;
    }
  }
  EXPECT_NEAR(static_cast<double>(dropped) / total, 0.3, 0.02);
}

TEST(Lidar, SameSeedSameScan) {
  const World world = generate_world({});
  const Pose2 pose(5, 10, 0.3);
  Rng a(9), b(9), c(10);
  const LidarConfig config;
  const auto first = simulate_scan(world, pose, config, a).ranges;
  EXPECT_EQ(first, simulate_scan(world, pose, config, b).ranges);
  EXPECT_NE(first, simulate_scan(world, pose, config, c).ranges);
}

TEST(Lidar, RejectsBadConfig) {
  Rng rng(1);
  auto scan_with = [&](auto change) {
    LidarConfig c;
    change(c);
    return simulate_scan(wall_at_x5(), Pose2(), c, rng);
  };
  EXPECT_THROW(scan_with([](LidarConfig& c) { c.beams = 1; }), ConfigError);
  EXPECT_THROW(scan_with([](LidarConfig& c) { c.fov = 7.0; }), ConfigError);
  EXPECT_THROW(scan_with([](LidarConfig& c) { c.range_max = 0.01; }), ConfigError);
  EXPECT_THROW(scan_with([](LidarConfig& c) { c.noise_std = -1; }), ConfigError);
  EXPECT_THROW(scan_with([](LidarConfig& c) { c.max_range_dropout = 1.5; }), ConfigError);
  EXPECT_THROW(scan_with([](LidarConfig& c) { c.rate_hz = 0; }), ConfigError);
}

}  // namespace
}  // namespace dsswarm
