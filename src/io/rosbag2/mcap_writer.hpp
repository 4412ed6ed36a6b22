#pragma once
// A small MCAP writer (mcap_format.hpp) for the tests and the test
// converters: ros2 profile, CDR channels, unchunked or chunked (uncompressed,
// zstd, lz4), with message indexes, the summary (schemas, channels,
// statistics, chunk indexes, summary offsets) and every CRC. Schemas carry
// the type name only (no message definition text).
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace dsswarm::mcap {

enum class Chunking { None, Uncompressed, Zstd, Lz4 };

class McapWriter {
 public:
  // Chunks are closed once their records exceed `chunk_bytes`.
  explicit McapWriter(Chunking chunking, std::size_t chunk_bytes = 64 * 1024);

  // The channel of `topic`, created (with a schema for `type`) on first use.
  std::uint16_t channel(const std::string& topic, const std::string& type);
  void message(std::uint16_t channel, std::uint64_t log_time_ns,
               std::span<const std::uint8_t> data);

  // The whole file.
  std::vector<std::uint8_t> finish() &&;

 private:
  struct ChunkIndexEntry {
    std::uint64_t start_time, end_time, offset, length;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length, compressed_size, uncompressed_size;
  };
  std::vector<std::uint8_t>& records() { return chunking_ == Chunking::None ? file_ : chunk_; }
  void flush_chunk();
  std::vector<std::uint8_t> schema_record(std::uint16_t id) const;
  std::vector<std::uint8_t> channel_record(std::uint16_t id) const;
  std::vector<std::uint8_t> statistics_record() const;
  std::vector<std::uint8_t> chunk_index_record(const ChunkIndexEntry& e) const;
  std::uint64_t write_summary();  // returns where its SummaryOffset records start

  Chunking chunking_;
  std::size_t chunk_bytes_;
  std::vector<std::uint8_t> file_;
  std::vector<std::uint8_t> chunk_;  // records of the open chunk, uncompressed
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::vector<ChunkIndexEntry> chunk_indexes_;
  std::map<std::string, std::uint16_t> schema_ids_;  // by type
  std::map<std::string, std::uint16_t> channel_ids_;  // by topic
  std::vector<std::string> schema_names_, channel_topics_;
  std::vector<std::uint16_t> channel_schemas_;
  std::map<std::uint16_t, std::uint64_t> message_counts_;
  std::uint64_t message_count_ = 0, first_time_ = 0, last_time_ = 0;
};

}  // namespace dsswarm::mcap
