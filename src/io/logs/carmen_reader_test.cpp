// The CARMEN reader: PARAM lines, beam conventions, laser offsets and the
// errors a malformed record gets. Its quirks, gzip and the real logs:
// carmen_reader_quirks_test.cpp.
#include "io/logs/carmen_reader.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "io/logs/carmen_test_util.hpp"
#include "io/logs/logs_test_util.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using namespace test;  // scratch files (logs_test_util.hpp), records (carmen_test_util.hpp)

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

// Found by the carmen_text fuzzer: finite values whose beams together span
// more than a full turn (or overflow) are an error naming the record.
TEST(CarmenReader, ParamGeometryBeyondAFullTurnNamesTheLine) {
  const fs::path path = scratch_dir("params_turn") / "a.log";
  write_plain(path, "# PARAM laser_angle_increment 1e308\n" + flaser(beams(5), 1.0));
  std::string message = error_of(path);
  EXPECT_NE(message.find(path.string() + ":2: FLASER"), std::string::npos) << message;
  EXPECT_NE(message.find("more than a full turn"), std::string::npos) << message;
  write_plain(path, "# PARAM laser_angle_min -1\n# PARAM laser_angle_increment 2\n" + flaser(beams(5), 1.0));
  message = error_of(path);
  EXPECT_NE(message.find("5 beams spanning 8 rad"), std::string::npos) << message;
  // A full circle of beams is fine.
  write_plain(path, "# PARAM laser_angle_increment 1.5707963\n" + flaser(beams(5), 1.0));
  EXPECT_NO_THROW(read_carmen(path));
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


}  // namespace
}  // namespace dsswarm
