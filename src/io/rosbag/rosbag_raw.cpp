// The only translation unit of the reader that includes ROS headers; compiled
// as C++17 because they do not build as C++20 (std::allocator<void>::rebind).
#include "io/rosbag/rosbag_raw.hpp"

#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "io/bag_common/bag_collector.hpp"
#include "io/rosbag/bag_structure.hpp"

namespace dsswarm::rosbag_raw {
namespace {

// rosbag::View iterates in record-time order, but the true order of these
// logs is the order the messages were written (the intel log's stamps jump
// around by up to 0.9 s). That file position lives only in the private
// MessageInstance::index_entry_. An explicit template instantiation may name a
// private member ([temp.spec.general]/6), which lets us read it instead of
// re-reading the bag's index ourselves.
struct IndexEntryTag {
  using type = const rosbag::IndexEntry rosbag::MessageInstance::*;
  friend type member_pointer(IndexEntryTag);
};
template <typename Tag, typename Tag::type Member>
struct ExposeMember {
  friend typename Tag::type member_pointer(Tag) { return Member; }
};
template struct ExposeMember<IndexEntryTag, &rosbag::MessageInstance::index_entry_>;

// ros::serialization sizes a vector or string from its length field before
// checking that the message holds that many bytes, so one damaged length
// allocates up to 16 GB. Messages are decoded with this allocator, which
// refuses any single allocation larger than the message could need.
thread_local std::size_t g_allocation_limit = std::numeric_limits<std::size_t>::max();

template <typename T>
struct CappedAllocator {
  using value_type = T;
  template <typename U>
  struct rebind {  // the ROS message templates use the pre-C++20 rebind member
    using other = CappedAllocator<U>;
  };
  CappedAllocator() = default;
  template <typename U>
  CappedAllocator(const CappedAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > g_allocation_limit / sizeof(T))
      throw std::length_error("a length field exceeds the message size");
    return std::allocator<T>{}.allocate(n);
  }
  void deallocate(T* p, std::size_t n) noexcept { std::allocator<T>{}.deallocate(p, n); }
  friend bool operator==(const CappedAllocator&, const CappedAllocator&) { return true; }
  friend bool operator!=(const CappedAllocator&, const CappedAllocator&) { return false; }
};

using Scan = sensor_msgs::LaserScan_<CappedAllocator<void>>;
using Odometry = nav_msgs::Odometry_<CappedAllocator<void>>;
using Transforms = tf2_msgs::TFMessage_<CappedAllocator<void>>;

// Decodes a message with allocations capped to what its serialised size
// allows (in-memory elements are at most ~2x their serialised size).
template <typename T>
boost::shared_ptr<T> instantiate_capped(const rosbag::MessageInstance& m) {
  struct Limit {
    explicit Limit(std::size_t bytes) { g_allocation_limit = bytes; }
    ~Limit() { g_allocation_limit = std::numeric_limits<std::size_t>::max(); }
    Limit(const Limit&) = delete;
    Limit& operator=(const Limit&) = delete;
  };
  const Limit limit(4 * std::size_t{m.size()} + 4096);
  return m.instantiate<T>();
}

struct FilePosition {
  std::uint64_t chunk = 0;   // byte offset of the chunk in the file
  std::uint32_t offset = 0;  // byte offset of the record in the (decompressed) chunk
  bool operator<(const FilePosition& other) const {
    return std::tie(chunk, offset) < std::tie(other.chunk, other.offset);
  }
};

FilePosition file_position(const rosbag::MessageInstance& m) {
  const rosbag::IndexEntry& entry = m.*member_pointer(IndexEntryTag{});
  return {entry.chunk_pos, entry.offset};
}

template <typename Quaternion>
bag::RawQuaternion raw_quaternion(const Quaternion& q) {
  return {q.x, q.y, q.z, q.w};
}

// Decodes the messages the shared collector wants and hands them over.
class Ros1Collector {
 public:
  Ros1Collector(std::string path, const BagReadOptions& options)
      : path_(path), collector_(std::move(path), options) {}

  // Counts every message; true for those add() wants to see.
  bool wants(const rosbag::MessageInstance& m) {
    ++message_counts_[m.getTopic()];
    return collector_.role_of(m.getTopic()) != Role::Ignored;
  }

  // Messages must come in file order.
  void add(const rosbag::MessageInstance& m) {
    const double record_time = m.getTime().toSec();
    switch (collector_.role_of(m.getTopic())) {
      case Role::Scan: {
        const auto msg = decode<Scan>(m);
        RawScan scan;
        scan.angle_min = msg->angle_min;
        scan.angle_increment = msg->angle_increment;
        scan.range_min = msg->range_min;
        scan.range_max = msg->range_max;
        scan.ranges.assign(msg->ranges.begin(), msg->ranges.end());
        const std::string frame(msg->header.frame_id.begin(), msg->header.frame_id.end());
        collector_.add_scan(msg->header.stamp.toSec(), record_time, frame, std::move(scan));
        break;
      }
      case Role::Odometry: {
        const auto msg = decode<Odometry>(m);
        const auto& pose = msg->pose.pose;
        collector_.add_odometry(msg->header.stamp.toSec(), record_time, pose.position.x,
                                pose.position.y, raw_quaternion(pose.orientation));
        break;
      }
      case Role::Transforms:
      case Role::StaticTransforms:
        add_transforms(m, record_time);
        break;
      case Role::Ignored:
        break;
    }
  }

  RawBag finish(rosbag::View& view) && {
    std::map<std::string, RawTopic> topics;
    for (const rosbag::ConnectionInfo* c : view.getConnections()) {
      RawTopic& t = topics[c->topic];
      t.name = c->topic;
      // Several connections may share a topic; list each distinct type once.
      if (t.type.empty()) {
        t.type = c->datatype;
      } else if (t.type.find(c->datatype) == std::string::npos) {
        t.type += " | " + c->datatype;
      }
      t.messages = message_counts_[c->topic];
    }
    std::vector<RawTopic> sorted;
    for (auto& entry : topics) sorted.push_back(std::move(entry.second));
    return std::move(collector_).finish(std::move(sorted));
  }

 private:
  using Role = bag::BagCollector::Role;

  // The message as T, or InputError when the topic carries another type (or
  // another version of T: the MD5 sums differ).
  template <typename T>
  boost::shared_ptr<T> decode(const rosbag::MessageInstance& m) const {
    boost::shared_ptr<T> msg = instantiate_capped<T>(m);
    if (!msg) {
      throw InputError(path_ + ": topic " + m.getTopic() + " carries " + m.getDataType() +
                       " (md5 " + m.getMD5Sum() + "), not " +
                       ros::message_traits::DataType<T>::value() + " (md5 " +
                       ros::message_traits::MD5Sum<T>::value() + ")");
    }
    return msg;
  }

  void add_transforms(const rosbag::MessageInstance& m, double record_time) {
    // A /tf topic of some other type cannot hold what we look for: skip it
    // (the caller reports missing odometry or laser offset).
    const auto msg = instantiate_capped<Transforms>(m);
    if (!msg) return;
    const bool is_static = collector_.role_of(m.getTopic()) == Role::StaticTransforms;
    for (const auto& tf : msg->transforms) {
      const auto& t = tf.transform.translation;
      collector_.add_transform(is_static, tf.header.stamp.toSec(), record_time,
                               std::string(tf.header.frame_id.begin(), tf.header.frame_id.end()),
                               std::string(tf.child_frame_id.begin(), tf.child_frame_id.end()),
                               t.x, t.y, raw_quaternion(tf.transform.rotation));
    }
  }

  std::string path_;
  bag::BagCollector collector_;
  std::map<std::string, std::size_t> message_counts_;
};

}  // namespace

RawBag read_raw_bag(const std::string& path, const BagReadOptions& options) {
  try {
    check_bag_structure(path);
    rosbag::Bag bag;
    bag.open(path, rosbag::bagmode::Read);
    rosbag::View view(bag);
    Ros1Collector collector(path, options);
    // Decode in file order: that is the true order, and it reads each chunk
    // once (time order jumps between chunks at every glitched stamp, and
    // every jump decompresses a chunk again).
    std::vector<rosbag::MessageInstance> wanted;
    for (const rosbag::MessageInstance& m : view) {
      if (collector.wants(m)) wanted.push_back(m);
    }
    std::vector<std::size_t> order(wanted.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return file_position(wanted[a]) < file_position(wanted[b]);
    });
    for (const std::size_t i : order) collector.add(wanted[i]);
    return std::move(collector).finish(view);
  } catch (const InputError&) {
    throw;
  } catch (const rosbag::BagException& e) {
    throw InputError(path + ": not a readable ROS1 bag: " + e.what());
  } catch (const std::exception& e) {
    // Decoding errors (e.g. a message running past its record) and anything
    // else the ROS libraries throw.
    throw InputError(path + ": cannot read ROS1 bag: " + e.what());
  }
}

}  // namespace dsswarm::rosbag_raw
