#pragma once
// A .dsmap file around a hand-made payload, framed as encode_dsmap frames one
// (magic, version, the two CRC-32s, the sizes, zstd): for the tests and the
// payload fuzz target, whose payloads must reach the payload checks past the
// checksums.
#include <zlib.h>
#include <zstd.h>

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace dsswarm::dsmap_test {

inline constexpr std::string_view kDsmapMagic = "DSMAP";
// Where the payload's size sits: after magic, version and the two checksums.
inline constexpr std::size_t kDsmapSizesOffset = kDsmapMagic.size() + 2 + 4 + 4;

inline std::vector<std::uint8_t> frame_dsmap_payload(std::span<const std::uint8_t> payload, std::uint16_t version,
                                                     int zstd_level = 3) {
  std::vector<std::uint8_t> compressed(ZSTD_compressBound(payload.size()));
  compressed.resize(ZSTD_compress(compressed.data(), compressed.size(), payload.data(), payload.size(), zstd_level));
  std::vector<std::uint8_t> out(kDsmapMagic.begin(), kDsmapMagic.end());
  const auto le = [&](std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  le(version, 2);
  le(crc32_z(0, payload.data(), payload.size()), 4);
  le(crc32_z(0, compressed.data(), compressed.size()), 4);
  le(payload.size(), 8);
  le(compressed.size(), 8);
  out.insert(out.end(), compressed.begin(), compressed.end());
  return out;
}

}  // namespace dsswarm::dsmap_test
