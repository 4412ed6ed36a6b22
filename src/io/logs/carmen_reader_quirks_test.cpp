// The CARMEN reader: what real logs do (gzip, unknown records, timestamps
// running backwards, NaN and negative ranges, CRLF), the other laser records,
// the shared real logs and text in memory.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "io/logs/carmen_reader.hpp"
#include "io/logs/carmen_test_util.hpp"
#include "io/logs/logs_test_util.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using namespace test;  // scratch files (logs_test_util.hpp), records (carmen_test_util.hpp)

std::string small_log() {
  std::string text = "# PARAM laser_range_max 50\n";
  for (int i = 0; i < 200; ++i) {
    text += odom(i) + flaser(beams(180, fmt::format("{:.2f}", 1.0 + i * 0.01)), i + 0.5, Pose2(i * 0.1, 0, 0));
  }
  return text;
}

TEST(CarmenReader, GzipDetectedByContentNotName) {
  const fs::path dir = scratch_dir("gzip");
  write_plain(dir / "plain.log", small_log());
  write_gzip(dir / "compressed.log", small_log());  // gzip without .gz
  write_plain(dir / "plain.log.gz", small_log());   // .gz without gzip
  const SensorLog plain = read_carmen(dir / "plain.log");
  ASSERT_EQ(plain.scans.size(), 200u);
  EXPECT_FLOAT_EQ(plain.scans[199].ranges[0], 2.99f);
  EXPECT_DOUBLE_EQ(plain.scans[199].range_max, 50.0);
  for (const char* name : {"compressed.log", "plain.log.gz"}) {
    const SensorLog other = read_carmen(dir / name);
    ASSERT_EQ(other.scans.size(), plain.scans.size()) << name;
    for (std::size_t i = 0; i < plain.scans.size(); ++i) {
      EXPECT_EQ(other.scans[i].ranges, plain.scans[i].ranges) << name << " scan " << i;
      EXPECT_DOUBLE_EQ(other.scans[i].timestamp, plain.scans[i].timestamp) << name;
    }
  }
}

TEST(CarmenReader, TruncatedGzipIsAnErrorNamingTheFile) {
  const fs::path dir = scratch_dir("gzip_truncated");
  write_gzip(dir / "full.log.gz", small_log());
  std::string bytes;
  {
    std::ifstream in(dir / "full.log.gz", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  ASSERT_GT(bytes.size(), 100u);
  write_plain(dir / "cut.log.gz", bytes.substr(0, bytes.size() / 2));
  std::string message = error_of(dir / "cut.log.gz");
  EXPECT_NE(message.find((dir / "cut.log.gz").string()), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;

  // Only the 8-byte trailer (CRC, length) missing: every line is there, but the file is still incomplete.
  write_plain(dir / "no_trailer.log.gz", bytes.substr(0, bytes.size() - 8));
  EXPECT_NE(error_of(dir / "no_trailer.log.gz").find("truncated"), std::string::npos);

  std::string corrupt = bytes;
  for (std::size_t i = corrupt.size() / 3; i < corrupt.size() / 3 + 64; ++i) corrupt[i] = static_cast<char>(~corrupt[i]);
  write_plain(dir / "corrupt.log.gz", corrupt);
  message = error_of(dir / "corrupt.log.gz");
  EXPECT_NE(message.find((dir / "corrupt.log.gz").string()), std::string::npos) << message;
  EXPECT_NE(message.find("corrupt gzip data"), std::string::npos) << message;
}

TEST(CarmenReader, UnknownRecordTypesWarnOncePerTypeKnownOnesSilently) {
  const fs::path path = scratch_dir("unknown") / "a.log";
  write_plain(path, "PARAM robot_frontlaser_offset 0.0 host 0\nSYNC foo\nTRUEPOS 1 2 3 4 5 6 1.0 host 1.0\n" +
                        flaser(beams(5), 1.0) + "WIBBLE 1 2 3\n" + flaser(beams(5), 2.0) + "WIBBLE 4 5 6\n" +
                        "WOBBLE\n" + "RAWLASER1 0 -1.57 3.14 0.0174 80 0.01 0 1 1.0 0 1.0 host 1.0\n");
  const SensorLog log = read_carmen(path);
  EXPECT_EQ(log.scans.size(), 2u);
  ASSERT_EQ(log.warnings.size(), 2u) << all_warnings(log);
  EXPECT_NE(log.warnings[0].find(path.string() + ":5: unknown record type 'WIBBLE' skipped (2 lines)"),
            std::string::npos)
      << log.warnings[0];
  EXPECT_NE(log.warnings[1].find("'WOBBLE'"), std::string::npos) << log.warnings[1];
}

TEST(CarmenReader, BackwardsTimestampsWarnOnceAndKeepFileOrder) {
  const fs::path path = scratch_dir("backwards") / "a.log";
  const double stamps[] = {1.0, 2.0, 1.5, 3.0, 2.5, 4.0};
  std::string text;
  for (int i = 0; i < 6; ++i) text += odom(10.0 + i) + flaser(beams(5), stamps[i]);
  text += odom(14.5);  // one ODOM out of order too (15 came before)
  write_plain(path, text);
  const SensorLog log = read_carmen(path);
  ASSERT_EQ(log.scans.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_DOUBLE_EQ(log.scans[i].timestamp, stamps[i]);
  EXPECT_EQ(std::count_if(log.warnings.begin(), log.warnings.end(),
                          [](const std::string& w) { return w.find("scan timestamps") != std::string::npos; }),
            1);
  EXPECT_TRUE(has_warning(log, path.string() + ": 2 of 6 scan timestamps run backwards (kept in file order)"))
      << all_warnings(log);
  EXPECT_TRUE(has_warning(log, "1 of 7 ODOM timestamps run backwards")) << all_warnings(log);
}

TEST(CarmenReader, NanAndInfRangesStayAndWarn) {
  const fs::path path = scratch_dir("nan") / "a.log";
  write_plain(path, flaser({"1.0", "nan", "inf", "-inf", "2.0"}, 1.0) + flaser({"NaN", "1", "1", "1", "1"}, 2.0));
  const SensorLog log = read_carmen(path);
  ASSERT_EQ(log.scans.size(), 2u);
  const LaserScan& s = log.scans[0];
  EXPECT_TRUE(std::isnan(s.ranges[1]));
  EXPECT_TRUE(std::isinf(s.ranges[2]) && s.ranges[2] > 0);
  EXPECT_TRUE(std::isinf(s.ranges[3]) && s.ranges[3] < 0);
  EXPECT_EQ(s.valid_count(), 2u);
  EXPECT_TRUE(has_warning(log, ": 4 range readings are NaN or inf")) << all_warnings(log);
}

TEST(CarmenReader, NegativeRangesStayAndWarn) {
  const fs::path path = scratch_dir("negative") / "a.log";
  write_plain(path, flaser({"1.0", "-0.5", "-inf", "2.0"}, 1.0) + flaser({"-3", "1", "1", "1"}, 2.0));
  const SensorLog log = read_carmen(path);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_FLOAT_EQ(log.scans[0].ranges[1], -0.5f);
  EXPECT_EQ(log.scans[0].valid_count(), 2u);
  // -inf is counted once, with the non-finite readings.
  EXPECT_TRUE(has_warning(log, ": 2 range readings are negative (kept; they count as invalid beams)"))
      << all_warnings(log);
  EXPECT_TRUE(has_warning(log, ": 1 range readings are NaN or inf")) << all_warnings(log);
}

TEST(CarmenReader, WindowsLineEndingsAndTabs) {
  const fs::path path = scratch_dir("crlf") / "a.log";
  write_plain(path, "# PARAM laser_range_max 12\r\nFLASER\t3 1 2 3\t0 0 0 0 0 0 5.0 host 0\r\n  \r\n");
  const SensorLog log = read_carmen(path);
  ASSERT_EQ(log.scans.size(), 1u);
  EXPECT_DOUBLE_EQ(log.scans[0].range_max, 12.0);
  EXPECT_DOUBLE_EQ(log.scans[0].timestamp, 5.0);
}

TEST(CarmenReader, RearLaserOnlyWhenNoFrontLaser) {
  const fs::path dir = scratch_dir("rlaser");
  write_plain(dir / "rear.log", flaser(beams(4), {}, {}, 1.0, "RLASER") + flaser(beams(4), {}, {}, 2.0, "RLASER"));
  const SensorLog rear = read_carmen(dir / "rear.log");
  EXPECT_EQ(rear.scans.size(), 2u);
  EXPECT_TRUE(rear.warnings.empty()) << all_warnings(rear);

  write_plain(dir / "both.log", flaser(beams(4), {}, {}, 1.0, "RLASER") + flaser(beams(5), 1.1));
  const SensorLog both = read_carmen(dir / "both.log");
  ASSERT_EQ(both.scans.size(), 1u);
  EXPECT_EQ(both.scans[0].ranges.size(), 5u);
  EXPECT_TRUE(has_warning(both, "ignored 1 RLASER records")) << all_warnings(both);
}

TEST(CarmenReader, RobotLaserCarriesItsOwnGeometry) {
  const fs::path path = scratch_dir("robotlaser") / "a.log";
  const Pose2 robot(2.0, 1.0, 1.0);
  const Pose2 laser = robot * Pose2(0.1, 0.0, 0.0);
  const std::string record = fmt::format(
      "ROBOTLASER1 0 -1.0 2.0 0.5 40.0 0.01 0 5 1 2 3 4 5 2 0.5 0.6 {} {} {} {} {} {} 0.1 0.2 0.3 0.4 0.5 7.25 "
      "host 0.5\n",
      laser.x, laser.y, laser.theta, robot.x, robot.y, robot.theta);
  write_plain(path, record + record);
  CarmenOptions span;  // the record's own layout beats any convention
  span.beams = CarmenOptions::BeamConvention::Span180;
  const SensorLog log = read_carmen(path, span);
  ASSERT_EQ(log.scans.size(), 2u);
  const LaserScan& s = log.scans[0];
  EXPECT_DOUBLE_EQ(s.angle_min, -1.0);
  EXPECT_DOUBLE_EQ(s.angle_increment, 0.5);
  EXPECT_DOUBLE_EQ(s.range_max, 40.0);
  EXPECT_DOUBLE_EQ(s.timestamp, 7.25);
  EXPECT_EQ(s.ranges, (std::vector<float>{1, 2, 3, 4, 5}));
  EXPECT_NEAR(s.laser_offset.x, 0.1, 1e-9);
  EXPECT_NEAR(s.odometry->theta, 1.0, 1e-12);

  write_plain(path, "ROBOTLASER1 0 -1.0 2.0 0.5 40.0 0.01 0 5 1 2 3 4 5 2 0.5 0.6 0 0 0 0 0 0 0.1 7.25 host 0.5\n");
  const std::string message = error_of(path);
  EXPECT_NE(message.find(":1: ROBOTLASER1: expected 2 remissions"), std::string::npos) << message;
}

TEST(CarmenReader, ZeroBeamRecordsAreSkippedWithAWarning) {
  const fs::path path = scratch_dir("zero") / "a.log";
  write_plain(path, "FLASER 0 0 0 0 0 0 0 1.0 host 0\n" + flaser(beams(5), 2.0));
  const SensorLog log = read_carmen(path);
  ASSERT_EQ(log.scans.size(), 1u);
  EXPECT_TRUE(has_warning(log, "skipped 1 laser records with 0 readings")) << all_warnings(log);
}

TEST(CarmenReader, MalformedOdomIsAnError) {
  const fs::path path = scratch_dir("bad_odom") / "a.log";
  write_plain(path, flaser(beams(5), 1.0) + "ODOM 1 2 3\n");
  const std::string message = error_of(path);
  EXPECT_NE(message.find(":2: ODOM: expected 9 fields"), std::string::npos) << message;
}

// ---- real data (skipped when ../shared/data is absent) ----

struct RealLog {
  const char* file;
  std::size_t scans;
  std::size_t beams;
  double angle_increment;
  double offset_x;
  std::size_t backwards;
};

void check_real_log(const RealLog& expected) {
  const fs::path path = test::real_data(expected.file);
  if (!fs::exists(path)) GTEST_SKIP() << "real data not found at " << path;
  const auto start = std::chrono::steady_clock::now();
  const SensorLog log = read_carmen(path);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ::testing::Test::RecordProperty("read_seconds", fmt::format("{:.3f}", seconds));
  ASSERT_EQ(log.scans.size(), expected.scans);
  for (const LaserScan& s : log.scans) {
    ASSERT_EQ(s.ranges.size(), expected.beams);
    ASSERT_TRUE(s.odometry.has_value());
  }
  const LaserScan& first = log.scans.front();
  EXPECT_NEAR(first.angle_min, -kPi / 2, 1e-6);
  EXPECT_NEAR(first.angle_increment, expected.angle_increment, 1e-8);
  EXPECT_DOUBLE_EQ(first.range_max, 80.0);
  EXPECT_NEAR(first.laser_offset.x, expected.offset_x, 1e-9);
  EXPECT_GT(first.valid_count(), expected.beams / 4);
  if (expected.backwards > 0) {
    EXPECT_TRUE(has_warning(log, fmt::format("{} of {} scan timestamps run backwards", expected.backwards,
                                             expected.scans)))
        << all_warnings(log);
  } else {
    EXPECT_FALSE(has_warning(log, "scan timestamps run backwards")) << all_warnings(log);
  }
  EXPECT_FALSE(has_warning(log, "unknown record")) << all_warnings(log);
}

TEST(CarmenReaderRealData, Intel) { check_real_log({"carmen/intel.log.gz", 13631, 180, kPi / 179, 0.0, 631}); }
TEST(CarmenReaderRealData, Fr079) { check_real_log({"carmen/fr079.log.gz", 4934, 360, kPi / 359, 0.04, 0}); }
TEST(CarmenReaderRealData, MitCsail) { check_real_log({"carmen/mit-csail.log.gz", 1988, 361, 0.5 * kDeg, 0.0, 0}); }

TEST(CarmenReaderRealData, ClassicClfMatchesConvertedLog) {
  const fs::path clf_path = test::real_data("clf/mit-csail.clf.gz");
  const fs::path log_path = test::real_data("carmen/mit-csail.log.gz");
  if (!fs::exists(clf_path) || !fs::exists(log_path)) GTEST_SKIP() << "real data not found at " << clf_path;
  const SensorLog clf = read_carmen(clf_path);
  ASSERT_EQ(clf.scans.size(), 1988u);
  const LaserScan& s = clf.scans.front();
  ASSERT_EQ(s.ranges.size(), 361u);
  EXPECT_NEAR(s.angle_increment, 0.5 * kDeg, 1e-12);
  EXPECT_NEAR(s.angle_min, -kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(s.range_max, 80.0);
  EXPECT_DOUBLE_EQ(s.timestamp, 1134864629.895182);
  ASSERT_TRUE(s.odometry.has_value());
  EXPECT_NEAR(s.odometry->x, 576.536523, 1e-9);
  EXPECT_NEAR(s.odometry->theta, -2.255213, 1e-9);
  EXPECT_NEAR(s.laser_offset.x, 0.0, 1e-9);
  EXPECT_TRUE(clf.warnings.empty()) << all_warnings(clf);

  // Same recording as the converted log: same ranges, stamps and odometry.
  const SensorLog converted = read_carmen(log_path);
  ASSERT_EQ(converted.scans.size(), clf.scans.size());
  for (std::size_t i = 0; i < clf.scans.size(); i += 97) {
    EXPECT_EQ(clf.scans[i].ranges, converted.scans[i].ranges) << "scan " << i;
    EXPECT_NEAR(clf.scans[i].timestamp, converted.scans[i].timestamp, 1e-6) << "scan " << i;
    EXPECT_NEAR(clf.scans[i].odometry->x, converted.scans[i].odometry->x, 1e-6) << "scan " << i;
  }
}

TEST(CarmenReader, ParsesTextInMemoryAsItReadsFiles) {
  std::string text = "# PARAM laser_range_max 12\r\n" + flaser(beams(3), 1.0) + odom(1.5) +
                     flaser({"1", "inf", "3"}, 0.5, Pose2(0.5, 0.0, 0.1));
  text.pop_back();  // the last line without its newline
  const fs::path path = scratch_dir("in_memory") / "a.log";
  write_plain(path, text);
  const SensorLog from_file = read_carmen(path);
  const SensorLog from_text = parse_carmen(text, path.string());
  ASSERT_EQ(from_text.scans.size(), 2u);
  ASSERT_EQ(from_text.scans.size(), from_file.scans.size());
  for (std::size_t i = 0; i < from_text.scans.size(); ++i) {
    EXPECT_EQ(from_text.scans[i].ranges, from_file.scans[i].ranges) << i;
    EXPECT_EQ(from_text.scans[i].timestamp, from_file.scans[i].timestamp) << i;
    EXPECT_EQ(from_text.scans[i].range_max, 12.0) << i;
    ASSERT_TRUE(from_text.scans[i].odometry) << i;
    EXPECT_EQ(from_text.scans[i].odometry->x, from_file.scans[i].odometry->x) << i;
  }
  EXPECT_EQ(from_text.warnings, from_file.warnings);
  EXPECT_TRUE(has_warning(from_text, "1 of 2 scan timestamps run backwards")) << all_warnings(from_text);

  try {
    parse_carmen("\nFLASER 3 1 2x 3 0 0 0 0 0 0 2.0 host 0\n", "memory.log");
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("memory.log:2: FLASER", 0), 0u) << e.what();  // file:line of the text
  }
}


}  // namespace
}  // namespace dsswarm
