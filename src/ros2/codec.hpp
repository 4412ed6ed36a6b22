#pragma once
// CDR bytes of ROS 2 messages (cdr.hpp) and back: what a ROS 2 bag stores and
// what rmw puts on the DDS wire, encapsulation header included.
//
//   std::vector<std::uint8_t> bytes = ros2::encode(scan);
//   ros2::LaserScan again = ros2::decode<ros2::LaserScan>(bytes);
//
// decode<T> throws InputError naming the type, the field and the byte offset
// for truncated or damaged data, or bytes of another type (left over).
#include <cstdint>
#include <span>
#include <vector>

#include "ros2/messages.hpp"

namespace dsswarm::ros2 {

std::vector<std::uint8_t> encode(const Time& m);
std::vector<std::uint8_t> encode(const Header& m);
std::vector<std::uint8_t> encode(const Point& m);
std::vector<std::uint8_t> encode(const Vector3& m);
std::vector<std::uint8_t> encode(const Quaternion& m);
std::vector<std::uint8_t> encode(const Pose& m);
std::vector<std::uint8_t> encode(const PoseStamped& m);
std::vector<std::uint8_t> encode(const Transform& m);
std::vector<std::uint8_t> encode(const TransformStamped& m);
std::vector<std::uint8_t> encode(const PoseWithCovariance& m);
std::vector<std::uint8_t> encode(const Twist& m);
std::vector<std::uint8_t> encode(const TwistWithCovariance& m);
std::vector<std::uint8_t> encode(const MapMetaData& m);
std::vector<std::uint8_t> encode(const OccupancyGrid& m);
std::vector<std::uint8_t> encode(const Odometry& m);
std::vector<std::uint8_t> encode(const Path& m);
std::vector<std::uint8_t> encode(const LaserScan& m);
std::vector<std::uint8_t> encode(const TFMessage& m);

// Defined for every message type above.
template <typename T>
T decode(std::span<const std::uint8_t> bytes);

}  // namespace dsswarm::ros2
