// End-to-end: readers -> SLAM -> outputs -> evaluation, on simulated and real logs.
#include "apps/slam_runner.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "eval/ate.hpp"
#include "eval/relations.hpp"
#include "io/logs/log_reader.hpp"
#include "io/maps/map_server.hpp"
#include "sim/scenario.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

TEST(SlamRunner, DemoTrajectoryBeatsOdometryAndWritesEveryOutput) {
  DemoConfig demo;
  SimulatedRun sim = simulate_demo(demo);
  sim.log.scans.resize(800);  // keep the test short
  sim.ground_truth.resize(800);
  Slam slam;
  const RunResult r = run_slam(sim.log, slam, "");
  ASSERT_EQ(r.trajectory.size(), sim.log.scans.size());
  Trajectory truth, odometry;
  for (const auto& [t, p] : sim.ground_truth) truth.push_back({t, p});
  for (const auto& s : sim.log.scans) odometry.push_back({s.timestamp, *s.odometry});
  const double slam_ate = evaluate_ate(r.trajectory, truth).rmse;
  EXPECT_LT(slam_ate, 0.05);
  EXPECT_LT(slam_ate, evaluate_ate(odometry, truth).rmse);

  const fs::path dir = fs::path(DSSWARM_TEST_TMP) / "runner_outputs";
  fs::remove_all(dir);
  write_run_outputs(dir, r, slam, run_stats(r, slam, sim.log, 0.0));
  for (const char* f : {"trajectory.tum", "map.pgm", "map.yaml", "map.png", "stats.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const LoadedMap loaded = read_map_server(dir / "map.yaml");  // loads as map_server would
  EXPECT_GT(loaded.raster.width, 100);
  std::ifstream stats(dir / "stats.json");
  const auto j = nlohmann::json::parse(stats);
  for (const char* k : {"scans_read", "scans_matched", "wall_seconds", "scans_per_second", "peak_rss_bytes",
                        "cells_allocated", "bytes_per_cell"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["scans_read"].get<std::size_t>(), 800u);
}

// Accuracy regression on a real log: a generous bound (the README reports the
// measured figure); catches a broken matcher, reader or metric, not 1 cm.
TEST(SlamRunnerRealData, MitCsailRelationsStayAccurate) {
  const fs::path data = DSSWARM_SHARED_DATA;
  if (!fs::exists(data / "carmen/mit-csail.log.gz")) GTEST_SKIP() << "real data not found at " << data;
  const SensorLog log = read_log(data / "carmen/mit-csail.log.gz");
  Slam slam;
  const RunResult r = run_slam(log, slam, "");
  const RelationMetrics m = evaluate_relations(r.trajectory, read_relations(data / "relations/mit-csail.relations"));
  EXPECT_EQ(m.missing, 0u);
  EXPECT_LT(m.trans_mean, 0.10);
  EXPECT_LT(m.rot_mean_deg, 1.0);
}

}  // namespace
}  // namespace dsswarm
