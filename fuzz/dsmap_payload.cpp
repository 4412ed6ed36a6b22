// The .dsmap payload (layers, levels, tiles, masses). The input is the
// payload itself; the target frames it as encode_dsmap does (zstd, sizes,
// checksums), so the fuzzer's changes reach the payload checks instead of
// stopping at a checksum.
#include <zstd.h>

#include <stdexcept>

#include "common/errors.hpp"
#include "dsmap_common.hpp"
#include "fuzz_support.hpp"
#include "io/maps/dsmap.hpp"
#include "io/maps/dsmap_frame_util.hpp"

namespace dsswarm::fuzz {
namespace {

using dsmap_test::kDsmapSizesOffset;

std::vector<std::uint8_t> frame(std::span<const std::uint8_t> payload) {
  return dsmap_test::frame_dsmap_payload(payload, kDsmapFormatVersion, 1);
}

// The payload of encoded bytes (their zstd frame, decompressed).
std::string payload_of(const std::vector<std::uint8_t>& bytes) {
  const std::size_t header = kDsmapSizesOffset + 16;
  std::uint64_t size = 0;
  for (int i = 7; i >= 0; --i) size = (size << 8) | bytes[kDsmapSizesOffset + static_cast<std::size_t>(i)];
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
