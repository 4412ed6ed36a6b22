// Micro-benchmarks of the per-scan hot paths, on the fixed input of
// bench_fixture.hpp (the map of the demo robot's first 300 scans, scan 300).
// Run: build/bench/core_bench [--benchmark_filter=REGEX]
#include <benchmark/benchmark.h>

#include <array>

#include "bench_fixture.hpp"
#include "common/rng.hpp"
#include "filter/scan_histogram.hpp"
#include "grid/ray_traversal.hpp"
#include "matching/branch_and_bound_matcher.hpp"
#include "matching/monte_carlo_matcher.hpp"
#include "matching/scan_scorer.hpp"
#include "slam/loop_search.hpp"

namespace dsswarm::bench {
namespace {

// Dempster's rule on 4096 pairs of valid masses, as a map merge combines cells.
void BM_DempsterCombine(benchmark::State& state) {
  constexpr std::size_t kCells = 4096;
  std::vector<DsMass> a(kCells), b(kCells), out(kCells);
  Rng rng(3);
  for (std::size_t i = 0; i < kCells; ++i) {
    const float oa = static_cast<float>(rng.uniform(0.0, 0.6)), ob = static_cast<float>(rng.uniform(0.0, 0.6));
    a[i] = {oa, static_cast<float>(rng.uniform(0.0, 0.98 - oa))};
    b[i] = {ob, static_cast<float>(rng.uniform(0.0, 0.98 - ob))};
  }
  for (auto _ : state) {
    for (std::size_t i = 0; i < kCells; ++i) out[i] = combine(a[i], b[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kCells));
}
BENCHMARK(BM_DempsterCombine);

// The cells every beam of one scan crosses on the finest level, without updating them.
void BM_TraverseRays(benchmark::State& state) {
  const Fixture& f = fixture();
  const double resolution = f.slam.map().config().resolution;
  std::int64_t cells = 0;
  for (auto _ : state) {
    for (const ScanPoint& p : f.points)
      traverse_ray(f.pose.translation(), f.pose * Eigen::Vector2d(p.x, p.y), resolution,
                   [&cells](CellIndex c) { benchmark::DoNotOptimize(cells += c.x & 1); });
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.points.size()));
}
BENCHMARK(BM_TraverseRays);

// One scan inserted into the mapped area (all levels: traversal, Dempster
// updates, surfaces); the tiles already exist, as they mostly do in SLAM.
void BM_InsertScan(benchmark::State& state) {
  const Fixture& f = fixture();
  MultiResMap map = f.slam.map();
  for (auto _ : state) map.insert_scan(f.pose, f.scan.laser_offset, f.points);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_InsertScan);

// The same into an empty map each time: tile allocation included.
void BM_InsertScanNewMap(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) {
    MultiResMap map(f.slam.map().config());
    map.insert_scan(f.pose, f.scan.laser_offset, f.points);
    benchmark::DoNotOptimize(map.cells_allocated());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_InsertScanNewMap);

// One pose evaluation as the matcher makes it (a ScanScorer prepared once,
// the matcher's unknown_value) on level 0 (every point) and level 2 (every
// 4th point).
void BM_ScorePose(benchmark::State& state) {
  const Fixture& f = fixture();
  const int level = static_cast<int>(state.range(0));
  const std::size_t stride = std::size_t{1} << level;
  const ScanScorer scorer(f.slam.map().level(level), f.points, stride, MatcherConfig{}.unknown_value);
  for (auto _ : state) benchmark::DoNotOptimize(scorer.score(f.pose));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.points.size() / stride));
}
BENCHMARK(BM_ScorePose)->Arg(0)->Arg(2);

// One whole match with the default budget (240 evaluations over 3 levels).
void BM_MatchScan(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) {
    MonteCarloMatcher matcher(MatcherConfig{}, 1);  // same seed each time: the same search
    benchmark::DoNotOptimize(matcher.match(f.slam.map(), f.points, f.pose));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MatchScan);

// The scan filter's per-scan summary and its comparison with one kept scan.
void BM_FilterHistogram(benchmark::State& state) {
  const Fixture& f = fixture();
  const HistogramSpec spec{default_column_count(f.scan.ranges.size())};
  for (auto _ : state) benchmark::DoNotOptimize(scan_histogram(f.scan, spec));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FilterHistogram);

void BM_FilterCorrelation(benchmark::State& state) {
  const Fixture& f = fixture();
  const HistogramSpec spec{default_column_count(f.scan.ranges.size())};
  const std::vector<double> a = scan_histogram(f.scan, spec);
  const std::vector<double> b = scan_histogram(f.run.log.scans[kMapScans - 1], spec);
  for (auto _ : state) benchmark::DoNotOptimize(pearson_correlation(a, b));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FilterCorrelation);

// Loop-closure search, on the same fixture so that it compares with
// BM_MatchScan: the next scan searched in the map of the first kMapScans
// scans (as one finished submap) from a prior 0.36 m and 3° off, within the
// window a round gives it. First the branch-and-bound bounds a round builds
// per target submap, then one whole search (branch and bound, refinement,
// verification, runner-up search) with the default LoopSearchConfig.
constexpr SearchWindow kLoopWindow{1.0, 0.15};

void BM_LoopClosureBounds(benchmark::State& state) {
  const Fixture& f = fixture();
  const LoopSearchConfig config;
  for (auto _ : state) {
    const BranchAndBoundMatcher matcher(f.slam.map().finest(), kLoopWindow.xy, config.max_depth);
    benchmark::DoNotOptimize(&matcher);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LoopClosureBounds)->Unit(benchmark::kMillisecond);

void BM_LoopClosureSearch(benchmark::State& state) {
  const Fixture& f = fixture();
  const LoopSearchConfig config;
  Submap submap;
  submap.finished = true;
  submap.map = f.slam.map();
  const BranchAndBoundMatcher matcher(submap.map.finest(), kLoopWindow.xy, config.max_depth);
  const Pose2 prior = f.pose * Pose2(0.3, -0.2, 0.05);
  LoopRejection rejection = LoopRejection::no_match;
  for (auto _ : state) {
    const LoopSearch r = search_loop_closure(matcher, submap, f.points, prior, kLoopWindow, config, 7);
    rejection = r.rejection;
    benchmark::DoNotOptimize(r.candidate.relative);
  }
  state.SetLabel(to_string(rejection));  // what the search concluded: "none" is a closure
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LoopClosureSearch)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dsswarm::bench

BENCHMARK_MAIN();
