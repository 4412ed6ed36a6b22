// .dsmap decoding refuses what is not a map it wrote: bad headers, payloads
// and pieces, and fuzzed bytes, each with an error naming the file.
#include <gtest/gtest.h>
#include <zlib.h>
#include <zstd.h>

#include <bit>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "common/rng.hpp"
#include "io/maps/dsmap.hpp"
#include "io/maps/dsmap_frame_util.hpp"
#include "io/maps/dsmap_test_util.hpp"
#include "sim/scenario.hpp"

namespace dsswarm {
namespace {

using Bytes = std::vector<std::uint8_t>;
using namespace dsmap_test;

// Hand-made payloads have version 1's layout (no piece counts) unless they say otherwise.
Bytes frame(const Bytes& payload, std::uint16_t version = 1) { return frame_dsmap_payload(payload, version); }

// Hand-made payloads, field by field.
struct PayloadBuilder {
  Bytes b;
  PayloadBuilder& u8(std::uint8_t v) { return le(v, 1); }
  PayloadBuilder& u32(std::uint32_t v) { return le(v, 4); }
  PayloadBuilder& i32(std::int32_t v) { return le(static_cast<std::uint32_t>(v), 4); }
  PayloadBuilder& u64(std::uint64_t v) { return le(v, 8); }
  PayloadBuilder& f32(float v) { return le(std::bit_cast<std::uint32_t>(v), 4); }
  PayloadBuilder& f64(double v) { return le(std::bit_cast<std::uint64_t>(v), 8); }
  PayloadBuilder& str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    b.insert(b.end(), s.begin(), s.end());
    return *this;
  }
  PayloadBuilder& header(double resolution = 0.05, int levels = 1) {
    return f64(resolution).u8(static_cast<std::uint8_t>(levels)).f32(0.4f).f32(0.04f).f32(0.02f).str("s");
  }
  PayloadBuilder& layer_head(int levels = 1, double x = 0.0) {
    return str("o").u64(1).f64(x).f64(0.0).f64(0.0).i32(0).u8(static_cast<std::uint8_t>(levels));
  }
  // One level of tiles at the given tile coordinates, each with one cell set.
  PayloadBuilder& level(const std::vector<std::pair<int, int>>& tiles, std::uint16_t occ = 1000, std::uint16_t fr = 10) {
    u32(static_cast<std::uint32_t>(tiles.size()));
    for (const auto& [x, y] : tiles) i32(x).i32(y);
    for (std::size_t t = 0; t < tiles.size(); ++t)
      for (int i = 0; i < DsGrid::kTileCells; ++i) le(i == 5 ? occ : 0, 2);
    for (std::size_t t = 0; t < tiles.size(); ++t)
      for (int i = 0; i < DsGrid::kTileCells; ++i) le(i == 5 ? fr : 0, 2);
    return *this;
  }

 private:
  PayloadBuilder& le(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    return *this;
  }
};

// The decoder's verdict on `bytes`: "" when it decodes, else the InputError
// message. Anything else thrown (or a crash) fails the test.
std::string verdict(const Bytes& bytes) {
  try {
    decode_dsmap(bytes, "m.dsmap");
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

void expect_rejected(const Bytes& bytes, const std::string& fragment) {
  const std::string v = verdict(bytes);
  EXPECT_NE(v.find("m.dsmap: "), std::string::npos) << "accepted or unnamed: '" << v << "'";
  EXPECT_NE(v.find(fragment), std::string::npos) << "'" << v << "' lacks '" << fragment << "'";
}


TEST(Dsmap, RejectsBadHeaders) {
  const Bytes good = encode_dsmap(two_layer_snapshot());
  Bytes b = good;
  b[0] = 'X';
  expect_rejected(b, "not a .dsmap file");
  expect_rejected(frame(PayloadBuilder().header().u32(0).b, 3),
                  "version 3 is not supported (this build reads versions 1 to 2; it was written by a newer dsswarm)");
  expect_rejected(frame(PayloadBuilder().header().u32(0).b, 0), "version 0 is not supported");
  b = good;
  b[7] ^= 1;  // payload checksum
  expect_rejected(b, "checksum mismatch in the decompressed map");
  b = good;
  b[11] ^= 1;  // compressed checksum
  expect_rejected(b, "checksum mismatch in the compressed map");
  b = good;
  b[good.size() / 2] ^= 1;
  expect_rejected(b, "checksum mismatch in the compressed map");
  b = good;
  b.push_back(0);
  expect_rejected(b, "unexpected bytes after the compressed map");
  b = good;
  b.pop_back();
  expect_rejected(b, "truncated");
  b = good;
  b[22] = 0x7f;  // payload size: absurd
  expect_rejected(b, "implausible");
  b = good;
  b[15] ^= 1;  // payload size off by one: disagrees with the zstd frame
  expect_rejected(b, "the header says");
  expect_rejected(Bytes{'D', 'S', 'M'}, "truncated .dsmap header: magic");
  // Compressed bytes that are not zstd.
  Bytes garbage = frame(PayloadBuilder().header().u32(0).b);
  for (std::size_t i = 31; i < garbage.size(); ++i) garbage[i] = 0x55;
  const std::uint32_t crc = static_cast<std::uint32_t>(crc32_z(0, garbage.data() + 31, garbage.size() - 31));
  for (int i = 0; i < 4; ++i) garbage[11 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(crc >> (8 * i));
  expect_rejected(garbage, "zstd");
}

TEST(Dsmap, RejectsBadPayloads) {
  expect_rejected(frame(PayloadBuilder().header(0.001).u32(0).b), "resolution 0.001000 m is outside");
  expect_rejected(frame(PayloadBuilder().header(std::nan("")).u32(0).b), "resolution");
  expect_rejected(frame(PayloadBuilder().header(0.05, 0).u32(0).b), "level count 0 is outside [1, 6]");
  expect_rejected(frame(PayloadBuilder().header(0.05, 9).u32(0).b), "level count 9");
  expect_rejected(frame(PayloadBuilder().f64(0.05).u8(1).f32(1.5f).f32(0.04f).f32(0.02f).str("s").u32(0).b),
                  "evidence.hit_occupied");
  expect_rejected(frame(PayloadBuilder().header().u32(1000000).b), "1000000 layers cannot fit");
  expect_rejected(frame(PayloadBuilder().header().u32(1).layer_head(1, std::nan("")).level({}).b), "not finite");
  expect_rejected(frame(PayloadBuilder().header(0.05, 2).u32(1).layer_head(1).level({}).level({}).b),
                  "has 1 levels, the header says 2");
  expect_rejected(frame(PayloadBuilder().header().u32(1).layer_head().u32(4000000).b), "4000000 tiles need");
  expect_rejected(frame(PayloadBuilder().header().u32(1).layer_head().level({{0, 0}, {0, 0}}).b), "appears twice");
  expect_rejected(frame(PayloadBuilder().header().u32(1).layer_head().level({{-30000, -30000}, {30000, 30000}}).b),
                  "more than this reader accepts");
  expect_rejected(frame(PayloadBuilder().header().u32(1).layer_head().level({{40000000, 0}}).b), "int32 cell range");
  expect_rejected(frame(PayloadBuilder().header().u32(1).layer_head().level({{0, 0}}, 60000, 6000).b),
                  "occupied + free mass above 1");
  expect_rejected(frame(PayloadBuilder().header().u32(1).layer_head().level({{0, 0}}).u8(0).b),
                  "1 unexpected bytes after the last layer");
  expect_rejected(frame(PayloadBuilder().header().u32(2).layer_head().level({{0, 0}}).b), "truncated payload");
  // The hand-made builder itself makes valid files (so the cases above fail for their stated reason).
  EXPECT_EQ(verdict(frame(PayloadBuilder().header().u32(1).layer_head().level({{-3, 2}, {0, 0}}).b)), "");
}

// A robot with loop closure on sends its finished submaps apart (MapLayer::pieces).

TEST(Dsmap, RejectsBadPieces) {
  auto with_pieces = [](const std::function<void(PayloadBuilder&)>& pieces) {
    PayloadBuilder b;
    b.header().u32(1).layer_head().level({{0, 0}});
    pieces(b);
    return frame(b.b, 2);
  };
  EXPECT_EQ(verdict(with_pieces([](PayloadBuilder& b) {
              b.u32(1).i32(4).f64(1.0).f64(2.0).f64(0.5).u8(1).level({{1, 1}});
            })),
            "");
  expect_rejected(with_pieces([](PayloadBuilder& b) { b.u32(5000000); }), "5000000 pieces cannot fit");
  expect_rejected(with_pieces([](PayloadBuilder& b) { b.u32(1).i32(4).f64(1.0).f64(std::nan("")).f64(0.5).u8(1).level({}); }),
                  "layer 0 ('o') piece 0: pose");
  expect_rejected(with_pieces([](PayloadBuilder& b) { b.u32(1).i32(4).f64(1.0).f64(2.0).f64(0.5).u8(2).level({}); }),
                  "piece 0 has 2 levels, the header says 1");
  expect_rejected(with_pieces([](PayloadBuilder& b) {
                    b.u32(2).i32(4).f64(0.0).f64(0.0).f64(0.0).u8(1).level({}).i32(4).f64(0.0).f64(0.0).f64(0.0).u8(1).level({});
                  }),
                  "piece id 4 appears twice");
  expect_rejected(with_pieces([](PayloadBuilder& b) {
                    b.u32(2).i32(4).f64(0.0).f64(0.0).f64(0.0).u8(1).level({}).i32(5).f64(0.0);
                  }),
                  "2 pieces cannot fit in the 45 bytes");
}

// Garbage must give InputError, never a crash, a hang or a huge allocation
// (run under -DDSSWARM_SANITIZE=ON too). Truncations and byte flips of a
// valid file must all be refused; should one slip through, it must at least
// decode to exactly the original map.
TEST(Dsmap, FuzzedInputsAreRejectedCleanly) {
  MapConfig config;
  config.levels = 2;
  MapSnapshot s;
  s.sender = "f";
  auto map = std::make_shared<MultiResMap>(config);
  map->insert_scan(Pose2(), Pose2(), room_scan(Pose2()));
  s.layers.push_back({"f", 1, Pose2(), 0, map, {}});
  const Bytes good = encode_dsmap(s);
  auto accepted_only_if_identical = [&](const Bytes& b, const std::string& what) {
    try {
      const MapSnapshot back = decode_dsmap(b, "fuzz");
      EXPECT_EQ(encode_dsmap(back), good) << what << " decoded to a different map";
      return 1;
    } catch (const InputError&) {
      return 0;
    }
  };

  int accepted = 0;
  for (std::size_t n = 0; n < good.size(); ++n)
    accepted += accepted_only_if_identical(Bytes(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n)),
                                           "truncation to " + std::to_string(n));
  EXPECT_EQ(accepted, 0) << "a truncated file was accepted";

  Rng rng(11);
  int flips_accepted = 0;  // every byte is covered by a check: none may pass
  for (std::size_t i = 0; i < good.size(); ++i) {
    Bytes b = good;
    b[i] = static_cast<std::uint8_t>(b[i] ^ (1 + static_cast<int>(rng.uniform() * 255)));
    flips_accepted += accepted_only_if_identical(b, "flip at " + std::to_string(i));
  }
  EXPECT_EQ(flips_accepted, 0) << "single-byte flips accepted";

  for (int trial = 0; trial < 3000; ++trial) {
    Bytes b(static_cast<std::size_t>(rng.uniform() * 200));
    for (auto& v : b) v = static_cast<std::uint8_t>(rng.uniform() * 256);
    if (trial % 2 == 0 && b.size() >= 7) {  // past the magic and version, to reach the deeper checks
      std::copy(good.begin(), good.begin() + 7, b.begin());
      if (trial % 4 == 0 && b.size() >= 31) std::copy(good.begin() + 23, good.begin() + 31, b.begin() + 23);
    }
    EXPECT_NE(verdict(b), "") << "random bytes accepted, trial " << trial;
  }
  // Valid compression and checksums around a damaged payload: the payload
  // checks alone must hold (counts, tile origins, masses...).
  Bytes payload(ZSTD_getFrameContentSize(good.data() + 31, good.size() - 31));
  ASSERT_EQ(ZSTD_decompress(payload.data(), payload.size(), good.data() + 31, good.size() - 31), payload.size());
  ASSERT_EQ(verdict(frame(payload, kDsmapFormatVersion)), "");
  for (int trial = 0; trial < 800; ++trial) {
    Bytes p = payload;
    const int flips = 1 + trial % 3;
    for (int f = 0; f < flips; ++f) {
      // Half the damage lands in the first bytes: header, layer fields, tile counts and origins.
      const double span = trial % 2 == 0 ? 120.0 : static_cast<double>(p.size());
      const auto at = std::min(p.size() - 1, static_cast<std::size_t>(rng.uniform() * span));
      p[at] = static_cast<std::uint8_t>(rng.uniform() * 256);
    }
    (void)verdict(frame(p, kDsmapFormatVersion));  // decodes or InputError; anything else fails
  }
  // Valid compression and checksums around a random payload.
  for (int trial = 0; trial < 2000; ++trial) {
    Bytes p = PayloadBuilder().header(0.05, 2).b;
    const auto n = static_cast<std::size_t>(rng.uniform() * 300);
    for (std::size_t i = 0; i < n; ++i) p.push_back(static_cast<std::uint8_t>(rng.uniform() * 256));
    (void)verdict(frame(p, kDsmapFormatVersion));  // accepted or InputError; anything else fails
  }
}

// A realistic map: the simulated building, every other scan inserted at its
// true pose. Prints the size per allocated cell and the zstd ratio.

}  // namespace
}  // namespace dsswarm
