#include "io/rosbag2/mcap_reader.hpp"

#include <fmt/format.h>

#include <array>
#include <cstring>
#include <fstream>
#include <map>

#include "common/errors.hpp"
#include "io/rosbag2/decompress.hpp"
#include "io/rosbag2/mcap_bytes.hpp"
#include "io/rosbag2/mcap_format.hpp"

namespace dsswarm::rosbag2 {
namespace {

using mcap::Fields;
using mcap::FileBytes;
using mcap::load_le;
using mcap::Op;
using mcap::op_name;

class McapParser {
 public:
  McapParser(std::istream& in, std::uint64_t size, const std::string& name,
             const TopicFilter& wanted, const MessageHandler& on_message)
      : file_(in, size, name), wanted_(wanted), on_message_(on_message) {}

  std::vector<StorageTopic> run();

 private:
  struct Prefix {
    Op op;
    std::uint64_t length;
    std::uint64_t offset;  // of the opcode in the file
  };
  Prefix read_prefix();
  std::string where(const Prefix& p) const {
    return fmt::format("{}: {} record at byte {}", file_.name(), op_name(p.op), p.offset);
  }
  std::vector<std::uint8_t> read_content(const Prefix& p, std::uint64_t max_bytes);
  void expect_magic(const char* where);
  bool record(const Prefix& p);  // false after the Footer
  void data_end(const Prefix& p, std::uint32_t computed_crc);
  void footer(const Prefix& p);
  void chunk(const Prefix& p);
  void data_record(Op op, Fields& f);
  void schema(Fields& f);
  void channel(Fields& f);
  void message(Fields& f);

  FileBytes file_;
  const TopicFilter& wanted_;
  const MessageHandler& on_message_;
  bool in_summary_ = false;  // after DataEnd: only structure is checked
  std::map<std::uint16_t, std::string> schemas_;         // id -> type name
  std::map<std::string, StorageTopic> topics_;           // by name (node addresses stay put)
  std::map<std::uint16_t, StorageTopic*> channel_topic_;  // channel id -> its topic
  std::map<std::uint16_t, bool> channel_wanted_;
};

void McapParser::expect_magic(const char* where) {
  std::array<std::uint8_t, sizeof(mcap::kMagic)> magic{};
  if (file_.left() < magic.size()) {
    throw InputError(fmt::format("{}: truncated: the {} magic is missing", file_.name(), where));
  }
  file_.read(magic, "magic");
  if (std::memcmp(magic.data(), mcap::kMagic, magic.size()) != 0) {
    throw InputError(fmt::format("{}: no MCAP magic at the {} (not an MCAP file, or damaged)",
                                 file_.name(), where));
  }
}

McapParser::Prefix McapParser::read_prefix() {
  Prefix p{Op::Header, 0, file_.pos()};
  if (file_.left() == 0) {
    throw InputError(fmt::format("{}: truncated: the file ends at byte {} without a Footer record",
                                 file_.name(), p.offset));
  }
  std::array<std::uint8_t, mcap::kRecordPrefixBytes> bytes{};
  file_.read(bytes, fmt::format("the record at byte {}", p.offset));
  p.op = static_cast<Op>(bytes[0]);
  p.length = load_le<std::uint64_t>(bytes.data() + 1);
  if (p.length > file_.left()) {
    throw InputError(fmt::format("{}: truncated: it claims {} bytes, only {} are left", where(p),
                                 p.length, file_.left()));
  }
  return p;
}

std::vector<std::uint8_t> McapParser::read_content(const Prefix& p, std::uint64_t max_bytes) {
  if (p.length > max_bytes) {
    throw InputError(fmt::format("{}: {} bytes exceed the cap of {}", where(p), p.length,
                                 max_bytes));
  }
  return file_.read_vector(p.length, where(p));
}

std::vector<StorageTopic> McapParser::run() {
  expect_magic("start");
  const Prefix first = read_prefix();
  if (first.op != Op::Header) {
    throw InputError(fmt::format("{}: the first record is not a Header (opcode 0x{:02x})",
                                 file_.name(), static_cast<unsigned>(first.op)));
  }
  const std::vector<std::uint8_t> header_content = read_content(first, 1 << 20);
  Fields header(header_content, where(first));
  header.string("profile");
  header.string("library");
  for (;;) {
    const std::uint32_t crc_before = file_.crc();
    const Prefix p = read_prefix();
    if (p.op == Op::DataEnd) {
      data_end(p, crc_before);
    } else if (!record(p)) {
      break;
    }
  }
  std::vector<StorageTopic> topics;
  for (auto& [name, topic] : topics_) topics.push_back(std::move(topic));
  return topics;
}

bool McapParser::record(const Prefix& p) {
  switch (p.op) {
    case Op::Footer:
      footer(p);
      return false;
    case Op::Header:
      throw InputError(where(p) + ": a second Header record");
    case Op::Chunk:
      if (!in_summary_) {
        chunk(p);
        return true;
      }
      break;
    case Op::Schema:
    case Op::Channel:
    case Op::Message:
      if (!in_summary_) {
        const std::vector<std::uint8_t> content = read_content(p, kMaxMessageBytes + 1024);
        Fields f(content, where(p));
        data_record(p.op, f);
        return true;
      }
      break;
    default:
      break;
  }
  file_.skip(p.length, where(p));  // indexes, attachments, metadata, the summary
  return true;
}

void McapParser::data_end(const Prefix& p, std::uint32_t computed_crc) {
  const std::vector<std::uint8_t> content = read_content(p, 1024);
  Fields f(content, where(p));
  const auto stored = f.number<std::uint32_t>("data_section_crc");
  if (stored != 0 && stored != computed_crc) {
    throw InputError(fmt::format("{}: data section CRC mismatch (recorded {:08x}, the data gives "
                                 "{:08x}): the file is damaged",
                                 where(p), stored, computed_crc));
  }
  in_summary_ = true;
}

void McapParser::footer(const Prefix& p) {
  const std::vector<std::uint8_t> content = read_content(p, 1024);
  Fields f(content, where(p));
  f.number<std::uint64_t>("summary_start");
  f.number<std::uint64_t>("summary_offset_start");
  f.number<std::uint32_t>("summary_crc");
  expect_magic("end");
  if (file_.left() > 0) {
    throw InputError(fmt::format("{}: {} bytes after the closing magic", file_.name(),
                                 file_.left()));
  }
}

void McapParser::chunk(const Prefix& p) {
  const std::string here = where(p);
  const std::vector<std::uint8_t> content = read_content(p, kMaxChunkBytes);
  Fields f(content, here);
  f.number<std::uint64_t>("message_start_time");
  f.number<std::uint64_t>("message_end_time");
  const auto size = f.number<std::uint64_t>("uncompressed_size");
  const auto crc = f.number<std::uint32_t>("uncompressed_crc");
  const std::string compression = f.string("compression");
  const auto records = f.bytes<std::uint64_t>("records");
  if (size > kMaxChunkBytes) {
    throw InputError(fmt::format("{}: uncompressed size {} exceeds the cap of {}", here, size,
                                 kMaxChunkBytes));
  }
  std::vector<std::uint8_t> decompressed;
  if (compression == mcap::kZstd) {
    decompressed = zstd_decompress(records, static_cast<std::size_t>(size), here);
  } else if (compression == mcap::kLz4) {
    decompressed = lz4_frame_decompress(records, static_cast<std::size_t>(size), here);
  } else if (!compression.empty()) {
    throw InputError(fmt::format("{}: compression '{}' is not supported (zstd, lz4 or none)",
                                 here, compression));
  }
  const auto data = compression.empty() ? records : std::span<const std::uint8_t>(decompressed);
  if (data.size() != size) {
    throw InputError(fmt::format("{}: the records are {} bytes, the chunk says {}", here,
                                 data.size(), size));
  }
  if (const std::uint32_t computed = mcap::crc32(data); crc != 0 && computed != crc) {
    throw InputError(fmt::format("{}: CRC mismatch (recorded {:08x}, the records give {:08x}): "
                                 "the chunk is damaged",
                                 here, crc, computed));
  }
  for (std::size_t pos = 0; pos < data.size();) {
    Fields prefix(data.subspan(pos), fmt::format("{}, record at byte {} inside", here, pos));
    const auto op = static_cast<Op>(prefix.number<std::uint8_t>("opcode"));
    const auto record = prefix.bytes<std::uint64_t>("content");
    Fields inner(record, fmt::format("{}: {} record at byte {} inside", here, op_name(op), pos));
    data_record(op, inner);
    pos += mcap::kRecordPrefixBytes + record.size();
  }
}

void McapParser::data_record(Op op, Fields& f) {
  if (op == Op::Schema) schema(f);
  if (op == Op::Channel) channel(f);
  if (op == Op::Message) message(f);
}

void McapParser::schema(Fields& f) {
  const auto id = f.number<std::uint16_t>("id");
  std::string name = f.string("name");
  f.string("encoding");
  f.bytes<std::uint32_t>("data");
  if (id != 0) schemas_[id] = std::move(name);  // id 0 is invalid: ignored, as the spec says
}

void McapParser::channel(Fields& f) {
  const auto id = f.number<std::uint16_t>("id");
  const auto schema_id = f.number<std::uint16_t>("schema_id");
  std::string name = f.string("topic");
  std::string encoding = f.string("message_encoding");
  f.bytes<std::uint32_t>("metadata");
  std::string type;
  if (schema_id != 0) {
    const auto it = schemas_.find(schema_id);
    if (it == schemas_.end()) {
      throw InputError(fmt::format("{}: channel {} ({}) refers to schema {}, which no Schema "
                                   "record before it defines",
                                   f.where(), id, name, schema_id));
    }
    type = it->second;
  }
  StorageTopic& topic = topics_[name];
  topic.name = name;
  topic.encoding = std::move(encoding);
  // Several channels (publishers) may share a topic; list each distinct type once.
  if (topic.type.empty()) {
    topic.type = type;
  } else if (topic.type.find(type) == std::string::npos) {
    topic.type += " | " + type;
  }
  channel_topic_[id] = &topic;
  channel_wanted_[id] = wanted_(name);
}

void McapParser::message(Fields& f) {
  const auto channel = f.number<std::uint16_t>("channel_id");
  f.number<std::uint32_t>("sequence");
  const auto log_time = f.number<std::uint64_t>("log_time");
  f.number<std::uint64_t>("publish_time");
  const auto it = channel_topic_.find(channel);
  if (it == channel_topic_.end()) {
    throw InputError(fmt::format("{}: channel {}, which no Channel record before it defines",
                                 f.where(), channel));
  }
  ++it->second->messages;
  if (channel_wanted_[channel]) {
    on_message_(StoredMessage{*it->second, static_cast<std::int64_t>(log_time), f.rest()});
  }
}

}  // namespace

std::vector<StorageTopic> read_mcap(std::istream& in, std::uint64_t size, const std::string& name,
                                    const TopicFilter& wanted, const MessageHandler& on_message) {
  return McapParser(in, size, name, wanted, on_message).run();
}

std::vector<StorageTopic> read_mcap_file(const std::filesystem::path& path,
                                         const TopicFilter& wanted,
                                         const MessageHandler& on_message) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!in || ec) throw InputError(path.string() + ": cannot open");
  return read_mcap(in, size, path.string(), wanted, on_message);
}

}  // namespace dsswarm::rosbag2
