#pragma once
// Swarm messages as bytes (all integers little-endian, floats IEEE 754):
//
//   "DSWM"  u16 protocol version  u8 kind
//   str sender  str recipient  u64 incarnation  u64 sequence
//   u32 body bytes  <body>  u32 CRC-32 of everything before it
//   (str = u32 byte length + UTF-8 bytes)
//
// Bodies (messages.hpp), field by field in declaration order; a pose is three
// f64 (x, y, θ); a point list is u32 count + count × (f32 x, f32 y, f32
// weight); optionals are a u8 flag (0/1) then the value; lists a u32 count.
//
// decode() checks everything before anything is used: magic, version, kind,
// sizes against the limits, the checksum, names, finite numbers, ratios in
// [0, 1], chunk indices, unique submap ids. A peer's bytes can at worst be refused.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "protocol/messages.hpp"

namespace dsswarm::protocol {

// A message that cannot be used: malformed, too large, another version.
class ProtocolError : public InputError {
 public:
  using InputError::InputError;
};

struct WireLimits {
  std::size_t max_message_bytes = 1 << 20;    // one message (a chunk carries at most ~this)
  std::size_t max_points = 20000;             // per point list of an offer
  // m from the robot: a lidar sees a few hundred at most, surroundings reach
  // 100 (encounter config); further is no scan, and a far point's cell index
  // would overflow where the map is read.
  double max_point_distance = 1000.0;
  // m from the map frame's origin, for any pose: a building-sized map stays
  // far inside it, and cell indices computed from it cannot overflow.
  double max_coordinate = 1.0e6;
  std::size_t max_inventory = 1024;           // layers an offer may list
  std::size_t max_confirmations = 64;
  std::size_t max_text = 1024;                // a decline's reason
  std::size_t max_pieces = 1 << 16;           // submap poses a Moved may carry
  std::size_t max_ties = 4096;                // encounter poses a Moved may carry
  std::size_t max_closures = 8192;            // loop closures a Moved may carry
  std::uint32_t max_chunks = 1 << 16;         // per transfer
  std::uint64_t max_transfer_bytes = 1ull << 30;
};

std::vector<std::uint8_t> encode(const Message& message);

// Throws ProtocolError saying what is wrong (and, once it can be read, who sent it).
Message decode(std::span<const std::uint8_t> bytes, const WireLimits& limits = {});

}  // namespace dsswarm::protocol
