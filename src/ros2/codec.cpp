// One write and one read function per message, field by field in the order
// the .msg files declare them; nested messages are plain members (XCDR1 has no
// headers for final structs).
#include "ros2/codec.hpp"

#include <fmt/format.h>

#include <string>

#include "ros2/cdr.hpp"

namespace dsswarm::ros2 {
namespace {

using Scope = CdrReader::Scope;

// Fewest bytes an element of a struct sequence takes (alignment padding not
// counted), to refuse damaged counts before allocating.
constexpr std::size_t kMinPoseStampedBytes = 8 + 4 + 7 * 8;       // stamp, frame_id, pose
constexpr std::size_t kMinTransformStampedBytes = 8 + 4 + 4 + 7 * 8;  // + child_frame_id

// ------------------------------------------------------------------ write

void put(CdrWriter& w, const Time& m) {
  w.put(m.sec);
  w.put(m.nanosec);
}
void put(CdrWriter& w, const Header& m) {
  put(w, m.stamp);
  w.put_string(m.frame_id);
}
void put(CdrWriter& w, const Point& m) {
  w.put(m.x);
  w.put(m.y);
  w.put(m.z);
}
void put(CdrWriter& w, const Vector3& m) {
  w.put(m.x);
  w.put(m.y);
  w.put(m.z);
}
void put(CdrWriter& w, const Quaternion& m) {
  w.put(m.x);
  w.put(m.y);
  w.put(m.z);
  w.put(m.w);
}
void put(CdrWriter& w, const Pose& m) {
  put(w, m.position);
  put(w, m.orientation);
}
void put(CdrWriter& w, const PoseStamped& m) {
  put(w, m.header);
  put(w, m.pose);
}
void put(CdrWriter& w, const Transform& m) {
  put(w, m.translation);
  put(w, m.rotation);
}
void put(CdrWriter& w, const TransformStamped& m) {
  put(w, m.header);
  w.put_string(m.child_frame_id);
  put(w, m.transform);
}
void put(CdrWriter& w, const PoseWithCovariance& m) {
  put(w, m.pose);
  w.put_elements(std::span<const double>(m.covariance));
}
void put(CdrWriter& w, const Twist& m) {
  put(w, m.linear);
  put(w, m.angular);
}
void put(CdrWriter& w, const TwistWithCovariance& m) {
  put(w, m.twist);
  w.put_elements(std::span<const double>(m.covariance));
}
void put(CdrWriter& w, const MapMetaData& m) {
  put(w, m.map_load_time);
  w.put(m.resolution);
  w.put(m.width);
  w.put(m.height);
  put(w, m.origin);
}
void put(CdrWriter& w, const OccupancyGrid& m) {
  put(w, m.header);
  put(w, m.info);
  w.put_sequence_length(m.data.size());
  w.put_elements(std::span<const std::int8_t>(m.data));
}
void put(CdrWriter& w, const Odometry& m) {
  put(w, m.header);
  w.put_string(m.child_frame_id);
  put(w, m.pose);
  put(w, m.twist);
}
void put(CdrWriter& w, const Path& m) {
  put(w, m.header);
  w.put_sequence_length(m.poses.size());
  for (const PoseStamped& p : m.poses) put(w, p);
}
void put(CdrWriter& w, const LaserScan& m) {
  put(w, m.header);
  for (const float f : {m.angle_min, m.angle_max, m.angle_increment, m.time_increment, m.scan_time,
                        m.range_min, m.range_max}) {
    w.put(f);
  }
  w.put_sequence_length(m.ranges.size());
  w.put_elements(std::span<const float>(m.ranges));
  w.put_sequence_length(m.intensities.size());
  w.put_elements(std::span<const float>(m.intensities));
}
void put(CdrWriter& w, const TFMessage& m) {
  w.put_sequence_length(m.transforms.size());
  for (const TransformStamped& t : m.transforms) put(w, t);
}

// ------------------------------------------------------------------ read

// The readers call each other through templates: declare them all first.
void get(CdrReader& r, Time& m);
void get(CdrReader& r, Header& m);
void get(CdrReader& r, Point& m);
void get(CdrReader& r, Vector3& m);
void get(CdrReader& r, Quaternion& m);
void get(CdrReader& r, Pose& m);
void get(CdrReader& r, PoseStamped& m);
void get(CdrReader& r, Transform& m);
void get(CdrReader& r, TransformStamped& m);
void get(CdrReader& r, PoseWithCovariance& m);
void get(CdrReader& r, Twist& m);
void get(CdrReader& r, TwistWithCovariance& m);
void get(CdrReader& r, MapMetaData& m);
void get(CdrReader& r, OccupancyGrid& m);
void get(CdrReader& r, Odometry& m);
void get(CdrReader& r, Path& m);
void get(CdrReader& r, LaserScan& m);
void get(CdrReader& r, TFMessage& m);

// A member `name` of a struct, read with its own scope.
template <typename T>
void get_member(CdrReader& r, const char* name, T& m) {
  const Scope s(r, name);
  get(r, m);
}

template <typename T>
void get_primitive_sequence(CdrReader& r, const char* field, std::vector<T>& out) {
  out.resize(r.get_sequence_length(field, sizeof(T)));
  r.get_elements(field, std::span<T>(out));
}

void get(CdrReader& r, Time& m) {
  m.sec = r.get<std::int32_t>("sec");
  m.nanosec = r.get<std::uint32_t>("nanosec");
}
void get(CdrReader& r, Header& m) {
  get_member(r, "stamp", m.stamp);
  m.frame_id = r.get_string("frame_id");
}
void get(CdrReader& r, Point& m) {
  m.x = r.get<double>("x");
  m.y = r.get<double>("y");
  m.z = r.get<double>("z");
}
void get(CdrReader& r, Vector3& m) {
  m.x = r.get<double>("x");
  m.y = r.get<double>("y");
  m.z = r.get<double>("z");
}
void get(CdrReader& r, Quaternion& m) {
  m.x = r.get<double>("x");
  m.y = r.get<double>("y");
  m.z = r.get<double>("z");
  m.w = r.get<double>("w");
}
void get(CdrReader& r, Pose& m) {
  get_member(r, "position", m.position);
  get_member(r, "orientation", m.orientation);
}
void get(CdrReader& r, PoseStamped& m) {
  get_member(r, "header", m.header);
  get_member(r, "pose", m.pose);
}
void get(CdrReader& r, Transform& m) {
  get_member(r, "translation", m.translation);
  get_member(r, "rotation", m.rotation);
}
void get(CdrReader& r, TransformStamped& m) {
  get_member(r, "header", m.header);
  m.child_frame_id = r.get_string("child_frame_id");
  get_member(r, "transform", m.transform);
}
void get(CdrReader& r, PoseWithCovariance& m) {
  get_member(r, "pose", m.pose);
  r.get_elements("covariance", std::span<double>(m.covariance));
}
void get(CdrReader& r, Twist& m) {
  get_member(r, "linear", m.linear);
  get_member(r, "angular", m.angular);
}
void get(CdrReader& r, TwistWithCovariance& m) {
  get_member(r, "twist", m.twist);
  r.get_elements("covariance", std::span<double>(m.covariance));
}
void get(CdrReader& r, MapMetaData& m) {
  get_member(r, "map_load_time", m.map_load_time);
  m.resolution = r.get<float>("resolution");
  m.width = r.get<std::uint32_t>("width");
  m.height = r.get<std::uint32_t>("height");
  get_member(r, "origin", m.origin);
}
void get(CdrReader& r, OccupancyGrid& m) {
  get_member(r, "header", m.header);
  get_member(r, "info", m.info);
  get_primitive_sequence(r, "data", m.data);
}
void get(CdrReader& r, Odometry& m) {
  get_member(r, "header", m.header);
  m.child_frame_id = r.get_string("child_frame_id");
  get_member(r, "pose", m.pose);
  get_member(r, "twist", m.twist);
}
// Elements are appended as they decode (no reserve): memory grows with the
// bytes actually present, whatever the count says.
template <typename T>
void get_struct_sequence(CdrReader& r, const char* field, std::size_t min_bytes,
                         std::vector<T>& out) {
  const std::size_t n = r.get_sequence_length(field, min_bytes);
  out.clear();
  const Scope s(r, field);
  for (std::size_t i = 0; i < n; ++i) {
    const Scope element(r, fmt::format("[{}]", i));
    get(r, out.emplace_back());
  }
}
void get(CdrReader& r, Path& m) {
  get_member(r, "header", m.header);
  get_struct_sequence(r, "poses", kMinPoseStampedBytes, m.poses);
}
void get(CdrReader& r, LaserScan& m) {
  get_member(r, "header", m.header);
  m.angle_min = r.get<float>("angle_min");
  m.angle_max = r.get<float>("angle_max");
  m.angle_increment = r.get<float>("angle_increment");
  m.time_increment = r.get<float>("time_increment");
  m.scan_time = r.get<float>("scan_time");
  m.range_min = r.get<float>("range_min");
  m.range_max = r.get<float>("range_max");
  get_primitive_sequence(r, "ranges", m.ranges);
  get_primitive_sequence(r, "intensities", m.intensities);
}
void get(CdrReader& r, TFMessage& m) {
  get_struct_sequence(r, "transforms", kMinTransformStampedBytes, m.transforms);
}

template <typename T>
std::vector<std::uint8_t> encode_message(const T& m) {
  CdrWriter w;
  put(w, m);
  return std::move(w).finish();
}

}  // namespace

template <typename T>
T decode(std::span<const std::uint8_t> bytes) {
  CdrReader r(bytes, T::kTypeName);
  T m;
  get(r, m);
  r.finish();
  return m;
}

#define DSSWARM_ROS2_MESSAGE(T)                                                    \
  std::vector<std::uint8_t> encode(const T& m) { return encode_message(m); } \
  template T decode<T>(std::span<const std::uint8_t>);
DSSWARM_ROS2_MESSAGE(Time)
DSSWARM_ROS2_MESSAGE(Header)
DSSWARM_ROS2_MESSAGE(Point)
DSSWARM_ROS2_MESSAGE(Vector3)
DSSWARM_ROS2_MESSAGE(Quaternion)
DSSWARM_ROS2_MESSAGE(Pose)
DSSWARM_ROS2_MESSAGE(PoseStamped)
DSSWARM_ROS2_MESSAGE(Transform)
DSSWARM_ROS2_MESSAGE(TransformStamped)
DSSWARM_ROS2_MESSAGE(PoseWithCovariance)
DSSWARM_ROS2_MESSAGE(Twist)
DSSWARM_ROS2_MESSAGE(TwistWithCovariance)
DSSWARM_ROS2_MESSAGE(MapMetaData)
DSSWARM_ROS2_MESSAGE(OccupancyGrid)
DSSWARM_ROS2_MESSAGE(Odometry)
DSSWARM_ROS2_MESSAGE(Path)
DSSWARM_ROS2_MESSAGE(LaserScan)
DSSWARM_ROS2_MESSAGE(TFMessage)
#undef DSSWARM_ROS2_MESSAGE

}  // namespace dsswarm::ros2
