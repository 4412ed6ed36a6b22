// Swarm network messages (src/protocol/wire.cpp): decode on the input with
// its CRC-32 appended, so the fuzzer's changes reach the field checks
// instead of stopping at the checksum. What decodes must encode to bytes
// that decode and encode the same again.
#include <zlib.h>

#include <algorithm>
#include <limits>
#include <string>

#include "fuzz_support.hpp"
#include "protocol/wire.hpp"

namespace dsswarm::fuzz {
namespace {

using namespace protocol;

std::vector<std::uint8_t> sealed(std::span<const std::uint8_t> bytes) {
  std::vector<std::uint8_t> out(bytes.begin(), bytes.end());
  const auto crc = static_cast<std::uint32_t>(crc32_z(0, bytes.data(), bytes.size()));
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(crc >> (8 * i)));
  return out;
}

// One message of each kind, as the unit tests (src/protocol/wire_test.cpp) send them.
std::vector<Body> seed_bodies() {
  Offer offer;
  offer.encounter = 7;
  offer.stamp = 976052000.125;
  offer.pose = {1.5, -2.0, 0.3};
  offer.points = {{1.0F, 2.0F, 1.5F}, {-0.5F, 3.25F, 1.0F}};
  offer.surroundings = {{4.0F, 4.0F, 1.0F}};
  offer.inventory = {{"robot1", 120, 0}, {"robot3", 40, 2}};
  Placement placement;
  placement.encounter = 7;
  placement.placement.valid = true;
  placement.placement.located.best = {{2.0, 1.0, -0.2}, 0.8, 0.6, 0.9, 0.95, 0.85};
  placement.placement.located.runner_up = PoseHypothesis{{5.0, 1.0, 2.0}, 0.5, 0.2, 0.4, 0.9, 0.3};
  placement.placement.located.evaluations = 9000;
  placement.placement.wide = Pose2{2.01, 1.0, -0.21};
  placement.known_transform = Pose2{0.1, 0.2, 0.3};
  placement.pending = {{1.0, 2.0, 3.0}};
  placement.compute_ms = 321.5;
  return {Heartbeat{AgentStatus{12.5, 100, 90, 10, 9.5, 2, 3, 1, 4.5, 88, 6}},
          Proximity{"robot1", "robot2", 99, 976052000.5, std::numeric_limits<double>::quiet_NaN()},
          offer,
          Decline{7, "no scan yet"},
          placement,
          Chunk{7, 1, 3, 150000, 0xdeadbeef, std::vector<std::uint8_t>(64, 0xab)},
          Moved{MapMoves{17,
                         {{0, {0.0, 0.0, 0.0}}, {3, {12.5, -4.0, 1.25}}},
                         {{7, {1.5, -2.0, 0.3}, {1.6, -2.1, 0.31}}},
                         {{4, {2.0, 1.0, 0.5}, {-3.0, 7.5, -1.0}}}}}};
}

}  // namespace

void write_seeds(Seeds& seeds) {
  for (const Body& body : seed_bodies()) {
    const std::vector<std::uint8_t> bytes = encode(Message{Header{"robot1", "robot2", 1234567, 42}, body});
    seeds.add(std::string(kind_name(kind_of(body))) + ".msg", std::string(bytes.begin(), bytes.end() - 4));
  }
  seeds.dictionary({"DSWM", std::string("DSWM\x01\x00", 6), "robot1", "robot2", "proximity"});
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::vector<std::uint8_t> bytes = fuzz::sealed({data, size});
  // ProtocolError messages name the sender, not a file: nothing to look for.
  // Decoding normalises angles, so the check is on the second round trip.
  fuzz::expect_clean<protocol::ProtocolError>("", [&] {
    const std::vector<std::uint8_t> again = protocol::encode(protocol::decode(bytes));
    const std::vector<std::uint8_t> twice = protocol::encode(protocol::decode(again));
    if (twice == again) return;
    const auto at = std::mismatch(twice.begin(), twice.end(), again.begin(), again.end()).first - twice.begin();
    fuzz::fail("a decoded message encodes differently the second time (" + std::to_string(twice.size()) +
               " bytes instead of " + std::to_string(again.size()) + ", first difference at byte " +
               std::to_string(at) + ")");
  });
  return 0;
}
