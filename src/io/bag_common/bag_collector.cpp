#include "io/bag_common/bag_collector.hpp"

#include <cmath>
#include <utility>

#include "common/errors.hpp"

namespace dsswarm::bag {
namespace {

constexpr const char* kTfTopic = "/tf";
constexpr const char* kTfStaticTopic = "/tf_static";

std::string without_leading_slash(const std::string& frame) {
  return !frame.empty() && frame.front() == '/' ? frame.substr(1) : frame;
}

void require_finite_position(double x, double y, const std::string& where) {
  if (!std::isfinite(x) || !std::isfinite(y)) throw InputError(where + ": position is not finite");
}

}  // namespace

double yaw_of(const RawQuaternion& q, const std::string& where) {
  // The form below is homogeneous in q, so q need not be normalised.
  const double norm2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
  if (!std::isfinite(norm2) || norm2 < 1e-12) {
    throw InputError(where + ": orientation quaternion is zero or not finite");
  }
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), q.w * q.w + q.x * q.x - q.y * q.y - q.z * q.z);
}

BagCollector::BagCollector(std::string path, BagReadOptions options)
    : path_(std::move(path)), options_(std::move(options)) {}

BagCollector::Role BagCollector::role_of(const std::string& topic) const {
  if (topic == options_.scan_topic) return Role::Scan;
  if (!options_.use_tf_odometry && topic == options_.odom_topic) return Role::Odometry;
  if (topic == kTfTopic) return Role::Transforms;
  if (topic == kTfStaticTopic) return Role::StaticTransforms;
  return Role::Ignored;
}

double BagCollector::stamp_of(double header_stamp, double record_time) {
  if (header_stamp != 0.0) return header_stamp;
  ++zero_header_stamps_;
  return record_time;
}

// Names a message for error messages by its record time (its index would
// not match what other tools show for a bag they list in time order).
std::string BagCollector::where(const std::string& topic, double record_time) const {
  return path_ + ": " + topic + " message at t=" + std::to_string(record_time);
}

void BagCollector::add_scan(double header_stamp, double record_time, const std::string& frame_id,
                            RawScan scan) {
  if (laser_frame_.empty()) laser_frame_ = without_leading_slash(frame_id);
  scan.stamp = stamp_of(header_stamp, record_time);
  scans_.push_back(std::move(scan));
}

void BagCollector::add_odometry(double header_stamp, double record_time, double x, double y,
                                const RawQuaternion& orientation) {
  const std::string here = where(options_.odom_topic, record_time);
  require_finite_position(x, y, here);
  odom_.push_back(RawOdom{stamp_of(header_stamp, record_time), x, y, yaw_of(orientation, here)});
}

void BagCollector::add_transform(bool is_static, double header_stamp, double record_time,
                                 const std::string& parent_frame, const std::string& child_frame,
                                 double x, double y, const RawQuaternion& rotation) {
  const std::string parent = without_leading_slash(parent_frame);
  const std::string child = without_leading_slash(child_frame);
  const auto here = [&] {
    return where(is_static ? kTfStaticTopic : kTfTopic, record_time) + " (" + parent + " -> " +
           child + ")";
  };
  if (options_.use_tf_odometry && !is_static && parent == kOdomFrame && child == kBaseFrame) {
    require_finite_position(x, y, here());
    odom_.push_back(RawOdom{stamp_of(header_stamp, record_time), x, y, yaw_of(rotation, here())});
  } else if (parent == kBaseFrame) {
    // The first transform to each child frame wins; the laser frame is known
    // only once a scan has been read, so keep them all.
    auto& found = is_static ? static_from_base_ : dynamic_from_base_;
    if (found.count(child) == 0) {
      require_finite_position(x, y, here());
      found[child] = RawStatic{true, x, y, yaw_of(rotation, here())};
    }
  }
}

RawStatic BagCollector::laser_offset(const std::string& laser_frame) const {
  if (laser_frame == kBaseFrame) return RawStatic{true, 0.0, 0.0, 0.0};
  for (const auto* found : {&static_from_base_, &dynamic_from_base_}) {
    const auto it = found->find(laser_frame);
    if (it != found->end()) return it->second;
  }
  return RawStatic{};
}

RawBag BagCollector::finish(std::vector<RawTopic> topics) && {
  RawBag bag;
  bag.scans = std::move(scans_);
  bag.odom = std::move(odom_);
  bag.laser_frame = laser_frame_.empty() ? kDefaultLaserFrame : laser_frame_;
  bag.laser_offset = laser_offset(bag.laser_frame);
  bag.zero_header_stamps = zero_header_stamps_;
  bag.topics = std::move(topics);
  return bag;
}

}  // namespace dsswarm::bag
