#include "swarm/swarm_agent.hpp"

#include <gtest/gtest.h>

#include "swarm/map_merge.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm {
namespace {

// Scans along a straight drive in the L-shaped office, odometry exact from the start.
std::vector<LaserScan> drive(const Pose2& from, const Pose2& to, int scans, std::uint64_t seed) {
  const World world = test::l_shaped_office();
  Rng rng(seed);
  std::vector<LaserScan> out;
  for (int k = 0; k < scans; ++k) {
    const Pose2 p = interpolate(from, to, static_cast<double>(k) / (scans - 1));
    LaserScan scan = simulate_scan(world, p, test::full_circle_lidar(), rng);
    scan.timestamp = 0.1 * k;
    scan.odometry = from.inverse() * p;
    out.push_back(std::move(scan));
  }
  return out;
}

double largest_difference(const DsGrid& a, const DsGrid& b) {
  double worst = 0.0;
  a.for_each_tile([&](CellIndex origin, const DsMass* cells) {
    for (int i = 0; i < DsGrid::kTileCells; ++i) {
      const DsMass m = b.at(DsGrid::tile_cell(origin, i));
      worst = std::max({worst, std::abs(double{m.occupied} - cells[i].occupied), std::abs(double{m.free} - cells[i].free)});
    }
  });
  return worst;
}

TEST(SwarmAgent, ComposingOffTheScanPathLosesNoScanAndCountsNoneTwice) {
  SwarmAgent a("a", SlamConfig{}), b("b", SlamConfig{});
  const auto scans_a = drive({1.5, 1.5, 0.4}, {3.5, 2.0, 0.1}, 40, 1);
  for (const LaserScan& s : drive({8.5, 2.0, -2.5}, {5.0, 2.5, 2.9}, 20, 2)) b.process(s);
  for (int k = 0; k < 20; ++k) a.process(scans_a[k]);
  const Pose2 b_in_a = Pose2{1.5, 1.5, 0.4}.inverse() * Pose2{8.5, 2.0, -2.5};
  ASSERT_TRUE(a.absorb(b.snapshot(), b_in_a));
  const SwarmAgent::ComposeJob job = a.compose_job();
  // What merging at once would have given: the working map then, and every
  // later scan inserted into it where the robot placed it.
  MultiResMap expected = SwarmAgent::compose(job);
  for (int k = 20; k < 40; ++k) {  // scans keep coming while it composes
    const std::size_t before = a.slam().scans_inserted();
    const SlamStep step = a.process(scans_a[k]);
    if (a.slam().scans_inserted() != before) expected.insert_scan(step.pose, Pose2{}, scan_to_points(scans_a[k]));
  }
  ASSERT_GT(a.slam().scans_inserted(), job.own_version);
  a.install(SwarmAgent::compose(job), job.own_version);
  for (int level = 0; level < expected.levels(); ++level)
    EXPECT_EQ(largest_difference(expected.level(level), a.slam().map().level(level)), 0.0) << "level " << level;
  // b's evidence is in the working map, not in the own map a shares.
  EXPECT_GT(largest_difference(a.slam().map().finest(), a.slam().own_map().finest()), 0.1);
}

}  // namespace
}  // namespace dsswarm
