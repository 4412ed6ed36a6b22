#include "sim/robot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

// One default run shared by the tests (simulating it takes a fraction of a second).
struct DefaultRun {
  World world = generate_world({});
  std::vector<Eigen::Vector2d> tour = world.waypoint_tour(7);
  RobotConfig robot;
  LidarConfig lidar;
  SimulatedRun run = simulate_run(world, tour, tour_start_pose(tour), robot, lidar, 11, 100.0);
};
const DefaultRun& default_run() {
  static const DefaultRun r;
  return r;
}

double path_length(const std::vector<std::pair<double, Pose2>>& truth, std::size_t upto) {
  double d = 0;
  for (std::size_t k = 1; k <= upto; ++k) d += (truth[k].second.translation() - truth[k - 1].second.translation()).norm();
  return d;
}

// Odometry error at scan k once the odometry frame is anchored at the first true pose.
Pose2 odometry_error(const SimulatedRun& run, std::size_t k) {
  const Pose2 anchored = run.ground_truth.front().second * *run.log.scans[k].odometry;
  return between(run.ground_truth[k].second, anchored);
}

TEST(Robot, RunIsConsistent) {
  const auto& r = default_run();
  const auto& scans = r.run.log.scans;
  ASSERT_GT(scans.size(), 100u);
  ASSERT_EQ(scans.size(), r.run.ground_truth.size());
  EXPECT_TRUE(r.run.log.warnings.empty());
  for (std::size_t k = 0; k < scans.size(); ++k) {
    EXPECT_DOUBLE_EQ(scans[k].timestamp, 100.0 + static_cast<double>(k) / r.lidar.rate_hz);
    EXPECT_EQ(r.run.ground_truth[k].first, scans[k].timestamp);
    ASSERT_TRUE(scans[k].odometry.has_value());
    EXPECT_EQ(scans[k].laser_offset.x, r.robot.laser_offset.x);
    EXPECT_EQ(scans[k].ranges.size(), 361u);
  }
  const Pose2 first = *scans.front().odometry;
  EXPECT_EQ(first.x, 0.0);
  EXPECT_EQ(first.y, 0.0);
  EXPECT_EQ(first.theta, 0.0);
  // Ends at the tour's last waypoint.
  EXPECT_LT((r.run.ground_truth.back().second.translation() - r.tour.back()).norm(), 0.05);
}

TEST(Robot, NeverComesCloseToWalls) {
  const auto& r = default_run();
  const auto& truth = r.run.ground_truth;
  double worst = 1e9, fastest = 0, fastest_turn = 0;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    worst = std::min(worst, r.world.clearance(truth[k].second.translation()));
    if (k == 0) continue;
    // Between scans too: the straight chord between consecutive poses.
    const Eigen::Vector2d a = truth[k - 1].second.translation(), b = truth[k].second.translation();
    worst = std::min(worst, r.world.clearance((a + b) / 2));
    fastest = std::max(fastest, (b - a).norm() * r.lidar.rate_hz);
    fastest_turn = std::max(fastest_turn, std::abs(normalize_angle(truth[k].second.theta - truth[k - 1].second.theta)) *
                                              r.lidar.rate_hz);
  }
  EXPECT_GE(worst, 0.4);
  EXPECT_LE(fastest, r.robot.max_speed + 1e-9);
  EXPECT_LE(fastest_turn, r.robot.max_turn_rate + 1e-9);
}

TEST(Robot, VisitsMostRooms) {
  const auto& r = default_run();
  const auto& rooms = r.world.layout().rooms;
  std::size_t visited = 0;
  for (const Room& room : rooms) {
    bool inside = false;
    for (const auto& [t, pose] : r.run.ground_truth) inside = inside || room.area.expanded(-0.5).contains(pose.translation());
    visited += inside ? 1 : 0;
  }
  EXPECT_GE(static_cast<double>(visited), 0.75 * static_cast<double>(rooms.size()));
}

TEST(Robot, OdometryDriftsWithDistanceButStaysSane) {
  const auto& r = default_run();
  const std::size_t n = r.run.ground_truth.size();
  const double total = path_length(r.run.ground_truth, n - 1);
  // Early on the error is small; at the end it is dominated by the systematic
  // heading drift (odom_drift rad per metre), and the position error stays a
  // modest fraction of the distance driven.
  const std::size_t early = n / 10;
  const Pose2 early_error = odometry_error(r.run, early);
  const Pose2 final_error = odometry_error(r.run, n - 1);
  const double early_distance = path_length(r.run.ground_truth, early);
  EXPECT_LT(std::hypot(early_error.x, early_error.y), 0.05 * early_distance + 0.1);
  EXPECT_NEAR(final_error.theta, r.robot.odom_drift * total, 0.1);
  EXPECT_GT(std::abs(final_error.theta), 5 * std::abs(early_error.theta));
  const double final_distance_error = std::hypot(final_error.x, final_error.y);
  EXPECT_GT(final_distance_error, std::hypot(early_error.x, early_error.y));
  EXPECT_LT(final_distance_error, 0.15 * total);
}

TEST(Robot, NoiselessOdometryIsExactRelativeMotion) {
  const auto& r = default_run();
  RobotConfig perfect;
  perfect.odom_trans_noise = perfect.odom_rot_noise = perfect.odom_drift = 0.0;
  const std::vector<Eigen::Vector2d> short_tour(r.tour.begin(), r.tour.begin() + 6);
  const SimulatedRun run = simulate_run(r.world, short_tour, tour_start_pose(short_tour), perfect, r.lidar, 3);
  const Pose2 origin = run.ground_truth.front().second;
  for (std::size_t k = 0; k < run.log.scans.size(); ++k) {
    const Pose2 expected = between(origin, run.ground_truth[k].second);
    const Pose2& odom = *run.log.scans[k].odometry;
    EXPECT_NEAR(odom.x, expected.x, 1e-9);
    EXPECT_NEAR(odom.y, expected.y, 1e-9);
    EXPECT_NEAR(normalize_angle(odom.theta - expected.theta), 0.0, 1e-9);
  }
}

TEST(Robot, SameSeedSameRunDifferentSeedDifferentNoise) {
  const auto& r = default_run();
  const std::vector<Eigen::Vector2d> short_tour(r.tour.begin(), r.tour.begin() + 6);
  const Pose2 start = tour_start_pose(short_tour);
  const SimulatedRun a = simulate_run(r.world, short_tour, start, r.robot, r.lidar, 5);
  const SimulatedRun b = simulate_run(r.world, short_tour, start, r.robot, r.lidar, 5);
  const SimulatedRun c = simulate_run(r.world, short_tour, start, r.robot, r.lidar, 6);
  ASSERT_EQ(a.log.scans.size(), b.log.scans.size());
  for (std::size_t k = 0; k < a.log.scans.size(); ++k) {
    EXPECT_EQ(a.log.scans[k].ranges, b.log.scans[k].ranges);
    EXPECT_EQ(a.log.scans[k].odometry->x, b.log.scans[k].odometry->x);
  }
  // The true path does not depend on the noise seed; the sensors do.
  ASSERT_EQ(a.ground_truth.size(), c.ground_truth.size());
  EXPECT_EQ(a.ground_truth.back().second.x, c.ground_truth.back().second.x);
  EXPECT_NE(a.log.scans.back().odometry->x, c.log.scans.back().odometry->x);
  EXPECT_NE(a.log.scans.back().ranges, c.log.scans.back().ranges);
}

TEST(Robot, TurnsInPlaceBeforeDrivingBackwards) {
  // Waypoint straight behind: the robot must turn around on the spot first.
  const DrivenPath path = drive_waypoints({Eigen::Vector2d(-2, 0)}, Pose2(), RobotConfig{}, 0.1);
  ASSERT_TRUE(path.reached_goal);
  for (const Pose2& p : path.poses) EXPECT_LE(p.x, 1e-9);  // never moves forward (+x)
  EXPECT_LT((path.poses.back().translation() - Eigen::Vector2d(-2, 0)).norm(), 0.05);
  // pi at 1 rad/s then 2 m at 0.6 m/s: about 6.5 s.
  EXPECT_NEAR(static_cast<double>(path.poses.size()) * 0.1, 6.5, 1.0);
}

TEST(Robot, RejectsBadConfig) {
  RobotConfig bad;
  bad.max_speed = 0;
  EXPECT_THROW(drive_waypoints({Eigen::Vector2d(1, 0)}, Pose2(), bad, 0.1), ConfigError);
  RobotConfig noisy;
  noisy.odom_trans_noise = -0.1;
  EXPECT_THROW(validate(noisy), ConfigError);
  EXPECT_THROW(drive_waypoints({Eigen::Vector2d(1, 0)}, Pose2(), RobotConfig{}, 0.0), ConfigError);
}

}  // namespace
}  // namespace dsswarm
