#include "io/rosbag/rosbag_reader.hpp"

#include <gtest/gtest.h>

#include "common/test_files.hpp"
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/rosbag/bag_structure.hpp"
#include "io/rosbag/rosbag_test_util.hpp"
#include "io/rosbag/rosbag_test_writer.hpp"

namespace dsswarm {
namespace {

using test::fresh_dir;

namespace fs = std::filesystem;
using rosbag_raw::RawOdom;
using rosbag_raw::RawScan;
using rosbag_raw::RawStatic;
using rosbag_raw::TestBagMessage;
using rosbag_raw::TestBagSpec;

using namespace rosbag_test;  // rosbag_test_util.hpp

// ---------------------------------------------------------------- bags written here

TestBagMessage scan_at(double stamp, std::vector<float> ranges) {
  TestBagMessage m;
  m.kind = TestBagMessage::Kind::Scan;
  m.scan.stamp = stamp;
  m.scan.angle_min = static_cast<float>(-kPi / 2);
  m.scan.angle_increment = static_cast<float>(kPi / 2);
  m.scan.range_min = 0.1F;
  m.scan.range_max = 30.0F;
  m.scan.ranges = std::move(ranges);
  return m;
}

TestBagMessage odom_at(double stamp, double x, double y, double theta) {
  TestBagMessage m;
  m.kind = TestBagMessage::Kind::Odometry;
  m.odom = RawOdom{stamp, x, y, theta};
  return m;
}

TestBagMessage laser_offset(double x, double y, double theta) {
  TestBagMessage m;
  m.kind = TestBagMessage::Kind::LaserOffset;
  m.offset = RawStatic{true, x, y, theta};
  return m;
}

// Odometry at 10, 11, 12 s (one glitched record in between, stamped 13.5),
// and five scans of which the third is stamped 0.4 s ahead of its true time.
TestBagSpec small_spec() {
  TestBagSpec spec;
  spec.messages = {
      laser_offset(0.25, -0.1, 0.05),
      odom_at(10.0, 0.0, 0.0, 0.0),
      scan_at(10.2, {1.0F, 2.0F, 3.0F}),
      scan_at(10.4, {1.5F, 2.5F, 3.5F}),
      odom_at(11.0, 1.0, 2.0, kPi / 2),
      scan_at(10.9, {4.0F, 40.0F, 0.0F}),  // stamp jumps ahead of the true 10.5 s
      odom_at(13.5, 50.0, 50.0, -1.0),     // glitch: must not be interpolated through
      scan_at(10.6, {5.0F, 5.0F, 5.0F}),
      odom_at(12.0, 1.0, 4.0, kPi),
      scan_at(11.5, {6.0F, 6.0F, 6.0F}),
  };
  return spec;
}

fs::path write_bag(const std::string& name, const TestBagSpec& spec) {
  const fs::path path = fresh_dir("rosbag_" + name) / (name + ".bag");
  rosbag_raw::write_test_bag(path.string(), spec);
  return path;
}

TEST(RosbagReader, ReadsScansInFileOrderWithInterpolatedOdometry) {
  const SensorLog log = read_rosbag(write_bag("small", small_spec()));
  ASSERT_EQ(log.scans.size(), 5U);
  EXPECT_NE(log.source.find("small.bag"), std::string::npos);

  // File order, original stamps (the bag index sorts them by time).
  const std::vector<double> stamps{10.2, 10.4, 10.9, 10.6, 11.5};
  for (std::size_t i = 0; i < stamps.size(); ++i)
    EXPECT_NEAR(log.scans[i].timestamp, stamps[i], 1e-9) << i;
  const LaserScan& third = log.scans[2];
  EXPECT_EQ(third.ranges, (std::vector<float>{4.0F, 40.0F, 0.0F}));
  EXPECT_NEAR(third.angle_min, -kPi / 2, 1e-6);
  EXPECT_NEAR(third.angle_increment, kPi / 2, 1e-6);
  EXPECT_FLOAT_EQ(static_cast<float>(third.range_min), 0.1F);
  EXPECT_FLOAT_EQ(static_cast<float>(third.range_max), 30.0F);
  EXPECT_EQ(third.valid_count(), 1U);  // 40 m is beyond range_max, 0 below range_min

  for (const LaserScan& s : log.scans) {
    EXPECT_NEAR(s.laser_offset.x, 0.25, 1e-12);
    EXPECT_NEAR(s.laser_offset.y, -0.1, 1e-12);
    EXPECT_NEAR(s.laser_offset.theta, 0.05, 1e-12);
  }

  // Between odometry at 10 s (0,0,0) and 11 s (1,2,pi/2); the glitched odometry record is skipped.
  expect_pose_near(log.scans[0].odometry, Pose2(0.2, 0.4, 0.2 * kPi / 2), 1e-9);
  expect_pose_near(log.scans[1].odometry, Pose2(0.4, 0.8, 0.4 * kPi / 2), 1e-9);
  // The scan stamped 10.9 s sits between 10.4 and 10.6 in the file: looked up at 10.5 s.
  expect_pose_near(log.scans[2].odometry, Pose2(0.5, 1.0, 0.5 * kPi / 2), 1e-9);
  expect_pose_near(log.scans[3].odometry, Pose2(0.6, 1.2, 0.6 * kPi / 2), 1e-9);
  // Between 11 s (1,2,pi/2) and 12 s (1,4,pi), not via the glitch at 13.5 s.
  expect_pose_near(log.scans[4].odometry, Pose2(1.0, 3.0, 0.75 * kPi), 1e-9);

  EXPECT_TRUE(has_warning(log, "1 of 5 scan timestamps run backwards (kept in file order)"))
      << joined(log.warnings);
  EXPECT_TRUE(has_warning(log, "1 of 4 odometry stamps on /odom are out of time order"))
      << joined(log.warnings);
  EXPECT_TRUE(has_warning(log, "1 scans with out-of-order stamps")) << joined(log.warnings);
  EXPECT_EQ(log.warnings.size(), 3U) << joined(log.warnings);
}

TEST(RosbagReader, CompressedChunksReadTheSame) {
  const SensorLog plain = read_rosbag(write_bag("small_plain", small_spec()));
  for (const auto compression : {TestBagSpec::Compression::Bz2, TestBagSpec::Compression::Lz4}) {
    TestBagSpec spec = small_spec();
    spec.compression = compression;
    const SensorLog compressed = read_rosbag(write_bag("small_compressed", spec));
    ASSERT_EQ(compressed.scans.size(), plain.scans.size());
    for (std::size_t i = 0; i < plain.scans.size(); ++i) {
      EXPECT_EQ(compressed.scans[i].timestamp, plain.scans[i].timestamp);
      EXPECT_EQ(compressed.scans[i].ranges, plain.scans[i].ranges);
      ASSERT_TRUE(compressed.scans[i].odometry.has_value());
      EXPECT_EQ(compressed.scans[i].odometry->x, plain.scans[i].odometry->x);
    }
    EXPECT_EQ(compressed.warnings.size(), plain.warnings.size());
  }
}

TEST(RosbagReader, OdometryFromTfWhenAsked) {
  TestBagSpec spec = small_spec();
  spec.odom_topic.clear();  // odometry only as odom -> base_link on /tf
  const fs::path path = write_bag("tf_only", spec);

  const SensorLog without = read_rosbag(path);
  ASSERT_EQ(without.scans.size(), 5U);
  for (const LaserScan& s : without.scans) EXPECT_FALSE(s.odometry.has_value());
  EXPECT_TRUE(has_warning(without, "no odometry on /odom: running without odometry"))
      << joined(without.warnings);

  RosbagOptions options;
  options.use_tf_odometry = true;
  const SensorLog with = read_rosbag(path, options);
  ASSERT_EQ(with.scans.size(), 5U);
  expect_pose_near(with.scans[2].odometry, Pose2(0.5, 1.0, 0.5 * kPi / 2), 1e-9);
  expect_pose_near(with.scans[4].odometry, Pose2(1.0, 3.0, 0.75 * kPi), 1e-9);
  EXPECT_TRUE(has_warning(with, "odometry stamps on /tf (odom -> base_link) are out of time order"))
      << joined(with.warnings);
}

TEST(RosbagReader, AbsentOdometryTopicListsTheTopicsAndNamesTheOptions) {
  TestBagSpec spec = small_spec();
  spec.odom_topic.clear();  // odometry only on /tf
  const fs::path path = write_bag("no_odom_topic", spec);
  // The default topic: a warning, and the run goes on without odometry.
  const SensorLog log = read_rosbag(path);
  EXPECT_TRUE(has_warning(log, "/scan (sensor_msgs/LaserScan, 5 messages)")) << joined(log.warnings);
  EXPECT_TRUE(has_warning(log, "--tf-odometry")) << joined(log.warnings);
  // A topic the user named and mistyped: an error saying what there is.
  RosbagOptions options;
  options.odom_topic = "/odm";
  options.odom_topic_named = true;
  const std::string error = input_error_of(path, options);
  EXPECT_NE(error.find("no odometry topic /odm"), std::string::npos) << error;
  EXPECT_NE(error.find("/tf (tf2_msgs/TFMessage"), std::string::npos) << error;
  EXPECT_NE(error.find("--tf-odometry"), std::string::npos) << error;
  options.use_tf_odometry = true;  // /tf it is: the topic does not matter then
  EXPECT_TRUE(read_rosbag(path, options).scans.front().odometry.has_value());
}

TEST(RosbagReader, NegativeRangesStayAndWarn) {
  TestBagSpec spec = small_spec();
  spec.messages[2] = scan_at(10.2, {1.0F, -2.0F, -std::numeric_limits<float>::infinity()});
  const SensorLog log = read_rosbag(write_bag("negative", spec));
  EXPECT_FLOAT_EQ(log.scans.front().ranges[1], -2.0F);
  EXPECT_TRUE(has_warning(log, ": 1 range readings are negative (kept; they count as invalid beams)"))
      << joined(log.warnings);
}

TEST(RosbagReader, ScansFarOutsideTheOdometrySpanGetNoOdometry) {
  TestBagSpec spec;
  spec.messages = {scan_at(9.0, {1.0F}),         scan_at(9.6, {1.0F}),
                   odom_at(10.0, 1.0, 0.0, 0.0), odom_at(11.0, 2.0, 0.0, 0.0),
                   scan_at(11.4, {1.0F}),        scan_at(12.0, {1.0F})};
  const SensorLog log = read_rosbag(write_bag("outside", spec));
  ASSERT_EQ(log.scans.size(), 4U);
  EXPECT_FALSE(log.scans[0].odometry.has_value());
  expect_pose_near(log.scans[1].odometry, Pose2(1.0, 0.0, 0.0), 1e-12);  // 0.4 s early: held
  expect_pose_near(log.scans[2].odometry, Pose2(2.0, 0.0, 0.0), 1e-12);
  EXPECT_FALSE(log.scans[3].odometry.has_value());
  EXPECT_TRUE(has_warning(log, "2 of 4 scans lie more than 0.5 s outside the odometry time span"))
      << joined(log.warnings);
  // No /tf_static: the laser is assumed at the base, and the user is told.
  EXPECT_TRUE(has_warning(log, "no base_link -> laser transform")) << joined(log.warnings);
  EXPECT_EQ(log.scans[0].laser_offset.x, 0.0);
}

TEST(RosbagReader, WrongTopicsAreInputErrorsListingWhatTheBagHas) {
  const fs::path path = write_bag("topics", small_spec());
  RosbagOptions options;
  options.scan_topic = "/base_scan";
  const std::string missing = input_error_of(path, options);
  EXPECT_NE(missing.find(path.string()), std::string::npos) << missing;
  EXPECT_NE(missing.find("/base_scan"), std::string::npos) << missing;
  EXPECT_NE(missing.find("/scan (sensor_msgs/LaserScan, 5 messages)"), std::string::npos)
      << missing;
  EXPECT_NE(missing.find("/odom (nav_msgs/Odometry, 4 messages)"), std::string::npos) << missing;
  EXPECT_NE(missing.find("/tf_static (tf2_msgs/TFMessage, 1 messages)"), std::string::npos)
      << missing;

  options.scan_topic = "/odom";
  const std::string wrong_type = input_error_of(path, options);
  EXPECT_NE(wrong_type.find("nav_msgs/Odometry"), std::string::npos) << wrong_type;
  EXPECT_NE(wrong_type.find("sensor_msgs/LaserScan"), std::string::npos) << wrong_type;

  options = {};
  options.odom_topic = "/scan";
  const std::string wrong_odom = input_error_of(path, options);
  EXPECT_NE(wrong_odom.find("nav_msgs/Odometry"), std::string::npos) << wrong_odom;
}

TEST(RosbagReader, NonFiniteScanGeometryIsAnInputErrorNamingTheField) {
  TestBagSpec spec = small_spec();
  spec.messages[3].scan.angle_increment = std::numeric_limits<float>::quiet_NaN();
  const std::string message = input_error_of(write_bag("nan_increment", spec));
  EXPECT_NE(message.find("/scan message #2"), std::string::npos) << message;
  EXPECT_NE(message.find("angle_increment"), std::string::npos) << message;
}

TEST(RosbagReader, FilesThatAreNotBagsAreInputErrors) {
  const fs::path dir = fresh_dir("rosbag_not_bags");
  EXPECT_NE(input_error_of(dir / "missing.bag").find("no such file"), std::string::npos);
  EXPECT_NE(input_error_of(dir).find("is a directory"), std::string::npos);

  write_file_atomically(dir / "x.bag", "# this is a text file\nFLASER 3 1 2 3\n");
  const std::string text = input_error_of(dir / "x.bag");
  EXPECT_NE(text.find((dir / "x.bag").string()), std::string::npos) << text;

  write_file_atomically(dir / "empty.bag", "");
  EXPECT_NE(input_error_of(dir / "empty.bag").find("empty.bag"), std::string::npos);
}

TEST(RosbagReader, TruncatedAndDamagedBagsAreInputErrorsNotCrashes) {
  TestBagSpec spec = small_spec();
  spec.compression = TestBagSpec::Compression::Bz2;
  const fs::path path = write_bag("damaged", spec);
  const std::string bytes = read_bytes(path);
  ASSERT_GT(bytes.size(), 1000U);
  const fs::path dir = path.parent_path();
  // Every cut: the index at the end goes missing first, then the chunks.
  for (std::size_t keep = 13; keep < bytes.size(); keep += 97) {
    const fs::path cut = dir / "cut.bag";
    write_file_atomically(cut, std::string_view(bytes).substr(0, keep));
    EXPECT_NE(input_error_of(cut).find("cut.bag"), std::string::npos) << keep;
  }
  // Flipped bytes inside the bz2 chunk (the file header record takes the first 4 kB).
  std::string damaged = bytes;
  for (std::size_t i = damaged.size() / 3; i < damaged.size() / 3 + 200; ++i)
    damaged[i] = static_cast<char>(~damaged[i]);
  write_file_atomically(dir / "flipped.bag", damaged);
  const std::string flipped = input_error_of(dir / "flipped.bag");
  EXPECT_NE(flipped.find("flipped.bag: damaged ROS1 bag"), std::string::npos) << flipped;
}

// Replaces the first occurrence of `from` in the file by `to` (same length).
void patch_file(const fs::path& path, const std::string& from, const std::string& to) {
  std::string bytes = read_bytes(path);
  const std::size_t at = bytes.find(from);
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, from.size(), to);
  write_file_atomically(path, bytes);
}

std::string le32_bytes(std::uint32_t v) {
  return {static_cast<char>(v & 0xFF), static_cast<char>((v >> 8) & 0xFF),
          static_cast<char>((v >> 16) & 0xFF), static_cast<char>(v >> 24)};
}

TEST(RosbagReader, DamagedIndexOffsetIsAnInputError) {
  // An uncompressed bag has no checksum: only the structure check stands
  // between a wrong index offset and rosbag_storage reading out of bounds.
  const fs::path path = write_bag("bad_offset", small_spec());
  // The index entry of the first scan: its stamp 10.2 s, then its offset.
  const std::string stamp = le32_bytes(10) + le32_bytes(200000000);
  std::string bytes = read_bytes(path);
  const std::size_t at = bytes.rfind(stamp);  // the index comes after the chunk
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at + 8, 4, le32_bytes(3));
  write_file_atomically(path, bytes);
  const std::string message = input_error_of(path);
  EXPECT_NE(message.find("where no message starts"), std::string::npos) << message;
}

TEST(RosbagReader, DamagedArrayLengthIsAnInputErrorNotAHugeAllocation) {
  // ros::serialization would size `ranges` from this length (8 GB) before
  // noticing the message is far shorter.
  const fs::path path = write_bag("bad_length", small_spec());
  const std::string ranges =
      le32_bytes(3) + std::string("\x00\x00\x80\x3f\x00\x00\x00\x40", 8);  // 3, 1.0F, 2.0F
  patch_file(path, ranges, le32_bytes(0x7FFFFFFF) + ranges.substr(4));
  const std::string message = input_error_of(path);
  EXPECT_NE(message.find("bad_length.bag"), std::string::npos) << message;
  EXPECT_NE(message.find("length field exceeds the message size"), std::string::npos) << message;
}

TEST(BagStructure, ChecksABagInMemoryNamingItsSource) {
  const std::string bytes = read_bytes(write_bag("in_memory", small_spec()));
  std::istringstream whole(bytes, std::ios::binary);
  EXPECT_NO_THROW(rosbag_raw::check_bag_structure(whole, "memory.bag"));
  std::istringstream cut(bytes.substr(0, bytes.size() - 10), std::ios::binary);
  try {
    rosbag_raw::check_bag_structure(cut, "memory.bag");
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("memory.bag: ", 0), 0u) << e.what();
  }
}

// Found by fuzzing (fuzz/rosbag_read.cpp): rosbag_storage reads the version
// line with sscanf, so "#ROSBAG V2.   0" is a 2.0 bag to it; the structural
// check let every line but "#ROSBAG V2.0" through unchecked, and rosbag_storage
// then allocated the 3.2 GB the next length field asked for.
TEST(RosbagReader, OtherVersionLinesAreRefusedNotReadUnchecked) {
  const fs::path dir = fresh_dir("rosbag_versions");
  const std::string lengths("\x45\x20\x20\xbf\x10\x00\x00\x00", 8);
  for (const std::string& line : {std::string("#ROSBAG V2.   0\n"), std::string("#ROSBAG V1.2\n")}) {
    const fs::path path = dir / "version.bag";
    write_file_atomically(path, line + lengths + std::string(64, ' '));
    const std::string message = input_error_of(path);
    EXPECT_NE(message.find(path.string() + ": ROS1 bag format \"" + line.substr(0, line.size() - 1) +
                           "\" is not supported"),
              std::string::npos)
        << message;
  }
}

// Peak resident memory of this process so far (each ctest case runs alone).
std::size_t peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::size_t>(usage.ru_maxrss) / 1024;
}

// Found by fuzzing (fuzz/rosbag_structure.cpp): a chunk whose size field
// claims almost 1 GB made the structural check allocate and clear that much
// before comparing it with the bytes there, for any compression.
TEST(BagStructure, AChunkClaimingMoreThanItHoldsCostsNoMemory) {
  for (const auto compression : {TestBagSpec::Compression::None, TestBagSpec::Compression::Bz2}) {
    TestBagSpec spec = small_spec();
    spec.compression = compression;
    const fs::path path = write_bag("huge_chunk", spec);
    std::string bytes = read_bytes(path);
    const std::size_t size_field = bytes.find("size=");  // the first chunk's header
    ASSERT_NE(size_field, std::string::npos);
    bytes.replace(size_field + 5, 4, le32_bytes(0x3ff00000));
    write_file_atomically(path, bytes);
    const std::size_t before = peak_rss_mb();
    const std::string message = input_error_of(path);
    EXPECT_NE(message.find(compression == TestBagSpec::Compression::None
                               ? "uncompressed chunk whose size field disagrees with its length"
                               : "its header says 1072693248"),
              std::string::npos)
        << message;
    EXPECT_LT(peak_rss_mb() - before, 256u) << "MB more at the peak";
  }
}

}  // namespace
}  // namespace dsswarm
