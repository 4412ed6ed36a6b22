#include "io/rosbag2/mcap_writer.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <stdexcept>
#include <tuple>

#include "io/rosbag2/mcap_bytes.hpp"
#include "io/rosbag2/mcap_format.hpp"

namespace dsswarm::mcap {
namespace {

using Bytes = std::vector<std::uint8_t>;

template <typename T>
void put(Bytes& out, T v) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
}
void put_bytes(Bytes& out, std::span<const std::uint8_t> bytes) {
  out.insert(out.end(), bytes.begin(), bytes.end());
}
void put_string(Bytes& out, const std::string& s) {
  put(out, static_cast<std::uint32_t>(s.size()));
  out.insert(out.end(), s.begin(), s.end());
}
void put_record(Bytes& out, Op op, const Bytes& content) {
  out.push_back(static_cast<std::uint8_t>(op));
  put(out, static_cast<std::uint64_t>(content.size()));
  put_bytes(out, content);
}

Bytes compress(Chunking chunking, const Bytes& in) {
  Bytes out;
  if (chunking == Chunking::Zstd) {
    out.resize(ZSTD_compressBound(in.size()));
    const std::size_t n = ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 3);
    if (ZSTD_isError(n)) throw std::runtime_error("zstd compression failed");
    out.resize(n);
  } else if (chunking == Chunking::Lz4) {
    out.resize(LZ4F_compressFrameBound(in.size(), nullptr));
    const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr);
    if (LZ4F_isError(n)) throw std::runtime_error("lz4 compression failed");
    out.resize(n);
  } else {
    out = in;
  }
  return out;
}

const char* compression_name(Chunking chunking) {
  return chunking == Chunking::Zstd ? kZstd : chunking == Chunking::Lz4 ? kLz4 : "";
}

}  // namespace

McapWriter::McapWriter(Chunking chunking, std::size_t chunk_bytes)
    : chunking_(chunking), chunk_bytes_(chunk_bytes) {
  file_.assign(std::begin(kMagic), std::end(kMagic));
  Bytes header;
  put_string(header, "ros2");
  put_string(header, "dsswarm test writer");
  put_record(file_, Op::Header, header);
}

Bytes McapWriter::schema_record(std::uint16_t id) const {
  Bytes content;
  put(content, id);
  put_string(content, schema_names_.at(id - 1U));
  put_string(content, "");  // no schema encoding: no definition text
  put(content, std::uint32_t{0});
  return content;
}

Bytes McapWriter::channel_record(std::uint16_t id) const {
  Bytes content;
  put(content, id);
  put(content, channel_schemas_.at(id));
  put_string(content, channel_topics_.at(id));
  put_string(content, "cdr");
  Bytes metadata;  // what rosbag2 writes: the QoS profiles (none here)
  put_string(metadata, "offered_qos_profiles");
  put_string(metadata, "");
  put(content, static_cast<std::uint32_t>(metadata.size()));
  put_bytes(content, metadata);
  return content;
}

std::uint16_t McapWriter::channel(const std::string& topic, const std::string& type) {
  if (const auto it = channel_ids_.find(topic); it != channel_ids_.end()) return it->second;
  const auto next_schema = static_cast<std::uint16_t>(schema_ids_.size() + 1);  // ids from 1
  auto [schema, is_new] = schema_ids_.emplace(type, next_schema);
  if (is_new) {
    schema_names_.push_back(type);
    put_record(records(), Op::Schema, schema_record(schema->second));
  }
  const auto id = static_cast<std::uint16_t>(channel_topics_.size());
  channel_ids_[topic] = id;
  channel_topics_.push_back(topic);
  channel_schemas_.push_back(schema->second);
  put_record(records(), Op::Channel, channel_record(id));
  return id;
}

void McapWriter::message(std::uint16_t channel, std::uint64_t log_time_ns,
                         std::span<const std::uint8_t> data) {
  Bytes content;
  put(content, channel);
  put(content, static_cast<std::uint32_t>(message_counts_[channel]));  // sequence
  put(content, log_time_ns);
  put(content, log_time_ns);  // publish time
  put_bytes(content, data);
  if (chunking_ != Chunking::None) {
    if (chunk_index_.empty()) chunk_start_ = chunk_end_ = log_time_ns;  // its first message
    chunk_index_[channel].emplace_back(log_time_ns, chunk_.size());
    chunk_start_ = std::min(chunk_start_, log_time_ns);
    chunk_end_ = std::max(chunk_end_, log_time_ns);
  }
  put_record(records(), Op::Message, content);
  ++message_counts_[channel];
  first_time_ = message_count_ == 0 ? log_time_ns : std::min(first_time_, log_time_ns);
  last_time_ = std::max(last_time_, log_time_ns);
  ++message_count_;
  if (chunking_ != Chunking::None && chunk_.size() >= chunk_bytes_) flush_chunk();
}

void McapWriter::flush_chunk() {
  if (chunk_.empty()) return;
  const Bytes compressed = compress(chunking_, chunk_);
  Bytes content;
  put(content, chunk_start_);
  put(content, chunk_end_);
  put(content, static_cast<std::uint64_t>(chunk_.size()));
  put(content, crc32(chunk_));
  put_string(content, compression_name(chunking_));
  put(content, static_cast<std::uint64_t>(compressed.size()));
  put_bytes(content, compressed);
  ChunkIndexEntry entry{chunk_start_, chunk_end_, file_.size(), 0, {}, 0, compressed.size(),
                        chunk_.size()};
  put_record(file_, Op::Chunk, content);
  entry.length = file_.size() - entry.offset;
  const std::uint64_t indexes_start = file_.size();
  for (const auto& [channel, entries] : chunk_index_) {
    Bytes index;
    put(index, channel);
    put(index, static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [time, offset] : entries) {
      put(index, time);
      put(index, offset);
    }
    entry.message_index_offsets[channel] = file_.size();
    put_record(file_, Op::MessageIndex, index);
  }
  entry.message_index_length = file_.size() - indexes_start;
  chunk_indexes_.push_back(entry);
  chunk_.clear();
  chunk_index_.clear();
}

Bytes McapWriter::statistics_record() const {
  Bytes statistics;
  put(statistics, message_count_);
  put(statistics, static_cast<std::uint16_t>(schema_names_.size()));
  put(statistics, static_cast<std::uint32_t>(channel_topics_.size()));
  put(statistics, std::uint32_t{0});  // attachments
  put(statistics, std::uint32_t{0});  // metadata
  put(statistics, static_cast<std::uint32_t>(chunk_indexes_.size()));
  put(statistics, first_time_);
  put(statistics, last_time_);
  put(statistics, static_cast<std::uint32_t>(message_counts_.size() * 10));
  for (const auto& [channel, count] : message_counts_) {
    put(statistics, channel);
    put(statistics, count);
  }
  return statistics;
}

Bytes McapWriter::chunk_index_record(const ChunkIndexEntry& e) const {
  Bytes c;
  put(c, e.start_time);
  put(c, e.end_time);
  put(c, e.offset);
  put(c, e.length);
  put(c, static_cast<std::uint32_t>(e.message_index_offsets.size() * 10));
  for (const auto& [channel, offset] : e.message_index_offsets) {
    put(c, channel);
    put(c, offset);
  }
  put(c, e.message_index_length);
  put_string(c, compression_name(chunking_));
  put(c, e.compressed_size);
  put(c, e.uncompressed_size);
  return c;
}

std::uint64_t McapWriter::write_summary() {
  // Grouped by opcode, each group listed in a SummaryOffset record.
  std::vector<std::tuple<Op, std::uint64_t, std::uint64_t>> groups;
  const auto group = [&](Op op, const std::vector<Bytes>& contents) {
    if (contents.empty()) return;
    const std::uint64_t start = file_.size();
    for (const Bytes& c : contents) put_record(file_, op, c);
    groups.emplace_back(op, start, file_.size() - start);
  };
  std::vector<Bytes> schemas, channels, chunk_indexes;
  for (std::size_t id = 1; id <= schema_names_.size(); ++id) {
    schemas.push_back(schema_record(static_cast<std::uint16_t>(id)));
  }
  for (std::size_t id = 0; id < channel_topics_.size(); ++id) {
    channels.push_back(channel_record(static_cast<std::uint16_t>(id)));
  }
  for (const ChunkIndexEntry& e : chunk_indexes_) chunk_indexes.push_back(chunk_index_record(e));
  group(Op::Schema, schemas);
  group(Op::Channel, channels);
  group(Op::Statistics, {statistics_record()});
  group(Op::ChunkIndex, chunk_indexes);
  const std::uint64_t offsets_start = file_.size();
  for (const auto& [op, start, length] : groups) {
    Bytes c;
    put(c, static_cast<std::uint8_t>(op));
    put(c, start);
    put(c, length);
    put_record(file_, Op::SummaryOffset, c);
  }
  return offsets_start;
}

std::vector<std::uint8_t> McapWriter::finish() && {
  flush_chunk();
  Bytes data_end;
  put(data_end, crc32(file_));  // everything so far, magic included
  put_record(file_, Op::DataEnd, data_end);
  const std::uint64_t summary_start = file_.size();
  const std::uint64_t offsets_start = write_summary();
  Bytes footer;
  put(footer, summary_start);
  put(footer, offsets_start);
  file_.push_back(static_cast<std::uint8_t>(Op::Footer));
  put(file_, std::uint64_t{20});
  put_bytes(file_, footer);
  // The summary CRC covers the summary, the summary offsets and the footer up to this field.
  put(file_, crc32(std::span(file_).subspan(summary_start)));
  file_.insert(file_.end(), std::begin(kMagic), std::end(kMagic));
  return std::move(file_);
}

}  // namespace dsswarm::mcap
