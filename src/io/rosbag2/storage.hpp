#pragma once
// What both ROS 2 bag storages (.db3, .mcap) hand the bag reader: the topics
// and the serialized messages in file order.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace dsswarm::rosbag2 {

struct StorageTopic {
  std::string name;
  std::string type;      // e.g. "sensor_msgs/msg/LaserScan"
  std::string encoding;  // serialization format: "cdr" for ROS 2
  std::size_t messages = 0;
};

struct StoredMessage {
  const StorageTopic& topic;
  std::int64_t log_time_ns = 0;  // when it was recorded
  std::span<const std::uint8_t> data;
};

// Which topics' messages to hand over (all are counted).
using TopicFilter = std::function<bool(const std::string& topic)>;
using MessageHandler = std::function<void(const StoredMessage&)>;

// Nothing a 2D-lidar bag holds comes near these; bigger is damage.
inline constexpr std::size_t kMaxMessageBytes = std::size_t{256} << 20;
inline constexpr std::size_t kMaxChunkBytes = std::size_t{1} << 30;

}  // namespace dsswarm::rosbag2
