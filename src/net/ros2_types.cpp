#include "net/ros2_types.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "common/errors.hpp"

namespace dsswarm::net {

ros::Time to_ros_time(double seconds) {
  const double whole = std::floor(seconds);
  if (!std::isfinite(seconds) || whole < std::numeric_limits<std::int32_t>::min() ||
      whole > std::numeric_limits<std::int32_t>::max()) {
    throw InputError(fmt::format("time {} s does not fit a ROS 2 builtin_interfaces/Time", seconds));
  }
  auto sec = static_cast<std::int64_t>(whole);
  auto nanosec = static_cast<std::int64_t>(std::llround((seconds - whole) * 1e9));
  if (nanosec >= 1'000'000'000) {  // rounded up to the next second
    nanosec -= 1'000'000'000;
    ++sec;
  }
  return {static_cast<std::int32_t>(sec), static_cast<std::uint32_t>(nanosec)};
}

double to_seconds(const ros::Time& time) { return static_cast<double>(time.sec) + 1e-9 * time.nanosec; }

ros::Quaternion yaw_to_quaternion(double yaw) { return {0.0, 0.0, std::sin(0.5 * yaw), std::cos(0.5 * yaw)}; }

double quaternion_yaw(const ros::Quaternion& q) {
  // Both terms scale with |q|², so atan2 needs no normalisation.
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), q.w * q.w + q.x * q.x - q.y * q.y - q.z * q.z);
}

ros::Pose to_ros_pose(const Pose2& pose) { return {{pose.x, pose.y, 0.0}, yaw_to_quaternion(pose.theta)}; }

ros::Transform to_ros_transform(const Pose2& pose) { return {{pose.x, pose.y, 0.0}, yaw_to_quaternion(pose.theta)}; }

Pose2 to_pose2(const ros::Pose& pose) { return {pose.position.x, pose.position.y, quaternion_yaw(pose.orientation)}; }

Pose2 to_pose2(const ros::Transform& transform) {
  return {transform.translation.x, transform.translation.y, quaternion_yaw(transform.rotation)};
}

ros::TransformStamped to_ros_transform_stamped(double stamp, const std::string& parent, const std::string& child,
                                               const Pose2& parent_from_child) {
  ros::TransformStamped t{};
  t.header.stamp = to_ros_time(stamp);
  t.header.frame_id = borrow(parent);
  t.child_frame_id = borrow(child);
  t.transform = to_ros_transform(parent_from_child);
  return t;
}

}  // namespace dsswarm::net
