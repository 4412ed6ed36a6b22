#include "ros2/codec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "common/errors.hpp"

namespace dsswarm::ros2 {
namespace {

using Bytes = std::vector<std::uint8_t>;

// The bytes below are worked out by hand from the XCDR1 rules: little endian,
// every primitive aligned to its size counted from the end of the 4-byte
// encapsulation header ("payload offset" in the comments), strings with a
// length that counts the NUL.

LaserScan small_scan() {
  LaserScan m;
  m.header.stamp = {1, 2};
  m.header.frame_id = "laser";
  m.angle_min = -0.5F;
  m.angle_max = 0.5F;
  m.angle_increment = 0.25F;
  m.time_increment = 0.0F;
  m.scan_time = 0.125F;
  m.range_min = 0.0625F;
  m.range_max = 30.0F;
  m.ranges = {1.0F, 2.0F, 1.5F};
  return m;
}

const Bytes kSmallScanBytes = {
    0x00, 0x01, 0x00, 0x00,              // encapsulation CDR_LE, options 0
    0x01, 0x00, 0x00, 0x00,              // payload 0: header.stamp.sec = 1
    0x02, 0x00, 0x00, 0x00,              // 4: header.stamp.nanosec = 2
    0x06, 0x00, 0x00, 0x00,              // 8: header.frame_id length 6 ("laser" + NUL)
    'l',  'a',  's',  'e',  'r',  0x00,  // 12..17: "laser\0"
    0x00, 0x00,                          // 18..19: padding to 4 for the floats
    0x00, 0x00, 0x00, 0xBF,              // 20: angle_min = -0.5 (0xBF000000)
    0x00, 0x00, 0x00, 0x3F,              // 24: angle_max = 0.5 (0x3F000000)
    0x00, 0x00, 0x80, 0x3E,              // 28: angle_increment = 0.25 (0x3E800000)
    0x00, 0x00, 0x00, 0x00,              // 32: time_increment = 0
    0x00, 0x00, 0x00, 0x3E,              // 36: scan_time = 0.125 (0x3E000000)
    0x00, 0x00, 0x80, 0x3D,              // 40: range_min = 0.0625 (0x3D800000)
    0x00, 0x00, 0xF0, 0x41,              // 44: range_max = 30 (0x41F00000)
    0x03, 0x00, 0x00, 0x00,              // 48: ranges count 3
    0x00, 0x00, 0x80, 0x3F,              // 52: 1.0 (0x3F800000)
    0x00, 0x00, 0x00, 0x40,              // 56: 2.0 (0x40000000)
    0x00, 0x00, 0xC0, 0x3F,              // 60: 1.5 (0x3FC00000)
    0x00, 0x00, 0x00, 0x00,              // 64: intensities count 0 (no padding after)
};

OccupancyGrid small_grid() {
  OccupancyGrid m;
  m.header.stamp = {10, 0};
  m.header.frame_id = "map";
  m.info.resolution = 0.25F;
  m.info.width = 2;
  m.info.height = 1;
  m.info.origin.position = {-1.0, 0.5, 0.0};
  m.data = {-1, 100};
  return m;
}

const Bytes kSmallGridBytes = {
    0x00, 0x01, 0x00, 0x00,                          // encapsulation CDR_LE, options 0
    0x0A, 0x00, 0x00, 0x00,                          // payload 0: header.stamp.sec = 10
    0x00, 0x00, 0x00, 0x00,                          // 4: header.stamp.nanosec = 0
    0x04, 0x00, 0x00, 0x00,                          // 8: header.frame_id length 4
    'm',  'a',  'p',  0x00,                          // 12..15: "map\0"
    0x00, 0x00, 0x00, 0x00,                          // 16: info.map_load_time.sec = 0
    0x00, 0x00, 0x00, 0x00,                          // 20: info.map_load_time.nanosec = 0
    0x00, 0x00, 0x80, 0x3E,                          // 24: info.resolution = 0.25
    0x02, 0x00, 0x00, 0x00,                          // 28: info.width = 2
    0x01, 0x00, 0x00, 0x00,                          // 32: info.height = 1
    0x00, 0x00, 0x00, 0x00,                          // 36..39: padding to 8 for the doubles
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF0, 0xBF,  // 40: origin.position.x = -1 (0xBFF0...)
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xE0, 0x3F,  // 48: origin.position.y = 0.5 (0x3FE0...)
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 56: origin.position.z = 0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 64: origin.orientation.x = 0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 72: origin.orientation.y = 0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  // 80: origin.orientation.z = 0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF0, 0x3F,  // 88: origin.orientation.w = 1 (0x3FF0...)
    0x02, 0x00, 0x00, 0x00,                          // 96: data count 2
    0xFF, 0x64,                                      // 100: data = -1, 100
};

TEST(Ros2Codec, LaserScanBytesAreThoseWorkedOutByHand) {
  EXPECT_EQ(encode(small_scan()), kSmallScanBytes);
  EXPECT_EQ(decode<LaserScan>(kSmallScanBytes), small_scan());
}

TEST(Ros2Codec, OccupancyGridBytesAreThoseWorkedOutByHand) {
  EXPECT_EQ(encode(small_grid()), kSmallGridBytes);
  EXPECT_EQ(decode<OccupancyGrid>(kSmallGridBytes), small_grid());
}

TEST(Ros2Codec, TrailingPaddingIsAcceptedButNotMore) {
  Bytes padded = kSmallGridBytes;  // 102 payload bytes: some writers pad to 104
  padded.insert(padded.end(), {0, 0});
  EXPECT_EQ(decode<OccupancyGrid>(padded), small_grid());
  padded.insert(padded.end(), {0, 0});  // 4 extra: not padding
  EXPECT_THROW(decode<OccupancyGrid>(padded), InputError);
}

// Messages with every field set to something distinct.
Header header(std::int32_t sec, const std::string& frame) {
  return {{sec, static_cast<std::uint32_t>(sec) * 1000U + 7U}, frame};
}

Odometry full_odometry() {
  Odometry m;
  m.header = header(1700000000, "odom");
  m.child_frame_id = "base_link";
  m.pose.pose.position = {1.5, -2.25, 0.125};
  m.pose.pose.orientation = {0.0, 0.0, 0.38268343236508978, 0.92387953251128674};
  m.twist.twist.linear = {0.5, 0.0, 0.0};
  m.twist.twist.angular = {0.0, 0.0, -0.1};
  for (std::size_t i = 0; i < 36; ++i) {
    m.pose.covariance[i] = 0.01 * static_cast<double>(i);
    m.twist.covariance[i] = -0.02 * static_cast<double>(i);
  }
  return m;
}

TFMessage full_tf() {
  TFMessage m;
  for (int i = 0; i < 3; ++i) {
    TransformStamped t;
    t.header = header(100 + i, i == 0 ? "odom" : "base_link");
    t.child_frame_id = i == 0 ? "base_link" : "laser_" + std::to_string(i);
    t.transform.translation = {0.1 * i, -0.2 * i, 0.3};
    t.transform.rotation = {0.0, 0.0, 0.1 * i, 1.0};
    m.transforms.push_back(t);
  }
  return m;
}

Path full_path() {
  Path m;
  m.header = header(5, "map");
  for (int i = 0; i < 4; ++i) {
    PoseStamped p;
    p.header = header(5 + i, "map");
    p.pose.position = {static_cast<double>(i), 2.0 * i, 0.0};
    p.pose.orientation = {0.0, 0.0, 0.0, 1.0};
    m.poses.push_back(p);
  }
  return m;
}

LaserScan full_scan() {
  LaserScan m = small_scan();
  m.ranges.assign(361, 0.0F);
  m.intensities.assign(361, 0.0F);
  for (std::size_t i = 0; i < m.ranges.size(); ++i) {
    m.ranges[i] = 0.01F * static_cast<float>(i);
    m.intensities[i] = 100.0F - static_cast<float>(i);
  }
  return m;
}

template <typename T>
void expect_round_trip(const T& m) {
  EXPECT_EQ(decode<T>(encode(m)), m) << T::kTypeName;
}

TEST(Ros2Codec, EveryMessageRoundTrips) {
  expect_round_trip(full_scan());
  expect_round_trip(small_grid());
  expect_round_trip(full_odometry());
  expect_round_trip(full_tf());
  expect_round_trip(full_path());
  expect_round_trip(full_path().poses[1]);
  expect_round_trip(full_tf().transforms[2]);
  expect_round_trip(full_odometry().pose);
  expect_round_trip(full_odometry().twist);
  expect_round_trip(small_grid().info);
  expect_round_trip(header(3, "x"));
  expect_round_trip(Time{-5, 999999999});
  expect_round_trip(TFMessage{});
  expect_round_trip(OccupancyGrid{});
  expect_round_trip(LaserScan{});
}

std::string decode_error(const Bytes& bytes, auto decoder) {
  try {
    decoder(bytes);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "decoded without error";
  return {};
}

TEST(Ros2Codec, EveryTruncationIsAnInputErrorNamingAField) {
  const Bytes bytes = encode(full_tf());
  for (std::size_t keep = 0; keep < bytes.size(); ++keep) {
    const Bytes cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(keep));
    const std::string message =
        decode_error(cut, [](const Bytes& b) { return decode<TFMessage>(b); });
    EXPECT_NE(message.find("tf2_msgs/msg/TFMessage"), std::string::npos) << message;
    if (keep >= 4) {
      EXPECT_NE(message.find("field transforms"), std::string::npos) << message;
    }
  }
  // The path names the element and the nested field.
  const Bytes cut(bytes.begin(), bytes.end() - 60);
  const std::string message =
      decode_error(cut, [](const Bytes& b) { return decode<TFMessage>(b); });
  EXPECT_NE(message.find("transforms[2].transform.translation"), std::string::npos) << message;
}

// Overwrites the little-endian uint32 at `payload_offset` (after the header).
Bytes with_u32(Bytes bytes, std::size_t payload_offset, std::uint32_t value) {
  for (std::size_t i = 0; i < 4; ++i) {
    bytes.at(4 + payload_offset + i) = static_cast<std::uint8_t>(value >> (8 * i));
  }
  return bytes;
}

TEST(Ros2Codec, DamagedLengthsAreRefusedBeforeAllocating) {
  const auto scan = [](const Bytes& b) { return decode<LaserScan>(b); };
  // ranges count (payload offset 48) of 2^30: would be 4 GB of floats.
  std::string message = decode_error(with_u32(kSmallScanBytes, 48, 1U << 30), scan);
  EXPECT_NE(message.find("field ranges: sequence of 1073741824 elements"), std::string::npos)
      << message;
  // frame_id length (payload offset 8): past the end, then beyond the string cap.
  message = decode_error(with_u32(kSmallScanBytes, 8, 1000), scan);
  EXPECT_NE(message.find("field header.frame_id: needs 1000 bytes"), std::string::npos) << message;
  message = decode_error(with_u32(kSmallScanBytes, 8, 0xFFFFFFFFU), scan);
  EXPECT_NE(message.find("exceeds the cap"), std::string::npos) << message;
  // A string whose last byte is not NUL.
  Bytes no_nul = kSmallScanBytes;
  no_nul.at(4 + 17) = 'x';
  message = decode_error(no_nul, scan);
  EXPECT_NE(message.find("header.frame_id: string is not NUL-terminated"), std::string::npos)
      << message;
  // A TFMessage claiming 2^31 transforms in 40 bytes.
  Bytes tf = encode(TFMessage{});
  tf.resize(44, 0);
  message = decode_error(with_u32(tf, 0, 1U << 31),
                         [](const Bytes& b) { return decode<TFMessage>(b); });
  EXPECT_NE(message.find("field transforms: sequence of 2147483648 elements"), std::string::npos)
      << message;
}

TEST(Ros2Codec, OtherEncapsulationsAreRefused) {
  const auto scan = [](const Bytes& b) { return decode<LaserScan>(b); };
  Bytes big_endian = kSmallScanBytes;
  big_endian[1] = 0x00;
  EXPECT_NE(decode_error(big_endian, scan).find("big-endian"), std::string::npos);
  Bytes xcdr2 = kSmallScanBytes;
  xcdr2[1] = 0x07;
  EXPECT_NE(decode_error(xcdr2, scan).find("00 07"), std::string::npos);
  EXPECT_NE(decode_error(Bytes{0x00}, scan).find("too short"), std::string::npos);
}

TEST(Ros2Codec, OtherMessageTypesDoNotPassForEachOther) {
  // An Odometry read as a LaserScan or a TFMessage: the lengths do not add up.
  const Bytes odometry = encode(full_odometry());
  EXPECT_THROW(decode<LaserScan>(odometry), InputError);
  EXPECT_THROW(decode<TFMessage>(odometry), InputError);
  EXPECT_THROW(decode<Odometry>(encode(full_scan())), InputError);
}

TEST(Ros2Codec, RandomBytesGiveInputErrorsOrMessagesNeverCrashes) {
  std::mt19937 rng(42);
  std::size_t errors = 0;
  for (int round = 0; round < 3000; ++round) {
    Bytes bytes = round % 2 == 0 ? encode(full_tf()) : encode(full_odometry());
    for (int flips = 0; flips < 1 + round % 5; ++flips) {
      bytes[rng() % bytes.size()] = static_cast<std::uint8_t>(rng());
    }
    bytes.resize(rng() % (bytes.size() + 1));
    for (const auto& decoder :
         {+[](const Bytes& b) { (void)decode<TFMessage>(b); },
          +[](const Bytes& b) { (void)decode<Odometry>(b); },
          +[](const Bytes& b) { (void)decode<LaserScan>(b); }}) {
      try {
        decoder(bytes);
      } catch (const InputError&) {
        ++errors;
      }
    }
  }
  EXPECT_GT(errors, 6000U);  // nearly every cut or damaged message is refused
}

TEST(Ros2Time, SecondsRoundTripAtNanosecondResolution) {
  EXPECT_EQ(time_from_seconds(1134864629.895182), (Time{1134864629, 895181894}));
  EXPECT_EQ(to_seconds(time_from_seconds(1134864629.895182)), 1134864629.895182);
  EXPECT_EQ(time_from_seconds(-1.25), (Time{-2, 750000000}));
  EXPECT_EQ(time_from_seconds(2.9999999999), (Time{3, 0}));
  EXPECT_THROW(time_from_seconds(1e10), InputError);
  EXPECT_THROW(time_from_seconds(std::nan("")), InputError);
}

}  // namespace
}  // namespace dsswarm::ros2
