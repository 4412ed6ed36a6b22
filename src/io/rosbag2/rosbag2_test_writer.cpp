#include "io/rosbag2/rosbag2_test_writer.hpp"

#include <sqlite3.h>
#include <zstd.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "geometry/pose2.hpp"
#include "io/bag_common/bag_collector.hpp"
#include "io/rosbag2/mcap_writer.hpp"

namespace dsswarm::rosbag2_test {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

Bytes zstd_compress(std::span<const std::uint8_t> in) {
  Bytes out(ZSTD_compressBound(in.size()));
  const std::size_t n = ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 3);
  if (ZSTD_isError(n)) throw std::runtime_error("zstd compression failed");
  out.resize(n);
  return out;
}

void write_bytes(const fs::path& path, std::span<const std::uint8_t> bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

Bytes read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

Bytes stored_data(const BagMessage& m, const WriteOptions& options) {
  return options.compression == rosbag2::Compression::Message ? zstd_compress(m.cdr) : m.cdr;
}

void sql(sqlite3* db, const std::string& statement) {
  char* error = nullptr;
  if (sqlite3_exec(db, statement.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error != nullptr ? error : "?";
    sqlite3_free(error);
    throw std::runtime_error("sqlite: " + message);
  }
}

// The tables rosbag2 Humble writes (schema version 3).
void write_db3(const fs::path& path, std::span<const BagMessage> messages,
               const WriteOptions& options) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
      SQLITE_OK) {
    sqlite3_close(db);
    throw std::runtime_error("cannot create " + path.string());
  }
  const std::unique_ptr<sqlite3, decltype(&sqlite3_close)> owner(db, &sqlite3_close);
  sql(db,
      "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);"
      "INSERT INTO schema VALUES (3, 'humble');"
      "CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL,"
      " metadata TEXT NOT NULL);"
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,"
      " serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,"
      " timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
      "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
      "BEGIN TRANSACTION;");
  std::map<std::string, std::int64_t> topic_ids;
  sqlite3_stmt* insert = nullptr;
  sqlite3_prepare_v2(db, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)", -1,
                     &insert, nullptr);
  for (const BagMessage& m : messages) {
    if (topic_ids.count(m.topic) == 0) {
      const auto id = static_cast<std::int64_t>(topic_ids.size() + 1);
      topic_ids[m.topic] = id;
      sql(db, "INSERT INTO topics VALUES (" + std::to_string(id) + ", '" + m.topic + "', '" +
                  m.type + "', 'cdr', '')");
    }
    const Bytes data = stored_data(m, options);
    sqlite3_bind_int64(insert, 1, topic_ids[m.topic]);
    sqlite3_bind_int64(insert, 2, m.log_time_ns);
    sqlite3_bind_blob(insert, 3, data.data(), static_cast<int>(data.size()), SQLITE_TRANSIENT);
    if (sqlite3_step(insert) != SQLITE_DONE) throw std::runtime_error("sqlite insert failed");
    sqlite3_reset(insert);
  }
  sqlite3_finalize(insert);
  sql(db, "COMMIT;");
}

mcap::Chunking chunking_of(Format format) {
  switch (format) {
    case Format::McapChunked: return mcap::Chunking::Uncompressed;
    case Format::McapZstd: return mcap::Chunking::Zstd;
    case Format::McapLz4: return mcap::Chunking::Lz4;
    default: return mcap::Chunking::None;
  }
}

void write_mcap(const fs::path& path, std::span<const BagMessage> messages,
                const WriteOptions& options) {
  mcap::McapWriter writer(chunking_of(options.format), options.chunk_bytes);
  for (const BagMessage& m : messages) {
    writer.message(writer.channel(m.topic, m.type), static_cast<std::uint64_t>(m.log_time_ns),
                   stored_data(m, options));
  }
  write_bytes(path, std::move(writer).finish());
}

void write_metadata(const fs::path& dir, const std::vector<fs::path>& files,
                    const std::vector<BagMessage>& messages, const WriteOptions& options) {
  std::map<std::string, std::pair<std::string, std::size_t>> topics;  // name -> type, count
  std::int64_t first = messages.empty() ? 0 : messages.front().log_time_ns, last = first;
  for (const BagMessage& m : messages) {
    auto& [type, count] = topics[m.topic];
    type = m.type;
    ++count;
    first = std::min(first, m.log_time_ns);
    last = std::max(last, m.log_time_ns);
  }
  std::ostringstream y;
  y << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: "
    << (options.format == Format::Db3 ? "sqlite3" : "mcap") << "\n  duration:\n    nanoseconds: "
    << last - first << "\n  starting_time:\n    nanoseconds_since_epoch: " << first
    << "\n  message_count: " << messages.size() << "\n  topics_with_message_count:\n";
  for (const auto& [name, info] : topics) {
    y << "    - topic_metadata:\n        name: " << name << "\n        type: " << info.first
      << "\n        serialization_format: cdr\n        offered_qos_profiles: \"\"\n"
      << "      message_count: " << info.second << "\n";
  }
  const bool compressed = options.compression != rosbag2::Compression::None;
  const char* mode = options.compression == rosbag2::Compression::File ? "FILE" : "MESSAGE";
  y << "  compression_format: " << (compressed ? "zstd" : "\"\"") << "\n  compression_mode: "
    << (compressed ? mode : "\"\"") << "\n  relative_file_paths:\n";
  for (const fs::path& f : files) y << "    - " << f.filename().string() << "\n";
  std::ofstream(dir / rosbag2::kMetadataFile) << y.str();
}

}  // namespace

const char* format_name(Format format) {
  switch (format) {
    case Format::Db3: return "db3";
    case Format::McapUnchunked: return "mcap-unchunked";
    case Format::McapChunked: return "mcap-chunked";
    case Format::McapZstd: return "mcap-zstd";
    case Format::McapLz4: return "mcap-lz4";
  }
  return "?";
}

std::vector<fs::path> write_bag(const fs::path& dir, const std::vector<BagMessage>& messages,
                                const WriteOptions& options) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<fs::path> files;
  const std::size_t per_file = (messages.size() + options.files - 1) / options.files;
  for (std::size_t i = 0; i < options.files; ++i) {
    const std::size_t begin = std::min(messages.size(), i * per_file);
    const auto part =
        std::span(messages).subspan(begin, std::min(per_file, messages.size() - begin));
    fs::path path = dir / (dir.filename().string() + "_" + std::to_string(i) +
                           (options.format == Format::Db3 ? ".db3" : ".mcap"));
    if (options.format == Format::Db3) {
      write_db3(path, part, options);
    } else {
      write_mcap(path, part, options);
    }
    if (options.compression == rosbag2::Compression::File) {
      const fs::path compressed = path.string() + ".zstd";
      write_bytes(compressed, zstd_compress(read_bytes(path)));
      fs::remove(path);
      path = compressed;
    }
    files.push_back(path);
  }
  if (options.metadata) write_metadata(dir, files, messages, options);
  return files;
}

ros2::LaserScan laser_scan(double stamp, std::vector<float> ranges) {
  ros2::LaserScan m;
  m.header = {ros2::time_from_seconds(stamp), "laser"};
  m.angle_min = static_cast<float>(-std::numbers::pi / 2);
  m.angle_increment = static_cast<float>(std::numbers::pi / 2);
  m.angle_max = m.angle_min + m.angle_increment * static_cast<float>(ranges.size() - 1);
  m.range_min = 0.1F;
  m.range_max = 30.0F;
  m.ranges = std::move(ranges);
  return m;
}

namespace {

double step(double v, int ulps) {
  for (; ulps > 0; --ulps) v = std::nextafter(v, 2.0);
  for (; ulps < 0; ++ulps) v = std::nextafter(v, -2.0);
  return v;
}

// A yaw rotation by `theta` whose heading, as the bag readers compute it
// (bag::yaw_of), is `theta` to the last bit where a quaternion within a few
// ulps of the plain one gives that: converted logs then read back unchanged.
ros2::Quaternion yaw_quaternion(double theta) {
  constexpr int kUlps = 4;
  const double z = std::sin(theta / 2), w = std::cos(theta / 2);
  ros2::Quaternion best{0.0, 0.0, z, w};
  double best_error = std::numeric_limits<double>::infinity();
  for (int i = -kUlps; i <= kUlps && best_error > 0.0; ++i) {
    for (int j = -kUlps; j <= kUlps && best_error > 0.0; ++j) {
      const ros2::Quaternion q{0.0, 0.0, step(z, i), step(w, j)};
      const double error =
          std::abs(normalize_angle(bag::yaw_of({q.x, q.y, q.z, q.w}, "") - theta));
      if (error < best_error) {
        best = q;
        best_error = error;
      }
    }
  }
  return best;
}

}  // namespace

ros2::Odometry odometry(double stamp, double x, double y, double theta) {
  ros2::Odometry m;
  m.header = {ros2::time_from_seconds(stamp), "odom"};
  m.child_frame_id = "base_link";
  m.pose.pose = {{x, y, 0.0}, yaw_quaternion(theta)};
  return m;
}

ros2::TFMessage transform(double stamp, const std::string& parent, const std::string& child,
                          double x, double y, double theta) {
  ros2::TransformStamped t;
  t.header = {ros2::time_from_seconds(stamp), parent};
  t.child_frame_id = child;
  t.transform = {{x, y, 0.0}, yaw_quaternion(theta)};
  return {{t}};
}

}  // namespace dsswarm::rosbag2_test
