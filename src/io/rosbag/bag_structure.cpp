// Format reference: http://wiki.ros.org/Bags/Format/2.0. A bag is the line
// "#ROSBAG V2.0\n" followed by records: <u32 header_len><header><u32
// data_len><data>, the header being fields <u32 len>name=value. Top level:
// the bag header (index_pos, conn_count, chunk_count), chunks each followed by
// one index-data record per connection in it, then (at index_pos) the
// connection records and the chunk-info records. Chunks hold message-data and
// connection records. All integers are little-endian.
#include "io/rosbag/bag_structure.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <istream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "io/rosbag/bag_chunk.hpp"
#include "io/rosbag/bag_fields.hpp"

namespace dsswarm::rosbag_raw {
namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;
constexpr std::uint32_t kMaxHeaderSize = 1U << 24;  // headers are a few hundred bytes
constexpr std::size_t kRecordLengthFields = 8;      // header_len + data_len

enum Op : std::uint8_t {
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};

class StructureCheck {
 public:
  StructureCheck(std::istream& in, std::string path) : path_(std::move(path)), in_(in) {}

  void run() {
    in_.seekg(0, std::ios::end);
    file_size_ = static_cast<std::uint64_t>(in_.tellg());
    in_.seekg(0);
    std::string magic(kMagicSize, '\0');
    if (file_size_ < kMagicSize || !read_exact(0, magic.data(), kMagicSize) || magic != kMagic) {
      // rosbag_storage would read any other version line ("#ROSBAG V1.2", but
      // also "#ROSBAG V2. 0" as 2.0) without these checks.
      if (magic.rfind("#ROSBAG V", 0) == 0) {
        std::string line(static_cast<std::size_t>(std::min<std::uint64_t>(file_size_, 40)), '\0');
        read_exact(0, line.data(), line.size());
        throw InputError(path_ + ": ROS1 bag format \"" + printable(line.substr(0, line.find('\n'))) +
                         "\" is not supported (only \"#ROSBAG V2.0\"; rewrite the bag with a current "
                         "rosbag, e.g. `rosbag filter old.bag new.bag True`)");
      }
      throw InputError(path_ + ": not a ROS1 bag (the file does not start with \"#ROSBAG V2.0\")");
    }
    for (std::uint64_t pos = kMagicSize; pos < file_size_;) pos = top_level_record(pos);
    check_index();
  }

 private:
  struct Record {
    std::uint64_t pos = 0;
    std::uint8_t op = 0;
  };

  [[noreturn]] void damaged(const std::string& what, std::uint64_t pos) const {
    damaged_record(path_, what, pos);
  }

  bool read_exact(std::uint64_t pos, char* out, std::size_t n) {
    in_.seekg(static_cast<std::streamoff>(pos));
    in_.read(out, static_cast<std::streamsize>(n));
    return static_cast<std::size_t>(in_.gcount()) == n;
  }

  // Reads the record at `pos` (header into `fields`, data into `data`),
  // returns the position after it.
  std::uint64_t read_record(std::uint64_t pos, Fields& fields, std::uint8_t& op,
                            std::string& data) {
    char len[4];
    if (file_size_ - pos < 4 || !read_exact(pos, len, 4)) truncated(pos);
    const std::uint32_t header_len = le32(len);
    if (header_len > kMaxHeaderSize)
      damaged("implausible header length " + std::to_string(header_len), pos);
    if (file_size_ - pos < std::uint64_t{header_len} + kRecordLengthFields) truncated(pos);
    std::string header(header_len, '\0');
    if (!read_exact(pos + 4, header.data(), header_len) ||
        !read_exact(pos + 4 + header_len, len, 4))
      truncated(pos);
    const std::uint32_t data_len = le32(len);
    const std::uint64_t data_pos = pos + kRecordLengthFields + header_len;
    if (file_size_ - data_pos < data_len) truncated(pos);
    if (!parse_fields(header.data(), header.size(), fields))
      damaged("malformed record header", pos);
    op = op_of(fields, pos);
    data.assign(data_len, '\0');
    if (!read_exact(data_pos, data.data(), data_len)) truncated(pos);
    return data_pos + data_len;
  }

  [[noreturn]] void truncated(std::uint64_t pos) const {
    throw InputError(path_ + ": truncated ROS1 bag: the record at byte " + std::to_string(pos) +
                     " runs past the end of the file (" + std::to_string(file_size_) + " bytes)");
  }

  std::uint8_t op_of(const Fields& fields, std::uint64_t pos) const {
    const auto it = fields.find("op");
    if (it == fields.end() || it->second.size() != 1)
      damaged("record without a valid op field", pos);
    return static_cast<std::uint8_t>(it->second[0]);
  }

  std::uint64_t field(const Fields& fields, const char* name, std::size_t size,
                      std::uint64_t pos) const {
    return fixed_size_field(path_, fields, name, size, pos);
  }

  std::uint64_t top_level_record(std::uint64_t pos) {
    Fields fields;
    std::uint8_t op = 0;
    std::string data;
    const std::uint64_t next = read_record(pos, fields, op, data);
    if (records_.empty() && op != kBagHeader)
      damaged("the first record is not the bag header", pos);
    records_.push_back({pos, op});
    switch (op) {
      case kBagHeader:
        if (records_.size() != 1) damaged("a second bag header", pos);
        index_pos_ = field(fields, "index_pos", 8, pos);
        connection_count_ = field(fields, "conn_count", 4, pos);
        chunk_count_ = field(fields, "chunk_count", 4, pos);
        if (index_pos_ == 0) {
          throw InputError(path_ +
                           ": unindexed ROS1 bag (the recording was not closed properly; "
                           "`rosbag reindex` can repair it)");
        }
        break;
      case kChunk:
        chunk(fields, data, pos);
        break;
      case kIndexData:
        index_data(fields, data, pos);
        break;
      case kConnection:
        connection(fields, data, pos, true);
        break;
      case kChunkInfo:
        chunk_info(fields, data, pos);
        break;
      default:
        break;  // rosbag_storage never reads other top-level records
    }
    return next;
  }

  void connection(const Fields& fields, const std::string& data, std::uint64_t pos,
                  bool top_level) {
    const auto id = static_cast<std::uint32_t>(field(fields, "conn", 4, pos));
    const auto topic = fields.find("topic");
    if (topic == fields.end() || topic->second.empty()) damaged("connection without a topic", pos);
    Fields connection_header;
    if (!parse_fields(data.data(), data.size(), connection_header))
      damaged("malformed connection header", pos);
    if (top_level) connection_ids_.insert(id);
  }

  // Walks the records inside a chunk; remembers where index offsets may point.
  void chunk(const Fields& fields, const std::string& data, std::uint64_t pos) {
    const std::vector<char> bytes = decompress_chunk(path_, fields, data, pos);
    chunk_pos_ = pos;
    message_offsets_.clear();
    std::vector<std::pair<std::uint32_t, std::uint8_t>> inner;  // offset, op
    for (std::size_t at = 0; at < bytes.size();) {
      const std::string where = "record at byte " + std::to_string(at) + " of the chunk";
      if (bytes.size() - at < kRecordLengthFields) damaged(where + " is cut off", pos);
      const std::uint32_t header_len = le32(bytes.data() + at);
      if (bytes.size() - at - kRecordLengthFields < header_len) damaged(where + " is cut off", pos);
      Fields inner_fields;
      if (!parse_fields(bytes.data() + at + 4, header_len, inner_fields))
        damaged(where + " has a malformed header", pos);
      const std::size_t data_at = at + kRecordLengthFields + header_len;
      const std::uint32_t data_len = le32(bytes.data() + at + 4 + header_len);
      if (bytes.size() - data_at < data_len) damaged(where + " is cut off", pos);
      const std::uint8_t op = op_of(inner_fields, pos);
      if (op == kMessageData) {
        message_connections_.insert(
            static_cast<std::uint32_t>(field(inner_fields, "conn", 4, pos)));
        field(inner_fields, "time", 8, pos);
      } else if (op == kConnection) {
        connection(inner_fields, std::string(bytes.data() + data_at, data_len), pos, false);
      } else {
        damaged(where + " has the unexpected op " + std::to_string(op), pos);
      }
      inner.emplace_back(static_cast<std::uint32_t>(at), op);
      at = data_at + data_len;
    }
    // rosbag_storage reads from an index offset on through connection
    // records until a message: valid offsets are messages and runs of
    // connection records that end in a message.
    bool message_follows = false;
    for (auto it = inner.rbegin(); it != inner.rend(); ++it) {
      if (it->second == kMessageData) message_follows = true;
      if (message_follows) message_offsets_.insert(it->first);
    }
    index_records_after_chunk_[pos] = 0;
  }

  void index_data(const Fields& fields, const std::string& data, std::uint64_t pos) {
    if (field(fields, "ver", 4, pos) != 1) damaged("unsupported index version", pos);
    index_connections_.insert(static_cast<std::uint32_t>(field(fields, "conn", 4, pos)));
    const std::uint64_t count = field(fields, "count", 4, pos);
    if (data.size() != count * 12) damaged("index data length disagrees with its count", pos);
    if (records_.size() < 2 || (records_[records_.size() - 2].op != kChunk &&
                                records_[records_.size() - 2].op != kIndexData)) {
      damaged("index data that does not follow a chunk", pos);
    }
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t offset = le32(data.data() + 12 * i + 8);
      if (message_offsets_.count(offset) == 0) {
        damaged("index entry " + std::to_string(i) + " points to byte " + std::to_string(offset) +
                    " of its chunk, where no message starts",
                pos);
      }
    }
    ++index_records_after_chunk_[chunk_pos_];
  }

  void chunk_info(const Fields& fields, const std::string& data, std::uint64_t pos) {
    if (field(fields, "ver", 4, pos) != 1) damaged("unsupported chunk info version", pos);
    const std::uint64_t chunk_pos = field(fields, "chunk_pos", 8, pos);
    field(fields, "start_time", 8, pos);
    field(fields, "end_time", 8, pos);
    const std::uint64_t count = field(fields, "count", 4, pos);
    if (data.size() != count * 8) damaged("chunk info length disagrees with its count", pos);
    chunk_infos_.emplace_back(pos, std::make_pair(chunk_pos, count));
  }

  // What rosbag_storage reads at open: conn_count connection records and
  // chunk_count chunk-info records from index_pos on, then for each chunk its
  // index records.
  void check_index() {
    if (records_.empty()) truncated(kMagicSize);
    const auto at = std::find_if(records_.begin(), records_.end(),
                                 [&](const Record& r) { return r.pos == index_pos_; });
    if (at == records_.end())
      damaged("the bag header's index position is not a record", records_.front().pos);
    const auto first = static_cast<std::size_t>(at - records_.begin());
    if (records_.size() - first < connection_count_ + chunk_count_) {
      damaged("fewer connection and chunk-info records than the bag header states", index_pos_);
    }
    for (std::size_t i = 0; i < connection_count_ + chunk_count_; ++i) {
      const Record& r = records_[first + i];
      if (r.op != (i < connection_count_ ? kConnection : kChunkInfo)) {
        damaged("unexpected record in the index section", r.pos);
      }
    }
    for (const auto& [info_pos, chunk] : chunk_infos_) {
      const auto found = index_records_after_chunk_.find(chunk.first);
      if (found == index_records_after_chunk_.end())
        damaged("chunk info pointing to no chunk", info_pos);
      if (found->second < chunk.second)
        damaged("chunk with fewer index records than its chunk info states", chunk.first);
    }
    for (const std::set<std::uint32_t>* used : {&index_connections_, &message_connections_}) {
      for (const std::uint32_t id : *used) {
        if (connection_ids_.count(id) == 0) {
          damaged("connection id " + std::to_string(id) + " is used but never defined", index_pos_);
        }
      }
    }
  }

  std::string path_;
  std::istream& in_;
  std::uint64_t file_size_ = 0;
  std::vector<Record> records_;
  std::uint64_t index_pos_ = 0;
  std::uint64_t connection_count_ = 0;
  std::uint64_t chunk_count_ = 0;
  std::uint64_t chunk_pos_ = 0;              // the chunk the next index records belong to
  std::set<std::uint32_t> message_offsets_;  // in that chunk
  std::map<std::uint64_t, std::uint64_t> index_records_after_chunk_;
  std::vector<std::pair<std::uint64_t, std::pair<std::uint64_t, std::uint64_t>>>
      chunk_infos_;  // pos, (chunk_pos, count)
  std::set<std::uint32_t>
      connection_ids_;  // top-level connection records (what rosbag_storage knows)
  std::set<std::uint32_t> index_connections_;
  std::set<std::uint32_t> message_connections_;
};

}  // namespace

void check_bag_structure(std::istream& in, const std::string& name) { StructureCheck(in, name).run(); }

void check_bag_structure(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file");
  check_bag_structure(in, path);
}

}  // namespace dsswarm::rosbag_raw
