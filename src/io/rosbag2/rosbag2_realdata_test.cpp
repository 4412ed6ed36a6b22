// The shared CARMEN logs converted to ROS 2 bags (both storages) give the
// trajectories of the CARMEN logs: the same scans and odometry to the bit,
// the same SLAM result with the same seed. A LaserScan holds its beam
// geometry as float32, so the comparison is with the CARMEN log's geometry
// rounded so; the double geometry read from the CARMEN text differs by
// ~5e-10 rad, enough for SLAM to take another path after a few hundred scans.
// mit-csail runs here; intel and fr079 take a minute each and run, with the
// figures for the double geometry, with DSSWARM_ROS2BAG_ALL_LOGS=1
// (scripts/ros2bag_realdata.sh).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include <fmt/format.h>

#include "apps/slam_runner.hpp"
#include "eval/relations.hpp"
#include "io/logs/log_reader.hpp"
#include "io/rosbag2/rosbag2_test_util.hpp"

namespace dsswarm::rosbag2_test {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double angle_apart(double a, double b) { return std::abs(normalize_angle(a - b)); }

// A sensor_msgs/LaserScan holds its geometry as float32: the CARMEN log's
// geometry as a ROS 2 robot would have recorded it.
SensorLog with_float_geometry(SensorLog log) {
  for (LaserScan& s : log.scans) {
    for (double* v : {&s.angle_min, &s.angle_increment, &s.range_min, &s.range_max}) {
      *v = static_cast<float>(*v);
    }
  }
  return log;
}

// Scan by scan, bit for bit: stamps, ranges, geometry, odometry, laser offset.
void expect_same_scans(const SensorLog& expected, const SensorLog& actual) {
  ASSERT_EQ(actual.scans.size(), expected.scans.size());
  for (std::size_t i = 0; i < expected.scans.size(); ++i) {
    const LaserScan& e = expected.scans[i];
    const LaserScan& a = actual.scans[i];
    ASSERT_EQ(a.timestamp, e.timestamp) << i;
    ASSERT_EQ(a.ranges, e.ranges) << i;
    ASSERT_EQ(a.angle_min, e.angle_min) << i;
    ASSERT_EQ(a.angle_increment, e.angle_increment) << i;
    ASSERT_EQ(a.range_min, e.range_min) << i;
    ASSERT_EQ(a.range_max, e.range_max) << i;
    ASSERT_EQ(a.odometry.has_value(), e.odometry.has_value()) << i;
    if (e.odometry) {
      ASSERT_TRUE(*a.odometry == *e.odometry) << i;
    }
    ASSERT_TRUE(a.laser_offset == e.laser_offset) << i;
  }
}

struct Difference {
  double worst = 0.0;        // metres or radians, whichever is larger
  std::size_t first = 0;     // first pose more than 1e-6 apart (size if none)
};

Difference difference(const Trajectory& a, const Trajectory& b) {
  Difference d{0.0, a.size()};
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    const Pose2& p = a[i].pose;
    const Pose2& q = b[i].pose;
    const double e =
        std::max({std::abs(p.x - q.x), std::abs(p.y - q.y), angle_apart(p.theta, q.theta)});
    if (e > 1e-6 && d.first == a.size()) d.first = i;
    d.worst = std::max(d.worst, e);
  }
  return d;
}

std::string accuracy(const Trajectory& t, const fs::path& relations) {
  if (!fs::exists(relations)) return "";
  const RelationMetrics m = evaluate_relations(t, read_relations(relations));
  return fmt::format(" (relations: {:.4f} m, {:.3f} deg)", m.trans_mean, m.rot_mean_deg);
}

constexpr const char* kSlow = "slow: set DSSWARM_ROS2BAG_ALL_LOGS=1 (scripts/ros2bag_realdata.sh)";

bool all_logs() {
  const char* all = std::getenv("DSSWARM_ROS2BAG_ALL_LOGS");
  return all != nullptr && std::string(all) == "1";
}

void expect_bags_give_the_carmen_trajectory(const std::string& name) {
  const fs::path data(DSSWARM_SHARED_DATA);
  const fs::path carmen_path = data / "carmen" / (name + ".log.gz");
  if (!fs::exists(carmen_path)) GTEST_SKIP() << "real data not found at " << carmen_path.string();
  const auto start = std::chrono::steady_clock::now();
  const SensorLog carmen = read_log(carmen_path);
  const std::vector<BagMessage> messages = messages_from_log(carmen);
  SensorLog from_bag;
  for (const Format format : {Format::Db3, Format::McapZstd}) {
    WriteOptions options;
    options.format = format;
    options.chunk_bytes = 768 * 1024;  // rosbag2's default
    const fs::path dir =
        fs::path(DSSWARM_TEST_TMP) / "rosbag2_realdata" / (name + "_" + format_name(format));
    write_bag(dir, messages, options);
    from_bag = read_log(dir);  // as `dsswarm run DIR` reads it
    expect_same_scans(with_float_geometry(carmen), from_bag);
    LogReadOptions tf;  // `dsswarm run DIR --tf-odometry`
    tf.use_tf_odometry = true;
    expect_same_scans(with_float_geometry(carmen), read_log(dir, tf));
    fs::remove_all(dir);
  }
  std::cout << "[ figures  ] " << name << ": " << carmen.scans.size()
            << " scans converted, written and read back in both storages in "
            << seconds_since(start) << " s\n";

  const auto slam_of = [](const SensorLog& log) {
    Slam slam;  // the defaults `dsswarm run` uses, seed included
    return run_slam(log, slam, "").trajectory;
  };
  const Trajectory bag_trajectory = slam_of(from_bag);
  const Trajectory float_trajectory = slam_of(with_float_geometry(carmen));
  const Difference same = difference(float_trajectory, bag_trajectory);
  const fs::path relations = data / "relations" / (name + ".relations");
  std::cout << "[ figures  ] " << name << ": ROS 2 bag vs CARMEN log with float32 geometry: worst "
            << "pose difference " << same.worst << accuracy(bag_trajectory, relations) << "\n";
  if (all_logs()) {  // a third SLAM run: what the double geometry changes
    const Trajectory carmen_trajectory = slam_of(carmen);
    const Difference as_read = difference(carmen_trajectory, bag_trajectory);
    std::cout << "[ figures  ] " << name << ": ROS 2 bag vs CARMEN log as read (double geometry): "
              << "worst " << as_read.worst << ", first pose > 1e-6 apart at scan " << as_read.first
              << " of " << carmen_trajectory.size() << "; CARMEN"
              << accuracy(carmen_trajectory, relations) << "\n";
  }
  std::cout << "[ figures  ] " << name << ": " << seconds_since(start) << " s in all\n";
  ASSERT_EQ(bag_trajectory.size(), carmen.scans.size());
  for (std::size_t i = 0; i < bag_trajectory.size(); ++i) {
    ASSERT_EQ(bag_trajectory[i].timestamp, float_trajectory[i].timestamp) << i;
  }
  EXPECT_EQ(same.worst, 0.0);  // the same input, so the same trajectory
}

TEST(Rosbag2RealData, MitCsailBagsGiveTheCarmenTrajectory) {
  expect_bags_give_the_carmen_trajectory("mit-csail");
}

TEST(Rosbag2RealData, IntelBagsGiveTheCarmenTrajectory) {
  if (!all_logs()) GTEST_SKIP() << kSlow;
  expect_bags_give_the_carmen_trajectory("intel");
}

TEST(Rosbag2RealData, Fr079BagsGiveTheCarmenTrajectory) {
  if (!all_logs()) GTEST_SKIP() << kSlow;
  expect_bags_give_the_carmen_trajectory("fr079");
}

}  // namespace
}  // namespace dsswarm::rosbag2_test
