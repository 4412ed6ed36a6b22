// Damaged, truncated and foreign storage files: each an InputError naming
// the file, never a crash, a hang or a huge allocation.
#include "io/rosbag2/mcap_reader.hpp"

#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "io/rosbag2/mcap_format.hpp"
#include "io/rosbag2/mcap_writer.hpp"
#include "io/rosbag2/rosbag2_test_util.hpp"

namespace dsswarm::rosbag2_test {
namespace {

struct Record {
  mcap::Op op;
  std::size_t offset;  // of the opcode
  std::size_t length;  // of the content
};

std::uint64_t le64(const std::string& bytes, std::size_t at) {
  std::uint64_t v = 0;
  for (std::size_t i = 8; i-- > 0;) v = (v << 8) | static_cast<unsigned char>(bytes.at(at + i));
  return v;
}

void put_le64(std::string& bytes, std::size_t at, std::uint64_t v) {
  for (std::size_t i = 0; i < 8; ++i) bytes.at(at + i) = static_cast<char>(v >> (8 * i));
}

// The top-level records of a well-formed MCAP file.
std::vector<Record> records_of(const std::string& bytes) {
  std::vector<Record> out;
  for (std::size_t pos = 8; pos + 9 <= bytes.size() - 8;) {
    const auto length = static_cast<std::size_t>(le64(bytes, pos + 1));
    out.push_back({static_cast<mcap::Op>(bytes[pos]), pos, length});
    pos += 9 + length;
  }
  return out;
}

Record first(const std::vector<Record>& records, mcap::Op op) {
  for (const Record& r : records) {
    if (r.op == op) return r;
  }
  ADD_FAILURE() << "no record of opcode " << static_cast<int>(op);
  return {};
}

// A bag folder in `format`; returns its storage file and that file's bytes.
std::pair<fs::path, std::string> bag_file(const std::string& name, Format format) {
  WriteOptions options;
  options.format = format;
  options.chunk_bytes = 100000;  // one chunk
  const fs::path dir = write_test_bag(name, small_recording(), options);
  const fs::path file = dir / (name + (format == Format::Db3 ? "_0.db3" : "_0.mcap"));
  return {file, read_file_bytes(file)};
}

std::string error_for(const fs::path& file, const std::string& bytes) {
  write_file_bytes(file, bytes);
  return input_error_of(file.parent_path());
}

TEST(McapReader, TheTestWriterWritesWhatTheSpecificationDescribes) {
  const auto [file, bytes] = bag_file("spec", Format::McapZstd);
  ASSERT_EQ(bytes.substr(0, 8), std::string("\x89MCAP0\r\n", 8));
  ASSERT_EQ(bytes.substr(bytes.size() - 8), std::string("\x89MCAP0\r\n", 8));
  std::vector<mcap::Op> ops;
  for (const Record& r : records_of(bytes)) ops.push_back(r.op);
  using mcap::Op;
  // Header, the chunk with the message indexes of its four topics, DataEnd,
  // the summary grouped by opcode (3 types, 4 topics), its offsets, Footer.
  const std::vector<Op> expected{Op::Header,  Op::Chunk,   Op::MessageIndex, Op::MessageIndex,
                                 Op::MessageIndex, Op::MessageIndex, Op::DataEnd, Op::Schema,
                                 Op::Schema,  Op::Schema,  Op::Channel,      Op::Channel,
                                 Op::Channel, Op::Channel, Op::Statistics,   Op::ChunkIndex,
                                 Op::SummaryOffset, Op::SummaryOffset, Op::SummaryOffset,
                                 Op::SummaryOffset, Op::Footer};
  EXPECT_EQ(ops, expected);
  const Record footer = first(records_of(bytes), Op::Footer);
  EXPECT_EQ(footer.length, 20U);
  EXPECT_EQ(le64(bytes, footer.offset + 9), first(records_of(bytes), Op::Schema).offset);
}

TEST(McapReader, TruncatedFilesAreInputErrorsNamingTheFile) {
  for (const Format format : {Format::McapUnchunked, Format::McapZstd, Format::McapLz4}) {
    const auto [file, bytes] = bag_file("truncated", format);
    for (std::size_t keep = 0; keep < bytes.size(); keep += 23) {
      const std::string message = error_for(file, bytes.substr(0, keep));
      EXPECT_NE(message.find(file.string()), std::string::npos) << keep << ": " << message;
    }
  }
}

TEST(McapReader, DamagedChunksAreCaughtByCrcOrDecompression) {
  for (const Format format : {Format::McapChunked, Format::McapZstd, Format::McapLz4}) {
    SCOPED_TRACE(format_name(format));
    const auto [file, good] = bag_file("damaged_chunk", format);
    const Record chunk = first(records_of(good), mcap::Op::Chunk);
    std::string bytes = good;
    // A byte in the middle of the (compressed) records.
    bytes[chunk.offset + 9 + chunk.length / 2] ^= 0x10;
    const std::string message = error_for(file, bytes);
    EXPECT_NE(message.find(file.string() + ": Chunk record at byte " +
                           std::to_string(chunk.offset)),
              std::string::npos)
        << message;
    const bool caught = message.find("CRC mismatch") != std::string::npos ||
                        message.find("damaged") != std::string::npos;
    EXPECT_TRUE(caught) << message;
  }
}

TEST(McapReader, DamagedUnchunkedDataFailsTheDataSectionCrc) {
  const auto [file, good] = bag_file("damaged_data", Format::McapUnchunked);
  const Record message_record = first(records_of(good), mcap::Op::Message);
  std::string bytes = good;
  bytes[message_record.offset + 9 + message_record.length - 1] ^= 0x01;  // last range byte
  const std::string message = error_for(file, bytes);
  EXPECT_NE(message.find("data section CRC mismatch"), std::string::npos) << message;
}

TEST(McapReader, ChunkSizesAreCheckedBeforeAllocating) {
  const auto [file, good] = bag_file("chunk_sizes", Format::McapZstd);
  const Record chunk = first(records_of(good), mcap::Op::Chunk);
  const std::size_t uncompressed_size_at = chunk.offset + 9 + 16;
  std::string bytes = good;
  put_le64(bytes, uncompressed_size_at, std::uint64_t{1} << 40);
  EXPECT_NE(error_for(file, bytes).find("exceeds the cap"), std::string::npos);
  // Claiming more than is there, or less: decompression stops at the claim.
  const std::uint64_t real = le64(good, uncompressed_size_at);
  put_le64(bytes, uncompressed_size_at, real + 100000);
  EXPECT_NE(error_for(file, bytes).find("the records are"), std::string::npos);
  put_le64(bytes, uncompressed_size_at, real - 1);
  EXPECT_NE(error_for(file, bytes).find("decompresses to more than"), std::string::npos);
  // A record length past the end of the file.
  bytes = good;
  put_le64(bytes, chunk.offset + 1, std::uint64_t{1} << 62);
  EXPECT_NE(error_for(file, bytes).find("truncated: it claims"), std::string::npos);
}

TEST(McapReader, UnsupportedCompressionIsNamed) {
  const auto [file, good] = bag_file("compression_name", Format::McapZstd);
  std::string bytes = good;
  bytes.replace(bytes.find("zstd"), 4, "bz2!");
  const std::string message = error_for(file, bytes);
  EXPECT_NE(message.find("compression 'bz2!' is not supported (zstd, lz4 or none)"),
            std::string::npos)
      << message;
}

TEST(McapReader, MessagesNeedTheirChannelFirst) {
  mcap::McapWriter writer(mcap::Chunking::None);
  writer.message(writer.channel("/scan", "sensor_msgs/msg/LaserScan"), 1,
                 std::vector<std::uint8_t>{1, 2, 3});
  const std::vector<std::uint8_t> written = std::move(writer).finish();
  std::string bytes(written.begin(), written.end());
  const Record message = first(records_of(bytes), mcap::Op::Message);
  bytes[message.offset + 9] = 9;  // channel id 9
  std::istringstream in(bytes);
  try {
    rosbag2::read_mcap(in, bytes.size(), "x.mcap", [](const std::string&) { return true; },
              [](const rosbag2::StoredMessage&) {});
    ADD_FAILURE() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("x.mcap: Message record at byte " +
                                         std::to_string(message.offset) +
                                         ": channel 9, which no Channel record before it defines"),
              std::string::npos)
        << e.what();
  }
}

TEST(McapReader, FilesOfOtherKindsAreInputErrors) {
  const fs::path dir = test::fresh_dir("rosbag2/foreign");
  write_file_bytes(dir / "text.mcap", "# just text, long enough to be read as records\n");
  EXPECT_NE(input_error_of(dir / "text.mcap").find("no MCAP magic at the start"),
            std::string::npos);
  write_file_bytes(dir / "text.db3", std::string(4096, 'x'));
  const std::string message = input_error_of(dir / "text.db3");
  EXPECT_NE(message.find((dir / "text.db3").string()), std::string::npos) << message;
  EXPECT_NE(message.find("file is not a database"), std::string::npos) << message;
  write_file_bytes(dir / "empty.db3", "");
  EXPECT_NE(input_error_of(dir / "empty.db3").find("not a rosbag2 SQLite database"),
            std::string::npos);
  write_file_bytes(dir / "scans.txt", "FLASER 1 1.0\n");
  EXPECT_NE(input_error_of(dir / "scans.txt").find("not a ROS 2 bag"), std::string::npos);
  EXPECT_NE(input_error_of(dir / "none.mcap").find("no such file"), std::string::npos);
}

TEST(Db3Reader, TruncatedAndDamagedDatabasesAreInputErrors) {
  const auto [file, good] = bag_file("damaged_db3", Format::Db3);
  ASSERT_GT(good.size(), 8192U);
  for (std::size_t keep = 0; keep < good.size(); keep += 1024) {
    const std::string message = error_for(file, good.substr(0, keep));
    EXPECT_NE(message.find(file.string()), std::string::npos) << keep << ": " << message;
  }
  std::string bytes = good;
  for (std::size_t i = 4096; i < bytes.size(); i += 7) bytes[i] = static_cast<char>(i);
  const std::string message = error_for(file, bytes);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
}

TEST(McapReader, RandomDamageGivesInputErrorsNeverCrashes) {
  const auto [file, good] = bag_file("random_damage", Format::McapLz4);
  std::mt19937 rng(7);
  std::size_t errors = 0;
  for (int round = 0; round < 300; ++round) {
    std::string bytes = good;
    for (int flips = 0; flips < 1 + round % 4; ++flips) {
      bytes[rng() % bytes.size()] = static_cast<char>(rng());
    }
    write_file_bytes(file, bytes);
    try {
      read_rosbag2(file);
    } catch (const InputError&) {
      ++errors;
    }
  }
  EXPECT_GT(errors, 250U);  // the CRCs catch nearly every change
}

}  // namespace
}  // namespace dsswarm::rosbag2_test
