// The ROS1 bag reader on the shared real bags (skipped when ../shared/data
// is absent): their scans, odometry and laser offsets against the CARMEN
// logs they were converted from.
#include <gtest/gtest.h>
#include <zlib.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.hpp"
#include "common/test_files.hpp"
#include "io/atomic_file.hpp"
#include "io/rosbag/rosbag_reader.hpp"
#include "io/rosbag/rosbag_test_util.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using namespace rosbag_test;
using test::fresh_dir;

// ---------------------------------------------------------------- the real data sets

fs::path shared_data() { return fs::path(DSSWARM_SHARED_DATA); }

// Each real bag is read once per test run (intel takes about a second); the
// first read reports its speed.
const SensorLog& real_log(const std::string& name) {
  static std::map<std::string, SensorLog> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    const std::clock_t cpu_start = std::clock();
    const auto start = std::chrono::steady_clock::now();
    SensorLog log = read_rosbag(shared_data() / "bags" / (name + ".orig.bag"));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    std::cout << "[ timing   ] " << name << ".orig.bag: " << log.scans.size() << " scans in "
              << seconds << " s wall, " << cpu_seconds << " s CPU\n";
    it = cache.emplace(name, std::move(log)).first;
  }
  return it->second;
}

#define REQUIRE_REAL_BAG(name)                                                 \
  if (!fs::exists(shared_data() / "bags" / (std::string(name) + ".orig.bag"))) \
  GTEST_SKIP() << "real data not found at " << (shared_data() / "bags").string()

// One FLASER record of a CARMEN log:
// FLASER n r1..rn x y theta odom_x odom_y odom_theta timestamp host logger_timestamp
struct CarmenScan {
  std::vector<double> ranges;
  Pose2 odometry;
  double timestamp = 0.0;
};

// The FLASER records of a gzip-compressed CARMEN log, in file order.
std::vector<CarmenScan> read_carmen_scans(const fs::path& path) {
  std::vector<CarmenScan> scans;
  gzFile in = gzopen(path.string().c_str(), "rb");
  if (in == nullptr) return scans;
  std::vector<char> line(1 << 16);
  while (gzgets(in, line.data(), static_cast<int>(line.size())) != nullptr) {
    std::istringstream fields(line.data());
    std::string kind;
    std::size_t n = 0;
    if (!(fields >> kind) || kind != "FLASER" || !(fields >> n)) continue;
    CarmenScan scan;
    scan.ranges.resize(n);
    for (double& r : scan.ranges) fields >> r;
    double laser_x = 0, laser_y = 0, laser_theta = 0, x = 0, y = 0, theta = 0;
    fields >> laser_x >> laser_y >> laser_theta >> x >> y >> theta >> scan.timestamp;
    if (!fields) ADD_FAILURE() << "bad FLASER line in " << path;
    scan.odometry = Pose2(x, y, theta);
    scans.push_back(std::move(scan));
  }
  gzclose(in);
  return scans;
}

// Same scans, stamps, ranges and odometry as the CARMEN log converted from the same bag.
void expect_matches_carmen(const std::string& name, std::size_t stride) {
  const fs::path carmen_path = shared_data() / "carmen" / (name + ".log.gz");
  if (!fs::exists(carmen_path)) GTEST_SKIP() << "real data not found at " << carmen_path.string();
  const SensorLog& log = real_log(name);
  const std::vector<CarmenScan> carmen = read_carmen_scans(carmen_path);
  ASSERT_EQ(carmen.size(), log.scans.size());
  double worst_range = 0, worst_odometry = 0, worst_stamp = 0;
  for (std::size_t i = 0; i < carmen.size(); i += stride) {
    const LaserScan& scan = log.scans[i];
    worst_stamp = std::max(worst_stamp, std::abs(scan.timestamp - carmen[i].timestamp));
    ASSERT_EQ(scan.ranges.size(), carmen[i].ranges.size()) << i;
    for (std::size_t b = 0; b < scan.ranges.size(); ++b) {
      worst_range = std::max(worst_range, std::abs(scan.ranges[b] - carmen[i].ranges[b]));
    }
    ASSERT_TRUE(scan.odometry.has_value()) << i;
    const Pose2& odo = *scan.odometry;
    const Pose2& ref = carmen[i].odometry;
    worst_odometry = std::max({worst_odometry, std::abs(odo.x - ref.x), std::abs(odo.y - ref.y),
                               std::abs(normalize_angle(odo.theta - ref.theta))});
  }
  EXPECT_LT(worst_stamp, 2e-6);  // CARMEN prints microseconds
  EXPECT_LT(worst_range, 1e-3);
  EXPECT_LT(worst_odometry, 1e-3);
}

TEST(RosbagRealData, Intel) {
  REQUIRE_REAL_BAG("intel");
  const SensorLog& log = real_log("intel");

  ASSERT_EQ(log.scans.size(), 13631U);
  for (const LaserScan& s : log.scans) {
    ASSERT_EQ(s.ranges.size(), 180U);
    ASSERT_TRUE(s.odometry.has_value());
  }
  EXPECT_NEAR(log.scans.front().angle_min, -kPi / 2, 1e-6);
  EXPECT_NEAR(log.scans.front().angle_increment, kPi / 179, 1e-6);
  EXPECT_NEAR(log.scans.front().range_max, 80.0, 1e-9);
  EXPECT_EQ(log.scans.front().laser_offset.x, 0.0);
  EXPECT_TRUE(has_warning(log, "631 of 13631 scan timestamps run backwards (kept in file order)"))
      << joined(log.warnings);
}

TEST(RosbagRealData, IntelMatchesItsCarmenLog) {
  REQUIRE_REAL_BAG("intel");
  expect_matches_carmen("intel", 1);  // includes the ~800 scans with glitched stamps
}

TEST(RosbagRealData, Fr079LaserOffsetFromTfStatic) {
  REQUIRE_REAL_BAG("fr079");
  const SensorLog& log = real_log("fr079");
  ASSERT_EQ(log.scans.size(), 4934U);
  EXPECT_EQ(log.scans.front().ranges.size(), 360U);
  for (const LaserScan& s : {log.scans.front(), log.scans.back()}) {
    EXPECT_NEAR(s.laser_offset.x, 0.04, 1e-9);
    EXPECT_NEAR(s.laser_offset.y, 0.0, 1e-9);
    EXPECT_NEAR(s.laser_offset.theta, 0.0, 1e-9);
  }
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
}

TEST(RosbagRealData, MitCsailMatchesItsCarmenLog) {
  REQUIRE_REAL_BAG("mit-csail");
  const SensorLog& log = real_log("mit-csail");
  ASSERT_EQ(log.scans.size(), 1988U);
  EXPECT_EQ(log.scans.front().ranges.size(), 361U);
  EXPECT_NEAR(log.scans.front().angle_increment, kPi / 360, 1e-6);
  EXPECT_TRUE(log.warnings.empty()) << joined(log.warnings);
  expect_matches_carmen("mit-csail", 1);
}

TEST(RosbagRealData, MitCsailFirstScanByHand) {
  // The first FLASER line, parsed here field by field, against the first scan.
  REQUIRE_REAL_BAG("mit-csail");
  const fs::path carmen_path = shared_data() / "carmen" / "mit-csail.log.gz";
  if (!fs::exists(carmen_path)) GTEST_SKIP() << "real data not found at " << carmen_path.string();
  const std::vector<CarmenScan> carmen = read_carmen_scans(carmen_path);
  ASSERT_FALSE(carmen.empty());
  const LaserScan& first = real_log("mit-csail").scans.front();
  EXPECT_NEAR(first.timestamp, 1134864629.895182, 2e-6);
  EXPECT_NEAR(first.timestamp, carmen.front().timestamp, 2e-6);
  ASSERT_EQ(first.ranges.size(), 361U);
  EXPECT_NEAR(first.ranges[0], 1.4, 1e-6);
  EXPECT_NEAR(first.ranges[24], 81.91, 1e-4);
  EXPECT_FALSE(first.is_valid(first.ranges[24]));  // "no return"
  expect_pose_near(first.odometry, Pose2(576.536523, 0.106594, -2.255213), 1e-6);
}

TEST(RosbagRealData, TruncatedRealBagIsAnInputError) {
  REQUIRE_REAL_BAG("mit-csail");
  const std::string bytes = read_bytes(shared_data() / "bags" / "mit-csail.orig.bag");
  ASSERT_GT(bytes.size(), 100'000U);
  const fs::path cut = fresh_dir("rosbag_truncated_real") / "mit-csail-100k.bag";
  write_file_atomically(cut, std::string_view(bytes).substr(0, 100'000));
  const std::string message = input_error_of(cut);
  EXPECT_NE(message.find("mit-csail-100k.bag"), std::string::npos) << message;
}

}  // namespace
}  // namespace dsswarm
