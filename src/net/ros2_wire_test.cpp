// The ROS 2 wire format: the serialized bytes of small messages against bytes
// worked out by hand from the XCDR1 rules (little endian; primitives aligned
// to their size, 8-byte ones to 8, relative to the start of the body; strings
// as uint32 length with the NUL, then the characters; sequences as uint32
// count, then the elements). XCDR2 would align doubles to 4 only.
#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "net/net_test_util.hpp"
#include "net/qos.hpp"
#include "net/ros2_types.hpp"

namespace dsswarm::net {
namespace {

using namespace std::chrono_literals;
using Bytes = std::vector<std::uint8_t>;

// Writes `sample` and returns what a reader receives, still serialized.
template <class T>
Bytes serialized(const T& sample) {
  Participant p(test::loopback_config());
  Topic<T> topic(p, "rt" + test::test_namespace() + "/wire");
  Writer<T> writer(topic, ros_default(1));
  Reader<T> reader(topic, ros_default(1));
  EXPECT_TRUE(writer.wait_for_readers(1, 5s));
  writer.write(sample);
  EXPECT_TRUE(reader.wait(5s));
  ddsi_serdata* data = nullptr;
  dds_sample_info_t info;
  EXPECT_EQ(dds_takecdr(reader.handle(), &data, 1, &info, DDS_ANY_STATE), 1);
  if (data == nullptr) return {};
  Bytes bytes(ddsi_serdata_size(data));
  ddsi_serdata_to_ser(data, 0, bytes.size(), bytes.data());
  ddsi_serdata_unref(data);
  return bytes;
}

void append(Bytes& b, std::initializer_list<int> values) {
  for (int v : values) b.push_back(static_cast<std::uint8_t>(v));
}

TEST(RosWireFormat, LaserScanIsPlainLittleEndianXcdr1) {
  const std::string frame = "ab";
  const std::vector<float> ranges = {1.0f, 2.0f};
  ros::LaserScan scan{};
  scan.header.stamp = {1, 2};
  scan.header.frame_id = borrow(frame);
  scan.angle_min = 0.5f;
  scan.angle_max = 1.0f;
  scan.angle_increment = 0.25f;
  scan.range_min = 0.125f;
  scan.range_max = 8.0f;
  borrow(scan.ranges, ranges);

  Bytes want;
  append(want, {0x00, 0x01, 0x00, 0x00});              // encapsulation CDR_LE, no padding
  append(want, {1, 0, 0, 0, 2, 0, 0, 0});               // stamp: sec 1, nanosec 2
  append(want, {3, 0, 0, 0, 'a', 'b', 0, 0});          // "ab" + NUL, then 1 byte to align the floats
  append(want, {0, 0, 0, 0x3f, 0, 0, 0x80, 0x3f});     // angle_min 0.5, angle_max 1
  append(want, {0, 0, 0x80, 0x3e, 0, 0, 0, 0});        // angle_increment 0.25, time_increment 0
  append(want, {0, 0, 0, 0, 0, 0, 0, 0x3e});           // scan_time 0, range_min 0.125
  append(want, {0, 0, 0, 0x41, 2, 0, 0, 0});           // range_max 8, 2 ranges
  append(want, {0, 0, 0x80, 0x3f, 0, 0, 0, 0x40});     // 1, 2
  append(want, {0, 0, 0, 0});                          // no intensities
  EXPECT_EQ(serialized(scan), want);
}

TEST(RosWireFormat, OccupancyGridAlignsDoublesToEight) {
  const std::string frame = "map";
  const std::vector<std::int8_t> cells = {-1, 100};
  ros::OccupancyGrid grid{};
  grid.header.stamp = {3, 4};
  grid.header.frame_id = borrow(frame);
  grid.info.map_load_time = {3, 4};
  grid.info.resolution = 0.5f;
  grid.info.width = 2;
  grid.info.height = 1;
  grid.info.origin = to_ros_pose(Pose2(1.0, 2.0, 0.0));
  borrow(grid.data, cells);

  Bytes want;
  append(want, {0x00, 0x01, 0x00, 0x02});              // CDR_LE; the body is padded by 2 bytes at the end
  append(want, {3, 0, 0, 0, 4, 0, 0, 0});               // stamp
  append(want, {4, 0, 0, 0, 'm', 'a', 'p', 0});        // "map" + NUL
  append(want, {3, 0, 0, 0, 4, 0, 0, 0});               // map_load_time
  append(want, {0, 0, 0, 0x3f, 2, 0, 0, 0});           // resolution 0.5, width 2
  append(want, {1, 0, 0, 0, 0, 0, 0, 0});              // height 1, then 4 bytes to align the doubles to 8
  append(want, {0, 0, 0, 0, 0, 0, 0xf0, 0x3f});        // origin x = 1
  append(want, {0, 0, 0, 0, 0, 0, 0, 0x40});           // y = 2
  for (int i = 0; i < 4; ++i) append(want, {0, 0, 0, 0, 0, 0, 0, 0});  // z, qx, qy, qz
  append(want, {0, 0, 0, 0, 0, 0, 0xf0, 0x3f});        // qw = 1
  append(want, {2, 0, 0, 0, 0xff, 0x64, 0, 0});        // 2 cells: -1, 100; the 2 padding bytes
  EXPECT_EQ(serialized(grid), want);
}

}  // namespace
}  // namespace dsswarm::net
