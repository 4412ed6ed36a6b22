// Wall alignment in a whole pipeline: a simulated building (walls on the
// world's axes) toured by a swarm robot, which starts facing its first
// waypoint, at a slant to the walls.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/swarm_sim.hpp"
#include "slam/slam.hpp"

namespace dsswarm {
namespace {

double off_axes(double angle) { return std::abs(std::remainder(angle, std::numbers::pi / 2.0)); }

// Robot 2 of the simulated swarm's seed 1 starts 40.6° off the walls' axes.
SimulatedRun slanted_robot() {
  SwarmSimConfig sim;
  sim.seed = 1;
  return simulate_swarm(sim).runs[1];
}

struct AlignedRun {
  Pose2 first, last;
};

AlignedRun run_slam(const SimulatedRun& run, bool align, std::size_t scans) {
  SlamConfig config = with_loop_closure(SlamConfig{});
  config.align.enabled = align;
  Slam slam(config);
  AlignedRun r;
  for (std::size_t i = 0; i < scans; ++i) {
    const Pose2 pose = slam.process(run.log.scans[i]).pose;
    if (i == 0) r.first = pose;
    r.last = pose;
  }
  return r;
}

TEST(WallAlignScene, ANewMapsAxesRunAlongTheWallsAndTheTrajectoryKeepsItsShape) {
  const SimulatedRun run = slanted_robot();
  const std::size_t scans = 200;
  ASSERT_GT(run.log.scans.size(), scans);
  const Pose2 truth_first = run.ground_truth.front().second;
  // The robot starts at a slant to the walls, so the odometry frame is slanted too.
  ASSERT_GT(off_axes(truth_first.theta), 0.5);

  const AlignedRun aligned = run_slam(run, true, scans);
  // The map frame is the world's turned by a multiple of 90°: walls on its axes.
  EXPECT_LT(off_axes(truth_first.theta - aligned.first.theta), 0.003) << aligned.first.theta;
  const AlignedRun plain = run_slam(run, false, scans);
  EXPECT_NEAR(plain.first.theta, 0.0, 1e-9);  // the odometry frame

  // Either way the trajectory is the robot's, only the frame differs.
  const Pose2 truth = between(truth_first, run.ground_truth[scans - 1].second);
  for (const AlignedRun& r : {aligned, plain}) {
    const Pose2 moved = between(r.first, r.last);
    EXPECT_LT(std::hypot(moved.x - truth.x, moved.y - truth.y), 0.1);
    EXPECT_LT(std::abs(normalize_angle(moved.theta - truth.theta)), 0.01);
  }
}

// A map saved from such a run lies turned against the odometry frame: the
// same log loaded into it from its first odometry pose (`run --load-map`
// without --start-pose) is still placed where the saving run began.
TEST(WallAlignScene, TheSameLogLocalizesInATurnedMapFromItsOdometry) {
  const SimulatedRun run = slanted_robot();
  const SlamConfig config = with_loop_closure(SlamConfig{});
  Slam mapping(config);
  Pose2 first;
  for (std::size_t i = 0; i < 300; ++i) {
    const Pose2 pose = mapping.process(run.log.scans[i]).pose;
    if (i == 0) first = pose;
  }
  mapping.finish();
  ASSERT_GT(std::abs(first.theta), 0.5);  // turned to the walls
  Slam localizing(config, mapping.map(), run.log.scans.front().odometry.value_or(Pose2()), MapUse::localize);
  const Pose2 placed = localizing.process(run.log.scans.front()).pose;
  EXPECT_LT(std::hypot(placed.x - first.x, placed.y - first.y), 0.05);
  EXPECT_LT(std::abs(normalize_angle(placed.theta - first.theta)), 0.005) << placed.theta << " against " << first.theta;
}

}  // namespace
}  // namespace dsswarm
