#pragma once
// Seed bags for the two ROS1 bag targets, written by the unit tests' writer
// (rosbag_test_writer).
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "io/rosbag/rosbag_test_writer.hpp"

namespace dsswarm::fuzz {

// A bag of the test writer: a laser offset, then two rounds of odometry (on
// the odom topic and /tf) and a scan; or (`scans_only`) the scans alone, the
// smallest bag there is. Each connection carries its full message definition
// (a few KB) in the chunk and in the index, as every recorded bag does.
inline std::string seed_bag(bool scans_only, rosbag_raw::TestBagSpec::Compression compression) {
  using rosbag_raw::TestBagMessage;
  rosbag_raw::TestBagSpec spec;
  spec.compression = compression;
  if (scans_only) {
    spec.odom_topic.clear();
    spec.odometry_on_tf = false;
  } else {
    TestBagMessage offset;
    offset.kind = TestBagMessage::Kind::LaserOffset;
    offset.offset = {true, 0.1, 0.0, 0.0};
    spec.messages.push_back(offset);
  }
  for (int i = 0; i < 2; ++i) {
    if (!scans_only) {
      TestBagMessage odom;
      odom.kind = TestBagMessage::Kind::Odometry;
      odom.odom = {10.0 + i, 0.5 * i, 0.0, 0.1 * i};
      spec.messages.push_back(odom);
    }
    TestBagMessage scan;
    scan.kind = TestBagMessage::Kind::Scan;
    scan.scan.stamp = 10.2 + i;
    scan.scan.angle_min = static_cast<float>(-std::numbers::pi / 2);
    scan.scan.angle_increment = static_cast<float>(std::numbers::pi / 2);
    scan.scan.range_min = 0.1F;
    scan.scan.range_max = 30.0F;
    scan.scan.ranges = {1.0F, 2.0F, 3.0F};
    spec.messages.push_back(scan);
  }
  const auto path = scratch_dir() / "seed.bag";
  rosbag_raw::write_test_bag(path.string(), spec);
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Record header fields (op codes: 0x02 message, 0x03 bag header, 0x04 index,
// 0x05 chunk, 0x06 chunk info, 0x07 connection) and the topics the reader wants.
inline std::vector<std::string> rosbag_dictionary() {
  std::vector<std::string> tokens = {"#ROSBAG V2.0\n", "index_pos=", "conn_count=", "chunk_count=", "conn=",
                                     "topic=", "type=", "md5sum=", "message_definition=", "callerid=",
                                     "latching=1", "compression=none", "compression=bz2", "compression=lz4",
                                     "size=", "time=", "ver=", "count=", "chunk_pos=", "start_time=",
                                     "end_time=", "/scan", "/odom", "/tf", "/tf_static", "base_link", "odom",
                                     "laser", "BZh91AY&SY"};
  for (char op = 2; op <= 7; ++op) tokens.push_back(std::string("op=") + op);
  return tokens;
}

}  // namespace dsswarm::fuzz
