#include "io/logs/carmen_reader.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "io/logs/logs_test_util.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using test::scratch_dir;
using test::write_gzip;
using test::write_plain;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

std::string flaser(const std::vector<std::string>& ranges, const Pose2& laser, const Pose2& odom, double stamp,
                   const char* type = "FLASER") {
  return fmt::format("{} {} {} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} host {:.6f}\n", type, ranges.size(),
                     fmt::join(ranges, " "), laser.x, laser.y, laser.theta, odom.x, odom.y, odom.theta, stamp,
                     stamp - 100.0);
}

// A record whose laser pose equals the robot pose (zero mounting offset).
std::string flaser(const std::vector<std::string>& ranges, double stamp, const Pose2& odom = {}) {
  return flaser(ranges, odom, odom, stamp);
}

std::vector<std::string> beams(std::size_t n, const std::string& value = "1.5") {
  return std::vector<std::string>(n, value);
}

std::string odom(double stamp) { return fmt::format("ODOM 0 0 0 0 0 0 {:.6f} host {:.6f}\n", stamp, stamp); }

// Runs read_carmen and returns the InputError message ("" if nothing was thrown).
std::string error_of(const fs::path& path, const CarmenOptions& options = {}) {
  try {
    read_carmen(path, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool has_warning(const SensorLog& log, const std::string& needle) {
  return std::any_of(log.warnings.begin(), log.warnings.end(),
                     [&](const std::string& w) { return w.find(needle) != std::string::npos; });
}

std::string all_warnings(const SensorLog& log) { return fmt::format("{}", fmt::join(log.warnings, "\n")); }

TEST(CarmenReader, HonoursParamGeometryAndOffset) {
  const fs::path path = scratch_dir("params") / "a.log";
  const Pose2 robot(1.0, 2.0, 0.5);
  write_plain(path,
              "# PARAM laser_format FLASER\n"
              "# PARAM laser_angle_min -1.25\n"
              "# PARAM laser_angle_increment 0.5\n"
              "# PARAM laser_num_beams 5\n"
              "# PARAM laser_range_min 0.1\n"
              "# PARAM laser_range_max 30\n"
              "# PARAM laser_offset_x 0.25\n"
              "# PARAM laser_offset_y -0.05\n"
              "# PARAM laser_offset_theta 0.1\n"
              "# PARAM laser_frame laser (static tf base_link -> laser)\n" +
                  flaser({"1", "2", "3", "4", "5"}, robot * Pose2(0.25, -0.05, 0.1), robot, 10.0));
  const SensorLog log = read_carmen(path);
  ASSERT_EQ(log.scans.size(), 1u);
  const LaserScan& s = log.scans[0];
  EXPECT_DOUBLE_EQ(s.angle_min, -1.25);
  EXPECT_DOUBLE_EQ(s.angle_increment, 0.5);
  EXPECT_DOUBLE_EQ(s.range_min, 0.1);
  EXPECT_DOUBLE_EQ(s.range_max, 30.0);
  EXPECT_DOUBLE_EQ(s.laser_offset.x, 0.25);
  EXPECT_DOUBLE_EQ(s.laser_offset.y, -0.05);
  EXPECT_DOUBLE_EQ(s.laser_offset.theta, 0.1);
  ASSERT_TRUE(s.odometry.has_value());
  EXPECT_DOUBLE_EQ(s.odometry->x, 1.0);
  EXPECT_DOUBLE_EQ(s.odometry->y, 2.0);
  EXPECT_DOUBLE_EQ(s.odometry->theta, 0.5);
  EXPECT_DOUBLE_EQ(s.timestamp, 10.0);
  EXPECT_EQ(s.ranges, (std::vector<float>{1, 2, 3, 4, 5}));
  EXPECT_TRUE(log.warnings.empty()) << all_warnings(log);
}

TEST(CarmenReader, ParamAngleMaxGivesIncrementAndParamOffsetDisagreementWarns) {
  const fs::path path = scratch_dir("params_max") / "a.log";
  write_plain(path,
              "#PARAM laser_angle_min -1\n"
              "# PARAM laser_angle_max 1\n"
              "# PARAM laser_offset_x 0.3\n" +
                  flaser(beams(5), Pose2(0, 0, 0), Pose2(0, 0, 0), 1.0));
  const SensorLog log = read_carmen(path);
  ASSERT_EQ(log.scans.size(), 1u);
  EXPECT_DOUBLE_EQ(log.scans[0].angle_min, -1.0);
  EXPECT_DOUBLE_EQ(log.scans[0].angle_increment, 0.5);
  EXPECT_DOUBLE_EQ(log.scans[0].laser_offset.x, 0.3);  // the PARAM wins over the poses...
  EXPECT_TRUE(has_warning(log, "differs from the offset implied")) << all_warnings(log);  // ...but not silently
}

TEST(CarmenReader, ParamBeamCountMismatchNamesTheLine) {
  const fs::path path = scratch_dir("params_n") / "a.log";
  write_plain(path, "# PARAM laser_angle_min -1\n# PARAM laser_angle_increment 0.1\n# PARAM laser_num_beams 6\n" +
                        flaser(beams(5), 1.0));
  const std::string message = error_of(path);
  EXPECT_NE(message.find(path.string() + ":4: FLASER"), std::string::npos) << message;
  EXPECT_NE(message.find("laser_num_beams"), std::string::npos) << message;
}

TEST(CarmenReader, BadParamValueNamesKeyAndLine) {
  const fs::path path = scratch_dir("params_bad") / "a.log";
  write_plain(path, "# comment\n# PARAM laser_range_max eighty\n" + flaser(beams(5), 1.0));
  const std::string message = error_of(path);
  EXPECT_NE(message.find(path.string() + ":2:"), std::string::npos) << message;
  EXPECT_NE(message.find("laser_range_max"), std::string::npos) << message;
  EXPECT_NE(message.find("eighty"), std::string::npos) << message;
}

// A `# PARAM` line is a comment: a broken one stops the run only where its value would be used.
TEST(CarmenReader, BadParamThatIsNotNeededIsAWarning) {
  const fs::path dir = scratch_dir("params_unused");
  const std::string robotlaser =
      "ROBOTLASER1 0 -1.0 2.0 0.5 40.0 0.01 0 5 1 2 3 4 5 0 0.1 0 0 0 0 0 0.1 0.2 0.3 0.4 0.5 7.25 host 0.5\n";
  write_plain(dir / "own.log", "# PARAM laser_angle_min abc\n# PARAM laser_range_max\n# PARAM laser_offset_x 1e999\n" +
                                   robotlaser);
  const SensorLog own = read_carmen(dir / "own.log");
  ASSERT_EQ(own.scans.size(), 1u);
  EXPECT_DOUBLE_EQ(own.scans[0].angle_min, -1.0);
  EXPECT_NEAR(own.scans[0].laser_offset.x, 0.1, 1e-9);  // from the record's laser and robot poses
  const std::string file = (dir / "own.log").string();
  EXPECT_TRUE(has_warning(own, file + ":1: # PARAM laser_angle_min: 'abc' is not a number; ignored"))
      << all_warnings(own);
  EXPECT_TRUE(has_warning(own, file + ":2: # PARAM laser_range_max: missing value; ignored")) << all_warnings(own);
  EXPECT_TRUE(has_warning(own, file + ":3: # PARAM laser_offset_x:")) << all_warnings(own);

  // FLASER records use the PARAM geometry, unless an option overrides it.
  write_plain(dir / "flaser.log",
              "# PARAM laser_angle_increment x\n# PARAM laser_offset_y ?\n" + flaser(beams(5), 1.0));
  EXPECT_NE(error_of(dir / "flaser.log").find(":1: # PARAM laser_angle_increment"), std::string::npos);
  CarmenOptions classic;
  classic.beams = CarmenOptions::BeamConvention::Classic;
  const SensorLog overridden = read_carmen(dir / "flaser.log", classic);
  EXPECT_TRUE(has_warning(overridden, ":1: # PARAM laser_angle_increment: 'x' is not a number; ignored"))
      << all_warnings(overridden);
  EXPECT_TRUE(has_warning(overridden, ":2: # PARAM laser_offset_y")) << all_warnings(overridden);
}

TEST(CarmenReader, ClassicBeamConventionWithoutParams) {
  const fs::path dir = scratch_dir("classic");
  struct Case {
    std::size_t n;
    double increment;
  };
  for (const Case c : {Case{180, 1.0 * kDeg}, Case{181, 1.0 * kDeg}, Case{360, 0.5 * kDeg}, Case{361, 0.5 * kDeg},
                       Case{721, 0.25 * kDeg}, Case{5, kPi / 4}}) {
    const fs::path path = dir / fmt::format("{}.clf", c.n);
    write_plain(path, flaser(beams(c.n), 1.0));
    const SensorLog log = read_carmen(path);
    ASSERT_EQ(log.scans.size(), 1u);
    const LaserScan& s = log.scans[0];
    EXPECT_NEAR(s.angle_increment, c.increment, 1e-12) << c.n;
    // Centred on the forward axis.
    EXPECT_NEAR(s.angle_min, -(static_cast<double>(c.n) - 1) * c.increment / 2, 1e-12) << c.n;
    EXPECT_NEAR(s.beam_angle(c.n - 1), -s.angle_min, 1e-12) << c.n;
    EXPECT_DOUBLE_EQ(s.range_min, 0.0);
    EXPECT_DOUBLE_EQ(s.range_max, kCarmenDefaultRangeMax);
  }
  EXPECT_NEAR(classic_beam_geometry(180).angle_min, -89.5 * kDeg, 1e-12);
  EXPECT_NEAR(classic_beam_geometry(361).angle_min, -90.0 * kDeg, 1e-12);
}

TEST(CarmenReader, ExplicitConventionsOverrideParams) {
  const fs::path path = scratch_dir("conventions") / "a.log";
  write_plain(path, "# PARAM laser_angle_min -1\n# PARAM laser_angle_increment 0.001\n# PARAM laser_range_max 20\n" +
                        flaser(beams(180), 1.0));
  CarmenOptions span;
  span.beams = CarmenOptions::BeamConvention::Span180;
  const LaserScan s = read_carmen(path, span).scans.at(0);
  EXPECT_NEAR(s.angle_min, -kPi / 2, 1e-12);
  EXPECT_NEAR(s.angle_increment, kPi / 179, 1e-12);
  EXPECT_DOUBLE_EQ(s.range_max, 20.0);  // the convention is about angles only

  CarmenOptions classic;
  classic.beams = CarmenOptions::BeamConvention::Classic;
  EXPECT_NEAR(read_carmen(path, classic).scans.at(0).angle_increment, kDeg, 1e-12);
  EXPECT_NEAR(read_carmen(path).scans.at(0).angle_increment, 0.001, 1e-12);
}

TEST(CarmenReader, DerivesLaserOffsetFromRecordPoses) {
  const fs::path path = scratch_dir("offset") / "a.log";
  const Pose2 mount(0.2, -0.1, 0.3);
  const Pose2 a(1.0, 2.0, 0.5), b(-3.0, 4.0, 2.9);
  write_plain(path, flaser(beams(5), a * mount, a, 1.0) + flaser(beams(5), b * mount, b, 2.0));
  const SensorLog log = read_carmen(path);
  ASSERT_EQ(log.scans.size(), 2u);
  for (const LaserScan& s : log.scans) {
    EXPECT_NEAR(s.laser_offset.x, 0.2, 1e-5);
    EXPECT_NEAR(s.laser_offset.y, -0.1, 1e-5);
    EXPECT_NEAR(s.laser_offset.theta, 0.3, 1e-5);
  }
  EXPECT_NEAR(log.scans[1].odometry->theta, 2.9, 1e-9);
  EXPECT_TRUE(log.warnings.empty()) << all_warnings(log);

  CarmenOptions options;
  options.laser_offset = Pose2(-0.04, 0.0, 0.0);
  const SensorLog overridden = read_carmen(path, options);
  EXPECT_DOUBLE_EQ(overridden.scans[1].laser_offset.x, -0.04);
  EXPECT_DOUBLE_EQ(overridden.scans[1].laser_offset.theta, 0.0);
}

TEST(CarmenReader, OptionOffsetWinsOverParams) {
  const fs::path path = scratch_dir("offset_param") / "a.log";
  write_plain(path, "# PARAM laser_offset_x 0.04\n" + flaser(beams(5), 1.0));
  CarmenOptions options;
  options.laser_offset = Pose2(-0.04, 0.01, 0.02);
  const LaserScan s = read_carmen(path, options).scans.at(0);
  EXPECT_DOUBLE_EQ(s.laser_offset.x, -0.04);
  EXPECT_DOUBLE_EQ(s.laser_offset.y, 0.01);
  EXPECT_DOUBLE_EQ(s.laser_offset.theta, 0.02);
}

TEST(CarmenReader, VaryingImpliedOffsetWarns) {
  const fs::path path = scratch_dir("offset_vary") / "a.log";
  const Pose2 a(1.0, 2.0, 0.5);
  write_plain(path, flaser(beams(5), a * Pose2(0.2, 0, 0), a, 1.0) + flaser(beams(5), a * Pose2(0.3, 0, 0), a, 2.0) +
                        flaser(beams(5), a * Pose2(0.2, 0, 0), a, 3.0));
  const SensorLog log = read_carmen(path);
  EXPECT_NEAR(log.scans[1].laser_offset.x, 0.2, 1e-5);  // the first record's
  EXPECT_TRUE(has_warning(log, "varies in 1 of 3 scans")) << all_warnings(log);
}

TEST(CarmenReader, TruncatedLineNamesLineAndCounts) {
  const fs::path path = scratch_dir("truncated_line") / "a.log";
  std::string record = flaser(beams(5), 3.0);
  record = record.substr(0, record.find("1.5 1.5 1.5")) + "1.5 1.5\n";  // cut after 2 ranges
  write_plain(path, flaser(beams(5), 1.0) + odom(1.5) + record + flaser(beams(5), 4.0));
  const std::string message = error_of(path);
  EXPECT_NE(message.find(path.string() + ":3: FLASER: expected 5 ranges, found 2"), std::string::npos) << message;
}

TEST(CarmenReader, MissingTrailingFieldIsAnError) {
  const fs::path path = scratch_dir("missing_tail") / "a.log";
  std::string record = flaser(beams(5), 1.0);
  record = record.substr(0, record.rfind(' ')) + "\n";  // drop logger_timestamp
  write_plain(path, record);
  const std::string message = error_of(path);
  EXPECT_NE(message.find(path.string() + ":1: FLASER: expected 5 ranges"), std::string::npos) << message;
  EXPECT_NE(message.find("logger_timestamp"), std::string::npos) << message;
}

TEST(CarmenReader, NonNumericFieldsNameTheField) {
  const fs::path dir = scratch_dir("non_numeric");
  const fs::path bad_odom = dir / "odom.log";
  write_plain(bad_odom, flaser(beams(3), 1.0) + "FLASER 3 1 2 3 0 0 0 0 abc 0 2.0 host 0\n");
  std::string message = error_of(bad_odom);
  EXPECT_NE(message.find(bad_odom.string() + ":2: FLASER"), std::string::npos) << message;
  EXPECT_NE(message.find("'odom_y'"), std::string::npos) << message;
  EXPECT_NE(message.find("'abc'"), std::string::npos) << message;

  const fs::path bad_range = dir / "range.log";
  write_plain(bad_range, "FLASER 3 1 2x 3 0 0 0 0 0 0 2.0 host 0\n");
  message = error_of(bad_range);
  EXPECT_NE(message.find(":1: FLASER: field 'range 2 of 3'"), std::string::npos) << message;

  const fs::path bad_count = dir / "count.log";
  write_plain(bad_count, "FLASER -3 1 2 3 0 0 0 0 0 0 2.0 host 0\n");
  message = error_of(bad_count);
  EXPECT_NE(message.find("num_readings"), std::string::npos) << message;

  const fs::path nan_pose = dir / "nan_pose.log";
  write_plain(nan_pose, "FLASER 3 1 2 3 nan 0 0 0 0 0 2.0 host 0\n");
  message = error_of(nan_pose);
  EXPECT_NE(message.find("'x' must be finite"), std::string::npos) << message;

  const fs::path bad_stamp = dir / "stamp.log";
  write_plain(bad_stamp, "ODOM 0 0 0 0 0 0 12:00 host 0\n" + flaser(beams(3), 1.0));
  message = error_of(bad_stamp);
  EXPECT_NE(message.find(":1: ODOM: field 'timestamp'"), std::string::npos) << message;
}

// A count near 2^64 made "count + trailing fields" wrap to the number of
// fields found, so the line passed its length check and asked for 2^64
// ranges (found by the fuzzer).
TEST(CarmenReader, ACountNear2To64IsAnErrorNotAnAllocation) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"FLASER 18446744073709551615 1 2 3 4 5 6 7 8\n", "expected 18446744073709551615 ranges, found 8"},
      {"RLASER 18446744073709551614 1 2 3 4 5 6 7\n", "expected 18446744073709551614 ranges, found 7"},
      {"ROBOTLASER1 0 0 1 0.1 10 0 0 18446744073709551608 1 2 3\n",
       "expected 18446744073709551608 ranges then num_remissions, found 3"},
      {"ROBOTLASER1 0 0 1 0.1 10 0 0 1 5 18446744073709551613 1 2 3 4 5 6 7 8 9 10 11 12 13 h 15\n",
       "expected 18446744073709551613 remissions then 14 fields"},
  };
  for (const auto& [text, expected] : cases) {
    std::string message;
    try {
      parse_carmen(text, "count.log", {});
    } catch (const InputError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find("count.log:1: "), std::string::npos) << text << message;
    EXPECT_NE(message.find(expected), std::string::npos) << text << message;
  }
}

TEST(CarmenReader, MissingEmptyAndScanlessFiles) {
  const fs::path dir = scratch_dir("missing");
  std::string message = error_of(dir / "nope.log");
  EXPECT_NE(message.find((dir / "nope.log").string()), std::string::npos) << message;
  EXPECT_NE(message.find("no such file"), std::string::npos) << message;

  message = error_of(dir);
  EXPECT_NE(message.find("directory"), std::string::npos) << message;

  write_plain(dir / "empty.log", "");
  message = error_of(dir / "empty.log");
  EXPECT_EQ(message, (dir / "empty.log").string() + ": no laser scans (FLASER/RLASER/ROBOTLASER1) found");

  write_gzip(dir / "empty.log.gz", "");
  EXPECT_NE(error_of(dir / "empty.log.gz").find("no laser scans"), std::string::npos);

  write_plain(dir / "odom_only.log", "# header\n\n" + odom(1.0) + odom(2.0));
  EXPECT_NE(error_of(dir / "odom_only.log").find("no laser scans"), std::string::npos);
}

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
