#pragma once
// ROS 2 messages as plain structs, field for field as ROS 2 defines them
// (ros2/common_interfaces, rcl_interfaces, geometry2). The same layouts serve
// bag files (io/rosbag2) and the live DDS topics. Note ROS 2's Header has no
// `seq` (ROS 1's does), and Quaternion defaults to the identity (w = 1).
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dsswarm::ros2 {

struct Time {
  static constexpr std::string_view kTypeName = "builtin_interfaces/msg/Time";
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  bool operator==(const Time&) const = default;
};

struct Header {
  static constexpr std::string_view kTypeName = "std_msgs/msg/Header";
  Time stamp;
  std::string frame_id;
  bool operator==(const Header&) const = default;
};

struct Point {
  static constexpr std::string_view kTypeName = "geometry_msgs/msg/Point";
  double x = 0.0, y = 0.0, z = 0.0;
  bool operator==(const Point&) const = default;
};

struct Vector3 {
  static constexpr std::string_view kTypeName = "geometry_msgs/msg/Vector3";
  double x = 0.0, y = 0.0, z = 0.0;
  bool operator==(const Vector3&) const = default;
};

struct Quaternion {
  static constexpr std::string_view kTypeName = "geometry_msgs/msg/Quaternion";
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
  bool operator==(const Quaternion&) const = default;
};

struct Pose {
  static constexpr std::string_view kTypeName = "geometry_msgs/msg/Pose";
  Point position;
  Quaternion orientation;
  bool operator==(const Pose&) const = default;
};

struct PoseStamped {
  static constexpr std::string_view kTypeName = "geometry_msgs/msg/PoseStamped";
  Header header;
  Pose pose;
  bool operator==(const PoseStamped&) const = default;
};

struct Transform {
  static constexpr std::string_view kTypeName = "geometry_msgs/msg/Transform";
  Vector3 translation;
  Quaternion rotation;
  bool operator==(const Transform&) const = default;
};

// The transform from header.frame_id (parent) to child_frame_id.
struct TransformStamped {
  static constexpr std::string_view kTypeName = "geometry_msgs/msg/TransformStamped";
  Header header;
  std::string child_frame_id;
  Transform transform;
  bool operator==(const TransformStamped&) const = default;
};

// Covariance: row-major 6x6 over x, y, z, rotation about x, y, z.
struct PoseWithCovariance {
  static constexpr std::string_view kTypeName = "geometry_msgs/msg/PoseWithCovariance";
  Pose pose;
  std::array<double, 36> covariance{};
  bool operator==(const PoseWithCovariance&) const = default;
};

struct Twist {
  static constexpr std::string_view kTypeName = "geometry_msgs/msg/Twist";
  Vector3 linear;
  Vector3 angular;
  bool operator==(const Twist&) const = default;
};

struct TwistWithCovariance {
  static constexpr std::string_view kTypeName = "geometry_msgs/msg/TwistWithCovariance";
  Twist twist;
  std::array<double, 36> covariance{};
  bool operator==(const TwistWithCovariance&) const = default;
};

struct MapMetaData {
  static constexpr std::string_view kTypeName = "nav_msgs/msg/MapMetaData";
  Time map_load_time;
  float resolution = 0.0F;  // m/cell
  std::uint32_t width = 0;  // cells
  std::uint32_t height = 0;
  Pose origin;  // pose of cell (0, 0)'s corner in the map frame
  bool operator==(const MapMetaData&) const = default;
};

// Cells row-major from the origin, -1 unknown, 0..100 occupancy.
struct OccupancyGrid {
  static constexpr std::string_view kTypeName = "nav_msgs/msg/OccupancyGrid";
  Header header;
  MapMetaData info;
  std::vector<std::int8_t> data;
  bool operator==(const OccupancyGrid&) const = default;
};

// Pose in header.frame_id, twist in child_frame_id.
struct Odometry {
  static constexpr std::string_view kTypeName = "nav_msgs/msg/Odometry";
  Header header;
  std::string child_frame_id;
  PoseWithCovariance pose;
  TwistWithCovariance twist;
  bool operator==(const Odometry&) const = default;
};

struct Path {
  static constexpr std::string_view kTypeName = "nav_msgs/msg/Path";
  Header header;
  std::vector<PoseStamped> poses;
  bool operator==(const Path&) const = default;
};

struct LaserScan {
  static constexpr std::string_view kTypeName = "sensor_msgs/msg/LaserScan";
  Header header;
  float angle_min = 0.0F;        // rad
  float angle_max = 0.0F;        // rad
  float angle_increment = 0.0F;  // rad
  float time_increment = 0.0F;   // s between measurements
  float scan_time = 0.0F;        // s between scans
  float range_min = 0.0F;        // m
  float range_max = 0.0F;        // m
  std::vector<float> ranges;
  std::vector<float> intensities;
  bool operator==(const LaserScan&) const = default;
};

// The type of /tf and /tf_static.
struct TFMessage {
  static constexpr std::string_view kTypeName = "tf2_msgs/msg/TFMessage";
  std::vector<TransformStamped> transforms;
  bool operator==(const TFMessage&) const = default;
};

// Seconds as ROS 1 and rclcpp compute them: sec + nanosec * 1e-9.
double to_seconds(const Time& t);

// The Time nearest to `seconds` (nanosecond resolution). Throws InputError
// unless the value is finite and its seconds fit an int32.
Time time_from_seconds(double seconds);

}  // namespace dsswarm::ros2
