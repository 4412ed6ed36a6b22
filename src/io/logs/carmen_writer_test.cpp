#include "io/logs/carmen_writer.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "common/errors.hpp"
#include "io/logs/carmen_reader.hpp"
#include "io/logs/logs_test_util.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using test::scratch_dir;

std::vector<LaserScan> synthetic_scans(std::size_t count, bool with_odometry) {
  std::vector<LaserScan> scans;
  for (std::size_t i = 0; i < count; ++i) {
    LaserScan s;
    s.timestamp = 976052857.337284 + 0.1 * static_cast<double>(i);
    s.angle_min = -1.5707963705062866;  // float(pi/2), as ROS stores it
    s.angle_increment = 0.017550798;
    s.range_min = 0.1;
    s.range_max = 80.0;
    for (std::size_t b = 0; b < 180; ++b) s.ranges.push_back(0.3f + 0.0137f * static_cast<float>(b + i));
    s.ranges[7] = 81.91f;
    s.ranges[9] = std::numeric_limits<float>::quiet_NaN();
    if (with_odometry) s.odometry = Pose2(0.123456789 * static_cast<double>(i), -2.5e-7, 3.1 - 0.7 * static_cast<double>(i));
    s.laser_offset = Pose2(-0.04, 0.0125, 0.001);
    scans.push_back(s);
  }
  return scans;
}

void expect_same_scans(const std::vector<LaserScan>& a, const std::vector<LaserScan>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE(fmt::format("scan {}", i));
    EXPECT_EQ(a[i].timestamp, b[i].timestamp);
    EXPECT_EQ(a[i].angle_min, b[i].angle_min);
    EXPECT_EQ(a[i].angle_increment, b[i].angle_increment);
    EXPECT_EQ(a[i].range_min, b[i].range_min);
    EXPECT_EQ(a[i].range_max, b[i].range_max);
    ASSERT_EQ(a[i].ranges.size(), b[i].ranges.size());
    for (std::size_t r = 0; r < a[i].ranges.size(); ++r) {
      if (std::isnan(a[i].ranges[r])) {
        EXPECT_TRUE(std::isnan(b[i].ranges[r])) << "beam " << r;
      } else {
        EXPECT_EQ(a[i].ranges[r], b[i].ranges[r]) << "beam " << r;
      }
    }
    ASSERT_EQ(a[i].odometry.has_value(), b[i].odometry.has_value());
    if (a[i].odometry) {
      EXPECT_EQ(a[i].odometry->x, b[i].odometry->x);
      EXPECT_EQ(a[i].odometry->y, b[i].odometry->y);
      EXPECT_EQ(a[i].odometry->theta, b[i].odometry->theta);
    }
    EXPECT_EQ(a[i].laser_offset.x, b[i].laser_offset.x);
    EXPECT_EQ(a[i].laser_offset.y, b[i].laser_offset.y);
    EXPECT_EQ(a[i].laser_offset.theta, b[i].laser_offset.theta);
  }
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(CarmenWriter, RoundTripIsExact) {
  const fs::path path = scratch_dir("write_roundtrip") / "out.log";
  const std::vector<LaserScan> scans = synthetic_scans(25, true);
  write_carmen(path, scans, "synthetic test log\nsecond line");
  const SensorLog back = read_carmen(path);
  expect_same_scans(scans, back.scans);
  // The NaN beam is reported, nothing else.
  ASSERT_EQ(back.warnings.size(), 1u);
  EXPECT_NE(back.warnings[0].find("25 range readings are NaN"), std::string::npos) << back.warnings[0];

  const std::string text = slurp(path);
  EXPECT_NE(text.find("# synthetic test log\n# second line\n"), std::string::npos);
  EXPECT_NE(text.find("# PARAM laser_num_beams 180\n"), std::string::npos);
  EXPECT_NE(text.find("# PARAM laser_offset_x -0.04\n"), std::string::npos);
  // The laser pose field is odometry (+) offset, so readers that derive the offset get it too.
  const Pose2 implied = between(*scans[3].odometry, *scans[3].odometry * scans[3].laser_offset);
  EXPECT_NEAR(implied.x, -0.04, 1e-12);
}

TEST(CarmenWriter, ScansWithoutOdometryComeBackWithout) {
  const fs::path path = scratch_dir("write_no_odom") / "out.log";
  const std::vector<LaserScan> scans = synthetic_scans(3, false);
  write_carmen(path, scans);
  const SensorLog back = read_carmen(path);
  expect_same_scans(scans, back.scans);
  EXPECT_NE(slurp(path).find("# PARAM odometry none\n"), std::string::npos);
}

TEST(CarmenWriter, CommentThatLooksLikeAParamIsNotOne) {
  const fs::path path = scratch_dir("write_comment") / "out.log";
  write_carmen(path, synthetic_scans(2, true), "PARAM laser_range_max 3");
  const SensorLog back = read_carmen(path);
  EXPECT_EQ(back.scans.at(0).range_max, 80.0);
}

TEST(CarmenWriter, RejectsWhatFlaserCannotHold) {
  const fs::path dir = scratch_dir("write_reject");
  EXPECT_THROW(write_carmen(dir / "empty.log", {}), InputError);

  std::vector<LaserScan> scans = synthetic_scans(3, true);
  scans[2].angle_increment *= 2;
  try {
    write_carmen(dir / "mixed.log", scans);
    ADD_FAILURE() << "no error for differing geometry";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scan 2 has a different angle_increment"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "mixed.log"));

  scans = synthetic_scans(3, true);
  scans[1].timestamp = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_carmen(dir / "nan.log", scans), InputError);
  scans = synthetic_scans(3, true);
  scans[1].ranges.clear();
  EXPECT_THROW(write_carmen(dir / "no_ranges.log", scans), InputError);
  EXPECT_TRUE(fs::is_empty(dir)) << "nothing, not even a temporary file, is left behind";
}

TEST(CarmenWriter, VaryingBeamCountsRoundTrip) {
  const fs::path path = scratch_dir("write_varying") / "out.log";
  std::vector<LaserScan> scans = synthetic_scans(3, true);
  scans[1].ranges.resize(90);
  write_carmen(path, scans);
  expect_same_scans(scans, read_carmen(path).scans);
}

TEST(CarmenWriterRealData, IntelRoundTrip) {
  const fs::path source = test::real_data("carmen/intel.log.gz");
  if (!fs::exists(source)) GTEST_SKIP() << "real data not found at " << source;
  SensorLog log = read_carmen(source);
  log.scans.resize(500);
  const fs::path path = scratch_dir("write_intel") / "intel.log";
  write_carmen(path, log.scans, "first 500 scans of intel");
  expect_same_scans(log.scans, read_carmen(path).scans);
}

}  // namespace
}  // namespace dsswarm
