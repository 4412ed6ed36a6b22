#include "net/sensor_publisher.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "net/qos.hpp"
#include "net/ros_names.hpp"

namespace dsswarm::net {
namespace {

std::chrono::milliseconds left_until(std::chrono::steady_clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
  return std::max(left, std::chrono::milliseconds(0));
}

}  // namespace

ros::LaserScan to_ros_scan(const LaserScan& scan, const std::string& frame) {
  const bool finite = std::isfinite(scan.angle_min) && std::isfinite(scan.angle_increment) &&
                      std::isfinite(scan.range_min) && std::isfinite(scan.range_max);
  if (scan.ranges.empty() || !finite) {
    throw InputError(fmt::format("scan at {} s cannot be published: {}", scan.timestamp,
                                 scan.ranges.empty() ? "no readings" : "non-finite beam geometry"));
  }
  ros::LaserScan msg{};
  msg.header.stamp = to_ros_time(scan.timestamp);
  msg.header.frame_id = borrow(frame);
  msg.angle_min = static_cast<float>(scan.angle_min);
  msg.angle_max = static_cast<float>(scan.beam_angle(scan.ranges.size() - 1));
  msg.angle_increment = static_cast<float>(scan.angle_increment);
  msg.range_min = static_cast<float>(scan.range_min);
  msg.range_max = static_cast<float>(scan.range_max);
  borrow(msg.ranges, scan.ranges);
  return msg;
}

SensorPublisher::SensorPublisher(Participant& participant, const SensorPublisherConfig& config)
    : config_(config),
      scan_topic_(participant, ros_topic_name(config.ns, config.scan_topic)),
      odom_topic_(participant, ros_topic_name(config.ns, config.odom_topic)),
      tf_topic_(participant, ros_topic_name(config.ns, config.tf_topic)),
      tf_static_topic_(participant, ros_topic_name(config.ns, config.tf_static_topic)),
      // Reliable, with room for a reader that falls behind for a while (a
      // reliable one may be waiting for every scan: agent --reliable-input).
      scan_writer_(scan_topic_, ros_default(100)),
      odom_writer_(odom_topic_, ros_default(100)),
      tf_writer_(tf_topic_, ros_tf()),
      tf_static_writer_(tf_static_topic_, ros_tf_static(1)) {}

void SensorPublisher::publish(const LaserScan& scan) {
  const ros::LaserScan scan_msg = to_ros_scan(scan, config_.laser_frame);
  if (!published_offset_ || published_offset_->x != scan.laser_offset.x ||
      published_offset_->y != scan.laser_offset.y || published_offset_->theta != scan.laser_offset.theta) {
    publish_laser_offset(scan.laser_offset, scan.timestamp);
  }
  // Odometry first: a subscriber holding the scan for odometry at its stamp
  // gets it without waiting.
  if (scan.odometry) {
    ros::Odometry odom{};
    odom.header.stamp = scan_msg.header.stamp;
    odom.header.frame_id = borrow(config_.odom_frame);
    odom.child_frame_id = borrow(config_.base_frame);
    odom.pose.pose = to_ros_pose(*scan.odometry);
    odom_writer_.write(odom);
    if (config_.publish_tf) {
      ros::TransformStamped t =
          to_ros_transform_stamped(scan.timestamp, config_.odom_frame, config_.base_frame, *scan.odometry);
      ros::TFMessage tf{};
      tf.transforms = {1, 1, &t, false};
      tf_writer_.write(tf);
    }
  }
  scan_writer_.write(scan_msg);
}

void SensorPublisher::publish_laser_offset(const Pose2& offset, double stamp) {
  ros::TransformStamped t = to_ros_transform_stamped(stamp, config_.base_frame, config_.laser_frame, offset);
  ros::TFMessage tf{};
  tf.transforms = {1, 1, &t, false};
  tf_static_writer_.write(tf);
  published_offset_ = offset;
}

bool SensorPublisher::latch_laser_offset(const Pose2& offset, double stamp, std::chrono::milliseconds timeout) {
  publish_laser_offset(offset, stamp);
  return tf_static_writer_.wait_for_acks(timeout);
}

int SensorPublisher::subscribers() const { return std::min(scan_writer_.matched(), odom_writer_.matched()); }

bool SensorPublisher::wait_for_subscribers(int count, std::chrono::milliseconds timeout, bool odometry) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  return scan_writer_.wait_for_readers(count, timeout) &&
         (!odometry || odom_writer_.wait_for_readers(count, left_until(deadline)));
}

bool SensorPublisher::wait_for_acks(std::chrono::milliseconds timeout) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  return scan_writer_.wait_for_acks(timeout) && odom_writer_.wait_for_acks(left_until(deadline)) &&
         tf_writer_.wait_for_acks(left_until(deadline)) && tf_static_writer_.wait_for_acks(left_until(deadline));
}

}  // namespace dsswarm::net
