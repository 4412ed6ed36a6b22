// ROS 2 messages in CDR (src/ros2/codec.cpp), as bags store them and rmw
// sends them: the input decoded as every message type; what decodes must
// encode to bytes that decode and encode the same again.
#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/rosbag2/rosbag2_test_writer.hpp"
#include "ros2/codec.hpp"

namespace dsswarm::fuzz {
namespace {

template <typename T>
void decode_as(std::span<const std::uint8_t> bytes) {
  std::vector<std::uint8_t> again;
  expect_clean<InputError>(std::string(T::kTypeName), [&] { again = ros2::encode(ros2::decode<T>(bytes)); });
  if (again.empty()) return;
  try {
    check(ros2::encode(ros2::decode<T>(again)) == again, "a decoded message encodes differently the second time");
  } catch (const InputError& e) {
    fail(std::string("a decoded message does not decode again: ") + e.what());
  }
}

template <typename... T>
void decode_as_each(std::span<const std::uint8_t> bytes) {
  (decode_as<T>(bytes), ...);
}

std::string as_string(const std::vector<std::uint8_t>& bytes) { return {bytes.begin(), bytes.end()}; }

}  // namespace

void write_seeds(Seeds& seeds) {
  seeds.add("scan.cdr", as_string(ros2::encode(rosbag2_test::laser_scan(10.25, {1.0F, 2.0F, 3.0F}))));
  seeds.add("odometry.cdr", as_string(ros2::encode(rosbag2_test::odometry(10.5, 1.0, -2.0, 0.3))));
  seeds.add("tf.cdr", as_string(ros2::encode(rosbag2_test::transform(11.0, "odom", "base_link", 1.0, 2.0, 0.5))));
  ros2::OccupancyGrid grid;
  grid.header.frame_id = "map";
  grid.info.width = 2;
  grid.info.height = 2;
  grid.info.resolution = 0.05F;
  grid.data = {0, 100, -1, 50};
  seeds.add("grid.cdr", as_string(ros2::encode(grid)));
  seeds.dictionary({std::string("\x00\x01\x00\x00", 4), std::string("\x00\x00\x00\x00", 4), "laser", "base_link",
                    "odom", "map"});
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm::ros2;
  dsswarm::fuzz::decode_as_each<Time, Header, Point, Vector3, Quaternion, Pose, PoseStamped, Transform,
                                TransformStamped, PoseWithCovariance, Twist, TwistWithCovariance, MapMetaData,
                                OccupancyGrid, Odometry, Path, LaserScan, TFMessage>({data, size});
  return 0;
}
