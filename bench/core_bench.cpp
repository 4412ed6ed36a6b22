// Throughput of the hot paths on a simulated building: scan insertion, pose
// scoring and a whole match. Run: build/bench/core_bench
#include <benchmark/benchmark.h>

#include "matching/monte_carlo_matcher.hpp"
#include "matching/scan_scorer.hpp"
#include "sim/scenario.hpp"
#include "slam/slam.hpp"

namespace dsswarm {
namespace {

// A map built from the first 300 scans of the demo run, and the next scan.
struct Fixture {
  SimulatedRun run = simulate_demo(DemoConfig{});
  Slam slam;
  std::vector<ScanPoint> points;
  Pose2 pose;
  Fixture() {
    for (int i = 0; i < 300; ++i) pose = slam.process(run.log.scans[static_cast<std::size_t>(i)]).pose;
    points = scan_to_points(run.log.scans[300]);
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_ScorePose(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(score_pose(f.slam.map().finest(), f.points, f.pose));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.points.size()));
}
BENCHMARK(BM_ScorePose);

void BM_InsertScan(benchmark::State& state) {
  Fixture& f = fixture();
  MultiResMap map;  // repeated insertion of one scan: the cost of the beam traversal and updates
  for (auto _ : state) map.insert_scan(f.pose, Pose2(), f.points);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_InsertScan);

void BM_MatchScan(benchmark::State& state) {
  Fixture& f = fixture();
  MonteCarloMatcher matcher;
  for (auto _ : state) benchmark::DoNotOptimize(matcher.match(f.slam.map(), f.points, f.pose));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MatchScan);

}  // namespace
}  // namespace dsswarm

BENCHMARK_MAIN();
