// Single-robot SLAM with loop closing on simulated runs with exact ground truth.
#include <gtest/gtest.h>

#include "eval/ate.hpp"
#include "grid/map_combine.hpp"
#include "sim/loop_world.hpp"
#include "slam/slam.hpp"

namespace dsswarm {
namespace {

// 1.3 laps of a 40 m × 24 m corridor ring seen with an 8 m lidar, odometry
// turning 0.05 rad too much per metre: local SLAM drifts over the lap.
SimulatedRun long_loop(double laps = 1.3) {
  LoopWorldConfig config;
  config.laps = laps;
  const LoopWorld w = make_loop_world(config);
  LidarConfig lidar;
  lidar.range_max = 8.0;
  lidar.noise_std = 0.02;
  RobotConfig robot;
  robot.odom_drift = 0.05;
  return simulate_run(w.world, w.tour, w.start, robot, lidar, 1);
}

Trajectory stamped(const SimulatedRun& run, const std::vector<Pose2>& poses) {
  Trajectory t;
  for (std::size_t i = 0; i < poses.size(); ++i) t.push_back({run.log.scans[i].timestamp, poses[i]});
  return t;
}

Trajectory truth_of(const SimulatedRun& run) {
  Trajectory t;
  for (const auto& [time, p] : run.ground_truth) t.push_back({time, p});
  return t;
}

void run(Slam& slam, const SimulatedRun& sim) {
  for (const LaserScan& s : sim.log.scans) slam.process(s);
  slam.finish();
}

TEST(LoopClosing, TheDriftOfALongLoopIsTakenOutWithRightClosuresOnly) {
  const SimulatedRun sim = long_loop();
  // Without the degeneracy check, whose hold on odometry along the corridors
  // leaves this world's front end too little drift for the test (0.17-0.26 m).
  SlamConfig config = with_loop_closure();
  config.degeneracy.min_ratio = 0.0;
  Slam slam(config);
  run(slam, sim);
  const Trajectory truth = truth_of(sim);
  const double local = evaluate_ate(stamped(sim, slam.local_trajectory()), truth).rmse;
  const double closed = evaluate_ate(stamped(sim, slam.trajectory()), truth).rmse;
  // This world's front end drifts 0.25-0.31 m over 1.2-2 laps (0.27 m at
  // 1.3; just over 0.3 m before the scorer's single precision moved the
  // search's path). Drifts beyond 0.3 m, closed, over 50 worlds: the
  // loop-closure bench (docs/loop_closure.md).
  EXPECT_GT(local, 0.2);
  EXPECT_LT(closed, 0.05);
  EXPECT_LT(closed, 0.2 * local);
  const auto& closures = slam.loop_closer().closures();
  EXPECT_GT(closures.size(), 10u);
  // Each closure against the truth of the submap's nearest node. The submap
  // holds local SLAM's drift (0.27 m ATE here), so a right closure can be a
  // decimetre off by this measure: 0.08 m at most with GCC -O3, 0.13 m with
  // the sanitizer build's clang -O1 (another search path); the bench calls a
  // closure false beyond 0.2 m.
  for (const LoopClosure& c : closures) {
    ASSERT_TRUE(c.nearest_scan);
    const Pose2 e = between(between(sim.ground_truth[*c.nearest_scan].second, sim.ground_truth[c.scan].second),
                            c.relative_to_nearest);
    EXPECT_LT(std::hypot(e.x, e.y), 0.15) << "closure of scan " << c.scan << " into submap " << c.submap;
    EXPECT_LT(std::abs(e.theta), 0.02) << "closure of scan " << c.scan << " into submap " << c.submap;
  }
}

TEST(LoopClosing, NodesHangOnTheirSubmapsAndTheGlobalMapIsTheSubmapsAtTheirPoses) {
  const SimulatedRun sim = long_loop(1.1);
  Slam slam(with_loop_closure());
  run(slam, sim);
  const LoopCloser& closer = slam.loop_closer();
  const std::vector<const Submap*> submaps = slam.submaps().all();
  ASSERT_GT(submaps.size(), 5u);
  ASSERT_GT(closer.nodes(), 100u);
  const std::vector<Pose2> trajectory = slam.trajectory(), local = slam.local_trajectory();
  int last_submap = 0;
  for (std::size_t i = 0; i < closer.nodes(); ++i) {
    const TrajectoryNode n = closer.node(i);
    EXPECT_GE(n.submap, last_submap);  // submaps follow the trajectory
    last_submap = n.submap;
    const Submap& s = *submaps[static_cast<std::size_t>(n.submap)];
    const Pose2 expected = between(s.anchor, n.local);
    EXPECT_NEAR(n.in_submap.x, expected.x, 1e-9);
    EXPECT_NEAR(n.in_submap.theta, expected.theta, 1e-9);
    EXPECT_NEAR(local[n.scan].x, n.local.x, 1e-9);
    EXPECT_NEAR(trajectory[n.scan].x, n.global.x, 1e-9);
  }
  // Every inserted scan in exactly one submap.
  std::size_t scans = 0;
  for (const Submap* s : submaps) scans += static_cast<std::size_t>(s->scans);
  EXPECT_EQ(scans, slam.scans_inserted());
  // own_map() = the submaps, each at its optimized pose, combined in order.
  MultiResMap expected;
  for (const Submap* s : submaps)
    combine_into(expected, s->finished ? s->frozen.thaw(MapConfig{}) : s->map, closer.submap_cells_pose(s->id));
  const DsGrid& fine = slam.own_map().finest();
  std::size_t compared = 0;
  expected.finest().for_each_tile([&](CellIndex origin, const DsMass* cells) {
    for (int i = 0; i < DsGrid::kTileCells; i += 11) {
      ASSERT_NEAR(fine.at(DsGrid::tile_cell(origin, i)).occupied, cells[i].occupied, 1e-5f);
      ASSERT_NEAR(fine.at(DsGrid::tile_cell(origin, i)).free, cells[i].free, 1e-5f);
      ++compared;
    }
  });
  EXPECT_GT(compared, 10000u);
}

TEST(LoopClosing, LocalizingInASavedMapLeavesItUnchanged) {
  const SimulatedRun sim = long_loop(1.1);
  Slam mapping(with_loop_closure());
  run(mapping, sim);
  const MultiResMap saved = mapping.own_map();
  Slam localizing(with_loop_closure(), saved, sim.log.scans.front().odometry.value_or(Pose2()) * Pose2(0.1, -0.1, 0.03),
                  MapUse::localize);
  run(localizing, sim);
  EXPECT_EQ(localizing.scans_inserted(), 0u);
  EXPECT_EQ(localizing.loop_closer().stats().searches, 0u);
  const DsGrid& before = saved.finest();
  const DsGrid& after = localizing.map().finest();
  EXPECT_EQ(after.tiles_allocated(), before.tiles_allocated());
  before.for_each_tile([&](CellIndex origin, const DsMass* cells) {
    for (int i = 0; i < DsGrid::kTileCells; i += 13) {
      ASSERT_EQ(after.at(DsGrid::tile_cell(origin, i)).occupied, cells[i].occupied);
      ASSERT_EQ(after.at(DsGrid::tile_cell(origin, i)).free, cells[i].free);
    }
  });
  // It localizes: started 14 cm and 2 degrees off, it follows the mapping
  // run's trajectory (both in the saved map's frame).
  const std::vector<Pose2> mapped = mapping.trajectory(), localized = localizing.trajectory();
  double deviation = 0.0;
  for (std::size_t i = 0; i < mapped.size(); ++i) deviation += (mapped[i].translation() - localized[i].translation()).norm();
  EXPECT_LT(deviation / static_cast<double>(mapped.size()), 0.03);
}

}  // namespace
}  // namespace dsswarm
