// The .dsmap payload (layers, levels, tiles, masses). The input is the
// payload itself; the target frames it as encode_dsmap does (zstd, sizes,
// checksums), so the fuzzer's changes reach the payload checks instead of
// stopping at a checksum.
#include <zlib.h>
#include <zstd.h>

#include <stdexcept>

#include "common/errors.hpp"
#include "dsmap_common.hpp"
#include "fuzz_support.hpp"
#include "io/maps/dsmap.hpp"

namespace dsswarm::fuzz {
namespace {

constexpr std::string_view kMagic = "DSMAP";
constexpr std::size_t kSizesOffset = kMagic.size() + 2 + 4 + 4;  // magic, version, two checksums

std::vector<std::uint8_t> frame(std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> compressed(ZSTD_compressBound(payload.size()));
  compressed.resize(ZSTD_compress(compressed.data(), compressed.size(), payload.data(), payload.size(), 1));
  std::vector<std::uint8_t> out(kMagic.begin(), kMagic.end());
  const auto le = [&](std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  le(kDsmapFormatVersion, 2);
  le(crc32_z(0, payload.data(), payload.size()), 4);
  le(crc32_z(0, compressed.data(), compressed.size()), 4);
  le(payload.size(), 8);
  le(compressed.size(), 8);
  out.insert(out.end(), compressed.begin(), compressed.end());
  return out;
}

// The payload of encoded bytes (their zstd frame, decompressed).
std::string payload_of(const std::vector<std::uint8_t>& bytes) {
  const std::size_t header = kSizesOffset + 16;
  std::uint64_t size = 0;
  for (int i = 7; i >= 0; --i) size = (size << 8) | bytes[kSizesOffset + static_cast<std::size_t>(i)];
  std::string payload(size, '\0');
  const std::size_t got = ZSTD_decompress(payload.data(), payload.size(), bytes.data() + header, bytes.size() - header);
  if (ZSTD_isError(got) || got != size) throw std::runtime_error("cannot decompress a seed");
  return payload;
}

}  // namespace

void write_seeds(Seeds& seeds) {
  for (const auto& [name, snapshot] : dsmap_seed_snapshots()) seeds.add(name + ".payload", payload_of(encode_dsmap(snapshot)));
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::string source = "fuzz.dsmap";
  const std::vector<std::uint8_t> framed = fuzz::frame({data, size});
  fuzz::expect_clean<InputError>(source, [&] { fuzz::check_round_trip(decode_dsmap(framed, source), source); });
  return 0;
}
