#pragma once
// Snapshot transfers in chunks: a multi-megabyte .dsmap goes out as
// messages well under the transport's comfortable sample size, and comes
// back together only when every chunk is there and the whole checks out.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "protocol/messages.hpp"

namespace dsswarm::protocol {

// The chunks of `bytes` (each at most `chunk_bytes`), all carrying the whole
// transfer's size and CRC-32. Empty `bytes` give one chunk with count 0.
std::vector<Chunk> split_transfer(std::uint64_t encounter, std::span<const std::uint8_t> bytes,
                                  std::size_t chunk_bytes);

// Collects one incoming transfer. Memory is bounded by the transfer's
// declared size, which the caller caps (WireLimits::max_transfer_bytes).
class TransferAssembler {
 public:
  // Adds a chunk; returns true once the transfer is complete. A chunk that
  // contradicts the ones before (another count, size or checksum, a chunk
  // size that cannot add up) throws ProtocolError; a repeated one is ignored.
  bool add(const Chunk& chunk);
  bool complete() const { return started_ && received_ == count_; }
  // The whole transfer, checked against its CRC-32 (ProtocolError if not).
  std::vector<std::uint8_t> take();
  std::size_t bytes_received() const { return bytes_; }

 private:
  bool started_ = false;
  std::uint32_t count_ = 0;
  std::uint64_t total_ = 0;
  std::uint32_t crc_ = 0;
  std::uint32_t received_ = 0;
  std::size_t bytes_ = 0;
  std::vector<std::vector<std::uint8_t>> parts_;
};

}  // namespace dsswarm::protocol
