#pragma once
// The ROS 2 message types (idlc-generated from ros2_msgs.idl) as DDS topic
// types, and the conversions between them and ours.
//
// ros_type_hash: the REP 2011 type description hash (RIHS01) ROS 2 Iron and
// later put in endpoint USER_DATA. Computed from the message definitions with
// rosidl_generator_type_description's algorithm and checked against the
// hashes ROS 2's own generated code carries (`*__struct.h` TYPE_HASH /
// `*__description.c` EXPECTED_HASH of sensor_msgs, nav_msgs, geometry_msgs,
// tf2_msgs). A message layout change in ROS would change them.
#include <string>
#include <string_view>
#include <vector>

#include "geometry/pose2.hpp"
#include "net/dds.hpp"
#include "ros2_msgs.h"

namespace dsswarm::net {

namespace ros {
using Time = builtin_interfaces_msg_dds__Time_;
using Header = std_msgs_msg_dds__Header_;
using Quaternion = geometry_msgs_msg_dds__Quaternion_;
using Pose = geometry_msgs_msg_dds__Pose_;
using PoseStamped = geometry_msgs_msg_dds__PoseStamped_;
using Transform = geometry_msgs_msg_dds__Transform_;
using TransformStamped = geometry_msgs_msg_dds__TransformStamped_;
using Odometry = nav_msgs_msg_dds__Odometry_;
using OccupancyGrid = nav_msgs_msg_dds__OccupancyGrid_;
using Path = nav_msgs_msg_dds__Path_;
using LaserScan = sensor_msgs_msg_dds__LaserScan_;
using TFMessage = tf2_msgs_msg_dds__TFMessage_;
}  // namespace ros

template <>
struct TopicType<ros::LaserScan> {
  static const dds_topic_descriptor_t& descriptor() { return sensor_msgs_msg_dds__LaserScan__desc; }
  static constexpr std::string_view ros_type_hash =
      "RIHS01_64c191398013af96509d518dac71d5164f9382553fce5c1f8cca5be7924bd828";
};
template <>
struct TopicType<ros::Odometry> {
  static const dds_topic_descriptor_t& descriptor() { return nav_msgs_msg_dds__Odometry__desc; }
  static constexpr std::string_view ros_type_hash =
      "RIHS01_3cc97dc7fb7502f8714462c526d369e35b603cfc34d946e3f2eda2766dfec6e0";
};
template <>
struct TopicType<ros::OccupancyGrid> {
  static const dds_topic_descriptor_t& descriptor() { return nav_msgs_msg_dds__OccupancyGrid__desc; }
  static constexpr std::string_view ros_type_hash =
      "RIHS01_8d348150c12913a31ee0ec170fbf25089e4745d17035792a1ba94d6f0bc0cfc7";
};
template <>
struct TopicType<ros::Path> {
  static const dds_topic_descriptor_t& descriptor() { return nav_msgs_msg_dds__Path__desc; }
  static constexpr std::string_view ros_type_hash =
      "RIHS01_1957a5bb3cee5da65c4e52e52b65a93df227efce4c20f8458b36e73066ca334b";
};
template <>
struct TopicType<ros::PoseStamped> {
  static const dds_topic_descriptor_t& descriptor() { return geometry_msgs_msg_dds__PoseStamped__desc; }
  static constexpr std::string_view ros_type_hash =
      "RIHS01_10f3786d7d40fd2b54367835614bff85d4ad3b5dab62bf8bca0cc232d73b4cd8";
};
template <>
struct TopicType<ros::TFMessage> {
  static const dds_topic_descriptor_t& descriptor() { return tf2_msgs_msg_dds__TFMessage__desc; }
  static constexpr std::string_view ros_type_hash =
      "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087";
};

// builtin_interfaces/Time from seconds: whole seconds rounded down, nanoseconds
// in [0, 1e9). Throws InputError for a time that is not finite or does not fit int32 seconds.
ros::Time to_ros_time(double seconds);
double to_seconds(const ros::Time& time);

// Planar poses as ROS 3D poses (z = 0, rotation about z) and back (the yaw of
// the rotation; the quaternion need not be normalised).
ros::Quaternion yaw_to_quaternion(double yaw);
double quaternion_yaw(const ros::Quaternion& q);
ros::Pose to_ros_pose(const Pose2& pose);
ros::Transform to_ros_transform(const Pose2& pose);
Pose2 to_pose2(const ros::Pose& pose);
Pose2 to_pose2(const ros::Transform& transform);

// A TransformStamped parent → child for a planar pose (points at the strings).
ros::TransformStamped to_ros_transform_stamped(double stamp, const std::string& parent, const std::string& child,
                                               const Pose2& parent_from_child);

// The C structs' strings and sequences point at our storage (no copy; DDS
// neither frees nor keeps them): valid while `s` / `v` live and stay unchanged.
inline char* borrow(const std::string& s) { return const_cast<char*>(s.c_str()); }
template <class Sequence, class T>
void borrow(Sequence& sequence, const std::vector<T>& v) {
  sequence._buffer = const_cast<T*>(v.data());
  sequence._length = static_cast<std::uint32_t>(v.size());
  sequence._maximum = sequence._length;
  sequence._release = false;
}

}  // namespace dsswarm::net
