// Micro-benchmarks of what robots do with whole maps at an encounter:
// snapshot encode/decode (.dsmap) and merging (combine_into,
// compose_working_map). Input: the map of bench_fixture.hpp.
#include <benchmark/benchmark.h>

#include <memory>

#include "bench_fixture.hpp"
#include "io/maps/dsmap.hpp"
#include "swarm/map_merge.hpp"

namespace dsswarm::bench {
namespace {

// Where the other robot's map frame lies in ours: off-grid and rotated, so
// that merging resamples every cell.
const Pose2 kOtherFrame{0.37, -0.21, 0.4};

MapSnapshot snapshot() {
  const Fixture& f = fixture();
  return {"b", {MapLayer{"b", kMapScans, Pose2(), 0, std::make_shared<const MultiResMap>(f.slam.map()), {}}}};
}

void BM_DsmapEncode(benchmark::State& state) {
  const MapSnapshot s = snapshot();
  std::size_t bytes = 0;
  for (auto _ : state) bytes = encode_dsmap(s).size();
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(fixture().slam.map().cells_allocated()));
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_DsmapEncode)->Unit(benchmark::kMillisecond);

void BM_DsmapDecode(benchmark::State& state) {
  const std::vector<std::uint8_t> bytes = encode_dsmap(snapshot());
  for (auto _ : state) benchmark::DoNotOptimize(decode_dsmap(bytes, "bench"));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(fixture().slam.map().cells_allocated()));
}
BENCHMARK(BM_DsmapDecode)->Unit(benchmark::kMillisecond);

// The other robot's map (here: the same map) resampled into ours, every level.
void BM_CombineInto(benchmark::State& state) {
  const MultiResMap& source = fixture().slam.map();
  for (auto _ : state) {
    state.PauseTiming();
    MultiResMap target = source;
    state.ResumeTiming();
    combine_into(target, source, kOtherFrame);
    benchmark::DoNotOptimize(target.cells_allocated());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(source.cells_allocated()));
}
BENCHMARK(BM_CombineInto)->Unit(benchmark::kMillisecond);

// The map a robot matches against after a merge: its own plus one foreign layer.
void BM_ComposeWorkingMap(benchmark::State& state) {
  const MultiResMap& own = fixture().slam.map();
  const std::vector<MapLayer> foreign{
      MapLayer{"b", kMapScans, kOtherFrame, 1, std::make_shared<const MultiResMap>(own), {}}};
  for (auto _ : state) benchmark::DoNotOptimize(compose_working_map(own, foreign));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ComposeWorkingMap)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dsswarm::bench
