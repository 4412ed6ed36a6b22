#pragma once
// Bounded decompression of zstd streams and LZ4 frames (MCAP chunks, rosbag2
// message compression). Output memory grows with the bytes actually produced,
// never with a size a damaged file claims, and never past `max_bytes`.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dsswarm::rosbag2 {

// The whole input, decompressed. Throws InputError starting with `what` for
// damaged or truncated data, or output beyond `max_bytes`.
std::vector<std::uint8_t> zstd_decompress(std::span<const std::uint8_t> in, std::size_t max_bytes,
                                          const std::string& what);
std::vector<std::uint8_t> lz4_frame_decompress(std::span<const std::uint8_t> in,
                                               std::size_t max_bytes, const std::string& what);

}  // namespace dsswarm::rosbag2
