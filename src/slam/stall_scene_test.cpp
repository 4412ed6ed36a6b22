// The stall guard in a whole pipeline: the simulated building whose tour
// starts down a corridor with its end in sight (seed 34, 30 m lidar). Without
// the guard local SLAM "stood" there for 3.8 m while the robot drove
// (measured with GCC on x86; docs/loop_closure.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sim/scenario.hpp"
#include "slam/slam.hpp"

namespace dsswarm {
namespace {

// The simulated building's tour for `seed`, seen with a 30 m lidar.
SimulatedRun building_tour(std::uint64_t seed) {
  DemoConfig demo;
  demo.world.seed = seed;
  demo.seed = seed;
  demo.lidar.range_max = 30.0;
  return simulate_demo(demo);
}

TEST(StallScene, LocalSlamKeepsUpWithARobotLeavingItsFirstViewpoint) {
  const SimulatedRun run = building_tour(34);
  const std::size_t scans = 150;  // 9 m straight down the corridor
  ASSERT_GT(run.log.scans.size(), scans);
  SlamConfig config = with_loop_closure(SlamConfig{});
  config.seed = 34;
  Slam slam(config);
  Pose2 last;
  for (std::size_t i = 0; i < scans; ++i) last = slam.process(run.log.scans[i]).pose;
  const Pose2 truth = between(run.ground_truth.front().second, run.ground_truth[scans - 1].second);
  ASSERT_GT(std::hypot(truth.x, truth.y), 8.0);
  EXPECT_LT(std::hypot(last.x - truth.x, last.y - truth.y), 0.5)
      << "local SLAM at (" << last.x << ", " << last.y << "), the robot at (" << truth.x << ", " << truth.y << ")";
}

// Seed 4's robot: local SLAM falls 0.18 m behind before the guard steps in
// (its 0.2 m window), as on about a third of the building's seeds; catching
// up then puts the rest of the run back in line with the first scans instead
// of 0.18 m behind them for good.
TEST(StallScene, AStallLeavesNoLastingOffsetOnceTheGuardCatchesUp) {
  const SimulatedRun run = building_tour(4);
  const std::size_t scans = 150;
  ASSERT_GT(run.log.scans.size(), scans);
  const Pose2 truth = between(run.ground_truth.front().second, run.ground_truth[scans - 1].second);
  for (const bool catch_up : {true, false}) {
    SlamConfig config = with_loop_closure(SlamConfig{});
    config.seed = 4;
    config.stall.catch_up = catch_up;
    Slam slam(config);
    Pose2 first, last;
    for (std::size_t i = 0; i < scans; ++i) {
      last = slam.process(run.log.scans[i]).pose;
      if (i == 0) first = last;
    }
    const Pose2 moved = between(first, last);
    const double off = std::hypot(moved.x - truth.x, moved.y - truth.y);
    std::printf("catch_up %d: %.3f m off the truth after %zu scans (%zu held)\n", catch_up ? 1 : 0, off, scans,
                slam.scans_stall_held());
    EXPECT_GT(slam.scans_stall_held(), 0u);
    if (catch_up)
      EXPECT_LT(off, 0.08);
    else
      EXPECT_GT(off, 0.12);  // the scene still shows what catching up is for
  }
}

}  // namespace
}  // namespace dsswarm
