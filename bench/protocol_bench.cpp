// Micro-benchmarks of the swarm protocol's bytes (src/protocol/wire.hpp): an
// encounter Offer (scan + surroundings, the biggest message robots exchange
// before deciding) and one snapshot Chunk of the default size.
#include <benchmark/benchmark.h>

#include "bench_fixture.hpp"
#include "protocol/wire.hpp"
#include "swarm/relative_pose.hpp"
#include "swarm/swarm_config.hpp"

namespace dsswarm::bench {
namespace {

protocol::Message offer() {
  const Fixture& f = fixture();
  const RelativePoseConfig rc;
  protocol::Offer o;
  o.encounter = 42;
  o.stamp = f.scan.timestamp;
  o.pose = f.pose;
  o.points = f.points;
  o.surroundings = surroundings_points(f.slam.map(), f.pose, rc.surroundings_radius, rc.surroundings_points);
  o.wide_surroundings =
      surroundings_points(f.slam.map(), f.pose, rc.merge_surroundings_radius, rc.merge_surroundings_points);
  o.inventory = {{"a", 300, 0}, {"b", 120, 1}, {"c", 80, 2}};
  return {protocol::Header{"a", "b", 1, 7}, o};
}

protocol::Message chunk() {
  protocol::Chunk c;
  c.encounter = 42;
  c.count = 3;
  c.total_bytes = 3 * SwarmConfig{}.chunk_bytes;
  c.data.resize(SwarmConfig{}.chunk_bytes);
  for (std::size_t i = 0; i < c.data.size(); ++i) c.data[i] = static_cast<std::uint8_t>(i * 131 + 7);
  return {protocol::Header{"a", "b", 1, 8}, c};
}

void encode_bench(benchmark::State& state, const protocol::Message& m) {
  std::size_t bytes = 0;
  for (auto _ : state) bytes = protocol::encode(m).size();
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(bytes));
}

void decode_bench(benchmark::State& state, const protocol::Message& m) {
  const std::vector<std::uint8_t> bytes = protocol::encode(m);
  for (auto _ : state) benchmark::DoNotOptimize(protocol::decode(bytes));
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(bytes.size()));
}

void BM_WireEncodeOffer(benchmark::State& state) { encode_bench(state, offer()); }
void BM_WireDecodeOffer(benchmark::State& state) { decode_bench(state, offer()); }
void BM_WireEncodeChunk(benchmark::State& state) { encode_bench(state, chunk()); }
void BM_WireDecodeChunk(benchmark::State& state) { decode_bench(state, chunk()); }
BENCHMARK(BM_WireEncodeOffer);
BENCHMARK(BM_WireDecodeOffer);
BENCHMARK(BM_WireEncodeChunk);
BENCHMARK(BM_WireDecodeChunk);

}  // namespace
}  // namespace dsswarm::bench
