#include "io/rosbag2/rosbag2_reader.hpp"

#include <fmt/format.h>

#include <map>
#include <utility>

#include "common/errors.hpp"
#include "io/bag_common/bag_collector.hpp"
#include "io/bag_common/bag_log.hpp"
#include "io/rosbag2/bag_metadata.hpp"
#include "io/rosbag2/decompress.hpp"
#include "io/rosbag2/storage_files.hpp"
#include "ros2/codec.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using bag::BagCollector;
using rosbag2::StoredMessage;

constexpr const char* kCdr = "cdr";

double seconds_of(std::int64_t ns) {
  constexpr std::int64_t kNanos = 1'000'000'000;
  return static_cast<double>(ns / kNanos) + static_cast<double>(ns % kNanos) * 1e-9;
}

bag::RawQuaternion raw(const ros2::Quaternion& q) { return {q.x, q.y, q.z, q.w}; }

// Decodes the messages the collector wants and hands them over.
class Ros2Decoder {
 public:
  Ros2Decoder(BagCollector& collector, rosbag2::Compression compression)
      : collector_(collector), compression_(compression) {}

  // `file` names the storage file in errors.
  void add(const StoredMessage& m, const std::string& file) {
    const BagCollector::Role role = collector_.role_of(m.topic.name);
    // A scan or odometry topic of another type is reported with the topic
    // list once the bag is read; a /tf of another type cannot help.
    if (m.topic.type != expected_type(role)) return;
    if (m.topic.encoding != kCdr) {
      throw InputError(fmt::format("{}: topic {} is serialized as '{}'; only {} is read", file,
                                   m.topic.name, m.topic.encoding, kCdr));
    }
    const double record_time = seconds_of(m.log_time_ns);
    const std::string where =
        fmt::format("{}: {} message at t={:.6f}", file, m.topic.name, record_time);
    std::vector<std::uint8_t> decompressed;
    std::span<const std::uint8_t> data = m.data;
    if (compression_ == rosbag2::Compression::Message) {
      decompressed = rosbag2::zstd_decompress(data, rosbag2::kMaxMessageBytes, where);
      data = decompressed;
    }
    add_decoded(role, Message{data, record_time, where});
  }

 private:
  static std::string_view expected_type(BagCollector::Role role) {
    switch (role) {
      case BagCollector::Role::Scan: return ros2::LaserScan::kTypeName;
      case BagCollector::Role::Odometry: return ros2::Odometry::kTypeName;
      case BagCollector::Role::Transforms:
      case BagCollector::Role::StaticTransforms: return ros2::TFMessage::kTypeName;
      case BagCollector::Role::Ignored: break;
    }
    return {};
  }

  struct Message {
    std::span<const std::uint8_t> data;
    double record_time;
    const std::string& where;  // names the message in errors
  };

  // The CDR decoded, or an InputError naming the message.
  template <typename T>
  static T decode(const Message& m) {
    try {
      return ros2::decode<T>(m.data);
    } catch (const InputError& e) {
      throw InputError(m.where + ": " + e.what());
    }
  }

  void add_decoded(BagCollector::Role role, const Message& m) {
    const double t = m.record_time;
    if (role == BagCollector::Role::Scan) {
      auto scan = decode<ros2::LaserScan>(m);
      bag::RawScan raw_scan;
      raw_scan.angle_min = scan.angle_min;
      raw_scan.angle_increment = scan.angle_increment;
      raw_scan.range_min = scan.range_min;
      raw_scan.range_max = scan.range_max;
      raw_scan.ranges = std::move(scan.ranges);
      collector_.add_scan(ros2::to_seconds(scan.header.stamp), t, scan.header.frame_id,
                          std::move(raw_scan));
    } else if (role == BagCollector::Role::Odometry) {
      const auto odometry = decode<ros2::Odometry>(m);
      const ros2::Pose& pose = odometry.pose.pose;
      collector_.add_odometry(ros2::to_seconds(odometry.header.stamp), t, pose.position.x,
                              pose.position.y, raw(pose.orientation));
    } else {
      const bool is_static = role == BagCollector::Role::StaticTransforms;
      for (const ros2::TransformStamped& tf : decode<ros2::TFMessage>(m).transforms) {
        const ros2::Vector3& p = tf.transform.translation;
        collector_.add_transform(is_static, ros2::to_seconds(tf.header.stamp), t,
                                 tf.header.frame_id, tf.child_frame_id, p.x, p.y,
                                 raw(tf.transform.rotation));
      }
    }
  }

  BagCollector& collector_;
  rosbag2::Compression compression_;
};

// The topics of all storage files, merged by name.
void merge_topics(const std::vector<rosbag2::StorageTopic>& from,
                  std::map<std::string, bag::RawTopic>& into) {
  for (const rosbag2::StorageTopic& t : from) {
    bag::RawTopic& topic = into[t.name];
    topic.name = t.name;
    if (topic.type.empty()) {
      topic.type = t.type;
    } else if (topic.type.find(t.type) == std::string::npos) {
      topic.type += " | " + t.type;
    }
    topic.messages += t.messages;
  }
}

}  // namespace

bool is_rosbag2_path(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) || rosbag2::storage_kind_of(path).has_value();
}

SensorLog read_rosbag2(const fs::path& path, const BagReadOptions& options) {
  const std::string name = path.string();
  const rosbag2::BagFiles files = rosbag2::locate_bag_files(path);
  BagCollector collector(name, options);
  Ros2Decoder decoder(collector, files.compression);
  std::map<std::string, bag::RawTopic> topics;
  for (const fs::path& file : files.paths) {
    const std::string file_name = file.string();
    merge_topics(rosbag2::read_storage_file(
                     file, files.storage, files.compression,
                     [&](const std::string& topic) {
                       return collector.role_of(topic) != BagCollector::Role::Ignored;
                     },
                     [&](const StoredMessage& m) { decoder.add(m, file_name); }),
                 topics);
  }
  std::vector<bag::RawTopic> sorted;
  for (auto& entry : topics) sorted.push_back(std::move(entry.second));
  SensorLog log =
      sensor_log_from_bag(std::move(collector).finish(std::move(sorted)), name, options,
                          kRos2MessageTypes);
  log.warnings.insert(log.warnings.begin(), files.warnings.begin(), files.warnings.end());
  return log;
}

}  // namespace dsswarm
