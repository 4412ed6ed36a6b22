#include "protocol/transfer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "protocol/wire.hpp"

namespace dsswarm::protocol {
namespace {

std::vector<std::uint8_t> bytes_of(std::size_t n) {
  std::vector<std::uint8_t> b(n);
  for (std::size_t i = 0; i < n; ++i) b[i] = static_cast<std::uint8_t>(i * 7 + i / 256);
  return b;
}

TEST(Transfer, ChunksInAnyOrderAndRepeatedComeBackWhole) {
  const auto data = bytes_of(10000);
  std::vector<Chunk> chunks = split_transfer(5, data, 3000);
  ASSERT_EQ(chunks.size(), 4u);
  EXPECT_EQ(chunks.back().data.size(), 1000u);
  std::reverse(chunks.begin(), chunks.end());
  TransferAssembler a;
  EXPECT_FALSE(a.add(chunks[0]));
  EXPECT_FALSE(a.add(chunks[0]));  // a repeat changes nothing
  EXPECT_FALSE(a.add(chunks[1]));
  EXPECT_FALSE(a.add(chunks[2]));
  EXPECT_TRUE(a.add(chunks[3]));
  EXPECT_EQ(a.take(), data);
}

TEST(Transfer, NothingToSendIsOneEmptyChunk) {
  const std::vector<Chunk> chunks = split_transfer(5, {}, 3000);
  ASSERT_EQ(chunks.size(), 1u);
  EXPECT_EQ(chunks[0].count, 0u);
  TransferAssembler a;
  EXPECT_TRUE(a.add(chunks[0]));
  EXPECT_TRUE(a.take().empty());
}

TEST(Transfer, ContradictoryOrCorruptChunksAreRefused) {
  const auto data = bytes_of(9000);
  const std::vector<Chunk> chunks = split_transfer(5, data, 3000);
  {
    TransferAssembler a;
    a.add(chunks[0]);
    Chunk other = chunks[1];
    other.count = 9;
    EXPECT_THROW(a.add(other), ProtocolError);
  }
  {
    TransferAssembler a;
    Chunk fat = chunks[0];
    fat.data.resize(8000);
    a.add(fat);
    EXPECT_THROW(a.add(chunks[1]), ProtocolError);  // more than declared
  }
  {
    TransferAssembler a;
    std::vector<Chunk> bad = chunks;
    bad[1].data[10] ^= 1;
    for (const Chunk& c : bad) a.add(c);
    EXPECT_THROW(a.take(), ProtocolError);  // the whole fails its checksum
  }
  {
    TransferAssembler a;
    Chunk empty = chunks[0];
    empty.data.clear();
    EXPECT_THROW(a.add(empty), ProtocolError);
  }
}

}  // namespace
}  // namespace dsswarm::protocol
