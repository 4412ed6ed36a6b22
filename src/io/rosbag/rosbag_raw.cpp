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
#include <cmath>
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

template <typename String>
std::string without_leading_slash(const String& frame) {
  const std::string s(frame.begin(), frame.end());
  return !s.empty() && s.front() == '/' ? s.substr(1) : s;
}

// Yaw of a quaternion that need not be normalised (the form below is
// homogeneous in q). A zero or non-finite quaternion has no heading: refuse it
// rather than return 0.
template <typename Quaternion>
double yaw_of(const Quaternion& q, const std::string& where) {
  const double norm2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
  if (!std::isfinite(norm2) || norm2 < 1e-12) {
    throw InputError(where + ": orientation quaternion is zero or not finite");
  }
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), q.w * q.w + q.x * q.x - q.y * q.y - q.z * q.z);
}

void require_finite_position(double x, double y, const std::string& where) {
  if (!std::isfinite(x) || !std::isfinite(y)) throw InputError(where + ": position is not finite");
}

class BagCollector {
 public:
  BagCollector(std::string path, std::string scan_topic, std::string odom_topic, bool use_tf)
      : path_(std::move(path)),
        scan_topic_(std::move(scan_topic)),
        odom_topic_(std::move(odom_topic)),
        use_tf_(use_tf) {}

  // Counts every message; true for those add() wants to see.
  bool wants(const rosbag::MessageInstance& m) {
    const std::string& topic = m.getTopic();
    ++message_counts_[topic];
    return topic == scan_topic_ || (!use_tf_ && topic == odom_topic_) || topic == "/tf" ||
           topic == "/tf_static";
  }

  // Messages must come in file order.
  void add(const rosbag::MessageInstance& m) {
    const std::string& topic = m.getTopic();
    if (topic == scan_topic_) {
      add_scan(m);
    } else if (!use_tf_ && topic == odom_topic_) {
      add_odometry(m);
    } else if (topic == "/tf" || topic == "/tf_static") {
      add_transforms(m, topic == "/tf_static");
    }
  }

  RawBag finish(rosbag::View& view) {
    RawBag bag;
    bag.scans = std::move(scans_);
    bag.odom = std::move(odom_);
    bag.laser_frame = laser_frame_.empty() ? kDefaultLaserFrame : laser_frame_;
    bag.laser_offset = laser_offset(bag.laser_frame);
    bag.zero_header_stamps = zero_header_stamps_;
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
    for (auto& entry : topics) bag.topics.push_back(std::move(entry.second));
    return bag;
  }

 private:
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

  double stamp_of(const ros::Time& header_stamp, const rosbag::MessageInstance& m) {
    if (!header_stamp.isZero()) return header_stamp.toSec();
    ++zero_header_stamps_;
    return m.getTime().toSec();
  }

  // Names a message for error messages by its record time (its index in
  // View order would not match the file order a user sees in other tools).
  std::string where(const rosbag::MessageInstance& m) const {
    return path_ + ": " + m.getTopic() + " message at t=" + std::to_string(m.getTime().toSec());
  }

  void add_scan(const rosbag::MessageInstance& m) {
    const auto msg = decode<Scan>(m);
    if (laser_frame_.empty()) laser_frame_ = without_leading_slash(msg->header.frame_id);
    RawScan scan;
    scan.stamp = stamp_of(msg->header.stamp, m);
    scan.angle_min = msg->angle_min;
    scan.angle_increment = msg->angle_increment;
    scan.range_min = msg->range_min;
    scan.range_max = msg->range_max;
    scan.ranges.assign(msg->ranges.begin(), msg->ranges.end());
    scans_.push_back(std::move(scan));
  }

  void add_odometry(const rosbag::MessageInstance& m) {
    const auto msg = decode<Odometry>(m);
    const std::string here = where(m);
    const auto& pose = msg->pose.pose;
    require_finite_position(pose.position.x, pose.position.y, here);
    odom_.push_back(RawOdom{stamp_of(msg->header.stamp, m), pose.position.x, pose.position.y,
                            yaw_of(pose.orientation, here)});
  }

  void add_transforms(const rosbag::MessageInstance& m, bool is_static) {
    // A /tf topic of some other type cannot hold what we look for: skip it
    // (the caller reports missing odometry or laser offset).
    const auto msg = instantiate_capped<Transforms>(m);
    if (!msg) return;
    for (const auto& tf : msg->transforms) {
      const std::string parent = without_leading_slash(tf.header.frame_id);
      const std::string child = without_leading_slash(tf.child_frame_id);
      const auto& t = tf.transform.translation;
      if (use_tf_ && !is_static && parent == kOdomFrame && child == kBaseFrame) {
        const std::string here = where(m) + " (" + parent + " -> " + child + ")";
        require_finite_position(t.x, t.y, here);
        odom_.push_back(
            RawOdom{stamp_of(tf.header.stamp, m), t.x, t.y, yaw_of(tf.transform.rotation, here)});
      } else if (parent == kBaseFrame) {
        // The first transform to each child frame wins; the laser frame is
        // known only once a scan has been read, so keep them all.
        auto& found = is_static ? static_from_base_ : dynamic_from_base_;
        if (found.count(child) == 0) {
          const std::string here = where(m) + " (" + parent + " -> " + child + ")";
          require_finite_position(t.x, t.y, here);
          found[child] = RawStatic{true, t.x, t.y, yaw_of(tf.transform.rotation, here)};
        }
      }
    }
  }

  RawStatic laser_offset(const std::string& laser_frame) const {
    if (laser_frame == kBaseFrame) return RawStatic{true, 0.0, 0.0, 0.0};
    for (const auto* found : {&static_from_base_, &dynamic_from_base_}) {
      const auto it = found->find(laser_frame);
      if (it != found->end()) return it->second;
    }
    return RawStatic{};
  }

  std::string path_;
  std::string scan_topic_;
  std::string odom_topic_;
  bool use_tf_;
  std::vector<RawScan> scans_;
  std::vector<RawOdom> odom_;
  std::map<std::string, RawStatic> static_from_base_;   // /tf_static: base_link -> child
  std::map<std::string, RawStatic> dynamic_from_base_;  // /tf: base_link -> child (older bags)
  std::map<std::string, std::size_t> message_counts_;
  std::string laser_frame_;
  std::size_t zero_header_stamps_ = 0;
};

}  // namespace

RawBag read_raw_bag(const std::string& path, const std::string& scan_topic,
                    const std::string& odom_topic, bool use_tf) {
  try {
    check_bag_structure(path);
    rosbag::Bag bag;
    bag.open(path, rosbag::bagmode::Read);
    rosbag::View view(bag);
    BagCollector collector(path, scan_topic, odom_topic, use_tf);
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
    return collector.finish(view);
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
