// End-to-end: readers -> SLAM -> outputs -> evaluation, on simulated and real logs.
#include "apps/slam_runner.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "apps/slam_options.hpp"
#include "common/errors.hpp"
#include "common/test_files.hpp"
#include "eval/ate.hpp"
#include "eval/relations.hpp"
#include "io/logs/log_reader.hpp"
#include "io/maps/dsmap.hpp"
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
  // Without map outputs the map is not composed for its figures alone.
  const nlohmann::json lean = run_stats(r, slam, sim.log, 0.0, false);
  for (const char* k : {"cells_allocated", "map_bytes", "bytes_per_cell"}) EXPECT_FALSE(lean.contains(k)) << k;
  EXPECT_EQ(lean["scans_read"], j["scans_read"]);
}

// A map with no evidence is refused before anything is written, with the
// trajectory-only outputs too (which need no raster).
TEST(SlamRunner, AnEmptyMapIsRefusedWithOrWithoutImages) {
  Slam slam;
  const RunResult r;
  const nlohmann::json stats;
  for (const bool images : {true, false})
    EXPECT_THROW(run_output_files(fs::path(DSSWARM_TEST_TMP) / "runner_empty", r, slam, stats, nullptr, images),
                 InputError)
        << "images " << images;
  SimulatedRun sim = simulate_demo(DemoConfig{});
  sim.log.scans.resize(5);
  Slam mapped;
  const RunResult some = run_slam(sim.log, mapped, "");
  EXPECT_NO_THROW(run_output_files(fs::path(DSSWARM_TEST_TMP) / "runner_some", some, mapped, stats, nullptr, false));
}

// --save-map then --load-map: the second run, started 20 cm and 4° off,
// localizes in the saved map and so follows the first run's trajectory (a
// run that ignored the map would found a new one at the wrong start and stay
// offset by that error).
TEST(SlamRunner, SavedMapIsLoadedAndUsedByASecondRun) {
  SimulatedRun sim = simulate_demo(DemoConfig{});
  sim.log.scans.resize(400);
  Slam first;
  const RunResult r1 = run_slam(sim.log, first, "");
  const fs::path file = test::fresh_dir("runner_dsmap") / "first.dsmap";
  write_dsmap(file.string(), own_map_snapshot(first, "robot"));

  SlamConfig config;
  config.map.evidence.hit_occupied = 0.3f;  // the file's evidence model must win
  ContinuedMap continued = load_map_to_continue(file.string(), config);
  EXPECT_EQ(continued.version, first.scans_inserted());
  EXPECT_FLOAT_EQ(config.map.evidence.hit_occupied, EvidenceModel{}.hit_occupied);
  ASSERT_EQ(continued.warnings.size(), 1u);  // the evidence model differed
  EXPECT_EQ(continued.map.finest().tiles_allocated(), first.own_map().finest().tiles_allocated());

  const Pose2 start = *sim.log.scans.front().odometry * Pose2(0.16, -0.12, 0.07);
  Slam second(config, std::move(continued.map), start);
  const RunResult r2 = run_slam(sim.log, second, "");
  ASSERT_EQ(r2.trajectory.size(), r1.trajectory.size());
  // The first scans of the first run were matched against a map still being
  // founded; from then on both runs live in the same map.
  auto deviation = [&](std::size_t i) {
    return (r1.trajectory[i].pose.translation() - r2.trajectory[i].pose.translation()).norm();
  };
  EXPECT_LT(deviation(0), 0.08) << "the 20 cm start error was not corrected";
  double sum = 0.0, worst = 0.0;
  for (std::size_t i = 5; i < r1.trajectory.size(); ++i) {
    sum += deviation(i);
    worst = std::max(worst, deviation(i));
  }
  const double mean = sum / static_cast<double>(r1.trajectory.size() - 5);
  std::printf("[ dsmap    ] second run in the saved map: first pose %.3f m from the first run's, then mean %.4f m, "
              "worst %.4f m\n", deviation(0), mean, worst);
  EXPECT_LT(mean, 0.02);
  EXPECT_LT(worst, 0.05);
  EXPECT_LT(std::abs(normalize_angle(r1.trajectory.back().pose.theta - r2.trajectory.back().pose.theta)), 0.02);

  // Saving the continued map counts the scans of both runs.
  const MapSnapshot saved = own_map_snapshot(second, "robot", continued.version);
  EXPECT_EQ(saved.layers.at(0).version, first.scans_inserted() + second.scans_inserted());
}

TEST(SlamRunner, LoadedMapMustMatchTheConfiguredGrid) {
  const fs::path file = test::fresh_dir("runner_dsmap_mismatch") / "coarse.dsmap";
  MapSnapshot s;
  s.layers.push_back({"robot", 1, Pose2(), 0, std::make_shared<MultiResMap>(MapConfig{0.1, 2, {}, false, false}), {}});
  s.layers.push_back(s.layers.front());
  write_dsmap(file.string(), s);
  SlamConfig config;  // 0.05 m, 3 levels
  try {
    load_map_to_continue(file.string(), config);
    FAIL() << "mismatch accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    for (const char* part : {"coarse.dsmap", "0.1 m and 2 levels", "0.05 m and 3 levels"})
      EXPECT_NE(m.find(part), std::string::npos) << m;
  }
  config.map.resolution = 0.1;
  config.map.levels = 2;
  const ContinuedMap c = load_map_to_continue(file.string(), config);
  ASSERT_EQ(c.warnings.size(), 1u);  // two layers: only layer 0 is used
  EXPECT_NE(c.warnings[0].find("layer 0"), std::string::npos);
  EXPECT_THROW(load_map_to_continue((file.parent_path() / "none.dsmap").string(), config), InputError);
}

TEST(SlamOptions, PoseOptionIsThreeFiniteNumbers) {
  const Pose2 p = pose_option({1.5, -2.0, 0.25}, "--start-pose");
  EXPECT_DOUBLE_EQ(p.x, 1.5);
  EXPECT_DOUBLE_EQ(p.y, -2.0);
  EXPECT_DOUBLE_EQ(p.theta, 0.25);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::vector<std::vector<double>> bad_values = {{}, {1, 2}, {1, 2, 3, 4}, {nan, 0, 0}, {0, inf, 0}};
  for (const std::vector<double>& bad : bad_values)
    EXPECT_THROW(pose_option(bad, "--start-pose"), ConfigError) << bad.size() << " values";
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
