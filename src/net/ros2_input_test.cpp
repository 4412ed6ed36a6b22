#include "net/ros2_input.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <thread>
#include <vector>

#include "net/net_test_util.hpp"
#include "net/qos.hpp"
#include "net/ros_names.hpp"
#include "net/sensor_publisher.hpp"

namespace dsswarm::net {
namespace {

using namespace std::chrono_literals;
using test::bits;
using test::loopback_config;
using test::test_namespace;

constexpr auto kTimeout = 5s;
constexpr double kStart = 1.7e9;  // a realistic epoch stamp

LaserScan make_scan(double stamp, int index) {
  LaserScan s;
  s.timestamp = stamp;
  s.angle_min = -1.5;
  s.angle_increment = 0.01;
  s.range_min = 0.1;
  s.range_max = 30.0;
  for (int i = 0; i < 301; ++i) s.ranges.push_back(1.0f + 0.001f * static_cast<float>(i + index));
  s.ranges[3] = std::numeric_limits<float>::infinity();  // no return
  s.ranges[4] = std::numeric_limits<float>::quiet_NaN();  // invalid reading
  s.odometry = Pose2(0.1 * index, -0.05 * index, 0.02 * index);
  s.laser_offset = Pose2(0.2, 0.0, 0.1);
  return s;
}

void expect_pose_near(const Pose2& a, const Pose2& b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(normalize_angle(a.theta - b.theta), 0.0, tolerance);
}

// An Odometry message putting frame `base` (borrowed: it must outlive the
// message) at `pose` at time `stamp`.
ros::Odometry odometry_message(double stamp, const Pose2& pose, const std::string& base) {
  ros::Odometry o{};
  o.header.stamp = to_ros_time(stamp);
  o.child_frame_id = borrow(base);
  o.pose.pose = to_ros_pose(pose);
  return o;
}

// Takes `played.size()` scans from `input`: each must be the one played, in
// order, with exactly its own odometry.
void expect_each_scan_with_its_own_odometry(LiveScanSource& input, const std::vector<LaserScan>& played) {
  for (const LaserScan& want : played) {
    const std::optional<LaserScan> got = input.next(kTimeout);
    ASSERT_TRUE(got.has_value());
    EXPECT_NEAR(got->timestamp, want.timestamp, 1e-6);
    ASSERT_TRUE(got->odometry.has_value()) << "scan at " << want.timestamp - kStart;
    expect_pose_near(*got->odometry, *want.odometry, 1e-9);
  }
  EXPECT_EQ(input.stats().scans_without_odometry, 0u);
}

// Everything under this test's namespace, tf included, so that no other test
// (sharing a domain by chance) can feed it.
LiveInputConfig input_config() {
  LiveInputConfig c;
  c.ns = test_namespace();
  c.tf_topic = "tf";
  c.tf_static_topic = "tf_static";
  return c;
}

SensorPublisherConfig sensors_config() {
  SensorPublisherConfig c;
  c.ns = test_namespace();
  c.tf_topic = "tf";
  c.tf_static_topic = "tf_static";
  return c;
}

template <class Condition>
bool eventually(Condition condition) {
  const auto deadline = std::chrono::steady_clock::now() + kTimeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(5ms);
  }
  return true;
}

// The two ends of a robot on loopback: its sensors, and our live input.
struct Robot {
  explicit Robot(const LiveInputConfig& config = input_config())
      : sensor_participant(loopback_config()), agent_participant(loopback_config()) {
    sensors.emplace(sensor_participant, sensors_config());
    input.emplace(agent_participant, config);
  }
  Participant sensor_participant;
  Participant agent_participant;
  std::optional<SensorPublisher> sensors;
  std::optional<LiveScanSource> input;
};

TEST(LiveScanSource, ScansAndOdometryArriveAsPublished) {
  Robot robot;
  ASSERT_TRUE(robot.sensors->wait_for_subscribers(1, kTimeout));
  for (int i = 0; i < 20; ++i) {
    const LaserScan expected = make_scan(kStart + 0.025 * i, i);
    robot.sensors->publish(expected);
    const std::optional<LaserScan> got = robot.input->next(kTimeout);
    ASSERT_TRUE(got.has_value());
    EXPECT_NEAR(got->timestamp, expected.timestamp, 1e-6);  // ROS time has nanoseconds
    EXPECT_EQ(bits(got->ranges), bits(expected.ranges));
    EXPECT_FLOAT_EQ(static_cast<float>(got->angle_min), static_cast<float>(expected.angle_min));
    EXPECT_FLOAT_EQ(static_cast<float>(got->angle_increment), static_cast<float>(expected.angle_increment));
    EXPECT_FLOAT_EQ(static_cast<float>(got->range_max), static_cast<float>(expected.range_max));
    ASSERT_TRUE(got->odometry.has_value());
    expect_pose_near(*got->odometry, *expected.odometry, 1e-9);
    expect_pose_near(got->laser_offset, expected.laser_offset, 1e-9);
  }
  const LiveInputStats stats = robot.input->stats();
  EXPECT_EQ(stats.scans_delivered, 20u);
  EXPECT_EQ(stats.scans_dropped, 0u);
  EXPECT_EQ(stats.scans_without_odometry, 0u);
}

TEST(LiveScanSource, OdometryIsInterpolatedAtTheScanStamp) {
  Participant robot(loopback_config());
  Participant agent(loopback_config());
  LiveInputConfig config = input_config();
  LiveScanSource input(agent, config);
  Topic<ros::Odometry> odom_topic(robot, ros_topic_name(config.ns, "odom"));
  Writer<ros::Odometry> odom(odom_topic, ros_default(10));
  Topic<ros::LaserScan> scan_topic(robot, ros_topic_name(config.ns, "scan"));
  Writer<ros::LaserScan> scan(scan_topic, ros_sensor_data());
  ASSERT_TRUE(odom.wait_for_readers(1, kTimeout));
  ASSERT_TRUE(scan.wait_for_readers(1, kTimeout));

  const std::string base = "base_link";
  for (int i = 0; i < 3; ++i)  // odometry at 0.0, 0.1, 0.2 s moving 1 m/s along x, turning 1 rad/s
    odom.write(odometry_message(kStart + 0.1 * i, Pose2(0.1 * i, 0.0, 0.1 * i), base));
  const LaserScan s = make_scan(kStart + 0.15, 0);
  scan.write(to_ros_scan(s, base));  // the laser at the base frame: no offset needed
  const std::optional<LaserScan> got = input.next(kTimeout);
  ASSERT_TRUE(got.has_value());
  ASSERT_TRUE(got->odometry.has_value());
  expect_pose_near(*got->odometry, Pose2(0.15, 0.0, 0.15), 1e-6);
  expect_pose_near(got->laser_offset, Pose2(), 0.0);
}

// A log played backward (`replay --scenario` of a backward agent): stamps
// decrease, so the odometry already held is all later than the next scan —
// which must still wait for, and get, exactly its own odometry, however its
// own arrives after it. The run is longer than the odometry history.
TEST(LiveScanSource, ABackwardPlayedStreamGetsEachScansOwnOdometry) {
  Participant robot(loopback_config());
  Participant agent(loopback_config());
  LiveInputConfig config = input_config();
  config.queue_capacity = 64;
  config.wait_for_odometry = 2.0;  // a loaded machine may delay the odometry; the old rule did not wait at all
  LiveScanSource input(agent, config);
  Topic<ros::Odometry> odom_topic(robot, ros_topic_name(config.ns, "odom"));
  Writer<ros::Odometry> odom(odom_topic, ros_default(50));
  Topic<ros::LaserScan> scan_topic(robot, ros_topic_name(config.ns, "scan"));
  Writer<ros::LaserScan> scan(scan_topic, ros_default(50));
  ASSERT_TRUE(odom.wait_for_readers(1, kTimeout));
  ASSERT_TRUE(scan.wait_for_readers(1, kTimeout));

  constexpr int kScans = 40;
  const double spacing = 1.5 * config.odometry_history / kScans;
  const std::string base = "base_link";
  std::vector<LaserScan> played;
  for (int i = kScans - 1; i >= 0; --i) played.push_back(make_scan(kStart + spacing * i, i));
  std::jthread robot_side([&] {
    for (const LaserScan& s : played) {
      scan.write(to_ros_scan(s, base));  // the scan first, its odometry a moment later
      std::this_thread::sleep_for(20ms);
      odom.write(odometry_message(s.timestamp, *s.odometry, base));
      std::this_thread::sleep_for(20ms);
    }
  });
  expect_each_scan_with_its_own_odometry(input, played);
}

// A consumer far behind the stream (a busy machine, a log played fast): the
// scans it has yet to take still find their odometry, though the stream has
// run on by more than the odometry history since.
TEST(LiveScanSource, AConsumerFarBehindStillGetsEachScansOdometry) {
  Participant robot(loopback_config());
  Participant agent(loopback_config());
  LiveInputConfig config = input_config();
  config.queue_capacity = 64;
  config.odometry_history = 0.5;  // s of scan time; the stream below spans 3 s
  config.wait_for_odometry = 2.0;
  LiveScanSource input(agent, config);
  Topic<ros::Odometry> odom_topic(robot, ros_topic_name(config.ns, "odom"));
  Writer<ros::Odometry> odom(odom_topic, ros_default(100));
  Topic<ros::LaserScan> scan_topic(robot, ros_topic_name(config.ns, "scan"));
  Writer<ros::LaserScan> scan(scan_topic, ros_default(100));
  ASSERT_TRUE(odom.wait_for_readers(1, kTimeout));
  ASSERT_TRUE(scan.wait_for_readers(1, kTimeout));

  constexpr int kScans = 30;
  const std::string base = "base_link";
  std::vector<LaserScan> played;
  for (int i = 0; i < kScans; ++i) played.push_back(make_scan(kStart + 0.1 * i, i));
  for (const LaserScan& s : played) {
    scan.write(to_ros_scan(s, base));
    odom.write(odometry_message(s.timestamp, *s.odometry, base));
  }
  std::this_thread::sleep_for(200ms);  // all of it has arrived before the first scan is taken
  expect_each_scan_with_its_own_odometry(input, played);
}

TEST(LiveScanSource, OdometryAndLaserMountFromTfThroughIntermediateFrames) {
  Participant robot(loopback_config());
  Participant agent(loopback_config());
  LiveInputConfig config = input_config();
  config.odometry = OdometrySource::kTf;
  LiveScanSource input(agent, config);
  Topic<ros::TFMessage> tf_topic(robot, ros_topic_name(config.ns, "tf"));
  Topic<ros::TFMessage> static_topic(robot, ros_topic_name(config.ns, "tf_static"));
  Writer<ros::TFMessage> tf(tf_topic, ros_tf());
  Writer<ros::TFMessage> tf_static(static_topic, ros_tf_static(1));
  Topic<ros::LaserScan> scan_topic(robot, ros_topic_name(config.ns, "scan"));
  Writer<ros::LaserScan> scan(scan_topic, ros_sensor_data());
  ASSERT_TRUE(tf.wait_for_readers(1, kTimeout));
  ASSERT_TRUE(scan.wait_for_readers(1, kTimeout));

  const std::string odom = "odom", base = "/base_link", mount = "mount", laser = "laser", other = "map";
  std::vector<ros::TransformStamped> statics = {
      to_ros_transform_stamped(kStart, base, mount, Pose2(0.1, 0.0, 0.0)),
      to_ros_transform_stamped(kStart, mount, laser, Pose2(0.0, 0.05, std::numbers::pi / 2)),
  };
  ros::TFMessage static_msg{};
  static_msg.transforms = {2, 2, statics.data(), false};
  tf_static.write(static_msg);
  for (int i = 0; i < 2; ++i) {
    std::vector<ros::TransformStamped> ts = {
        to_ros_transform_stamped(kStart + i, odom, base, Pose2(i, 2.0 * i, 0.0)),
        to_ros_transform_stamped(kStart + i, other, odom, Pose2(50.0, 50.0, 1.0)),  // not odometry
    };
    ros::TFMessage msg{};
    msg.transforms = {2, 2, ts.data(), false};
    tf.write(msg);
  }
  scan.write(to_ros_scan(make_scan(kStart + 0.5, 0), laser));
  const std::optional<LaserScan> got = input.next(kTimeout);
  ASSERT_TRUE(got.has_value());
  ASSERT_TRUE(got->odometry.has_value());
  expect_pose_near(*got->odometry, Pose2(0.5, 1.0, 0.0), 1e-6);
  expect_pose_near(got->laser_offset, Pose2(0.1, 0.05, std::numbers::pi / 2), 1e-9);
}

TEST(LiveScanSource, WhenTheConsumerFallsBehindTheOldestScansAreDroppedAndCounted) {
  LiveInputConfig config = input_config();
  config.queue_capacity = 3;
  Robot robot(config);
  ASSERT_TRUE(robot.sensors->wait_for_subscribers(1, kTimeout));
  for (int i = 0; i < 10; ++i) robot.sensors->publish(make_scan(kStart + 0.025 * i, i));
  ASSERT_TRUE(eventually([&] { return robot.input->stats().scans_received == 10; }));
  for (int i = 7; i < 10; ++i) {
    const std::optional<LaserScan> got = robot.input->next(kTimeout);
    ASSERT_TRUE(got.has_value());
    EXPECT_NEAR(got->timestamp, kStart + 0.025 * i, 1e-6);
  }
  EXPECT_FALSE(robot.input->next(50ms).has_value());
  EXPECT_EQ(robot.input->stats().scans_dropped, 7u);
}

TEST(LiveScanSource, ScansWithoutOdometryGoOutAfterTheWait) {
  LiveInputConfig config = input_config();
  config.wait_for_odometry = 0.1;
  Participant robot(loopback_config());
  Participant agent(loopback_config());
  LiveScanSource input(agent, config);
  Topic<ros::LaserScan> scan_topic(robot, ros_topic_name(config.ns, "scan"));
  Writer<ros::LaserScan> scan(scan_topic, ros_sensor_data());
  ASSERT_TRUE(scan.wait_for_readers(1, kTimeout));
  const std::string base = "base_link";
  scan.write(to_ros_scan(make_scan(kStart, 0), base));
  const auto t0 = std::chrono::steady_clock::now();
  const std::optional<LaserScan> got = input.next(kTimeout);
  ASSERT_TRUE(got.has_value());
  EXPECT_GE(std::chrono::steady_clock::now() - t0, 90ms);
  EXPECT_FALSE(got->odometry.has_value());
  EXPECT_EQ(input.stats().scans_without_odometry, 1u);
}

TEST(LiveScanSource, WakeEndsAWaitingNext) {
  Participant agent(loopback_config());
  LiveScanSource input(agent, input_config());
  std::thread waker([&] {
    std::this_thread::sleep_for(50ms);
    input.wake();
  });
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_FALSE(input.next(kTimeout).has_value());
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 2s);
  waker.join();
}

TEST(LiveScanSource, MalformedSamplesAreRejectedAndCounted) {
  Participant robot(loopback_config());
  Participant agent(loopback_config());
  LiveInputConfig config = input_config();
  config.wait_for_odometry = 0.0;
  LiveScanSource input(agent, config);
  Topic<ros::LaserScan> scan_topic(robot, ros_topic_name(config.ns, "scan"));
  Topic<ros::Odometry> odom_topic(robot, ros_topic_name(config.ns, "odom"));
  Topic<ros::TFMessage> static_topic(robot, ros_topic_name(config.ns, "tf_static"));
  Writer<ros::LaserScan> scan(scan_topic, ros_default(50));
  Writer<ros::Odometry> odom(odom_topic, ros_default(50));
  Writer<ros::TFMessage> tf_static(static_topic, ros_tf_static(1));
  ASSERT_TRUE(scan.wait_for_readers(1, kTimeout));
  ASSERT_TRUE(odom.wait_for_readers(1, kTimeout));
  ASSERT_TRUE(tf_static.wait_for_readers(1, kTimeout));

  const std::string frame = "base_link", laser = "laser";
  const LaserScan good = make_scan(kStart, 0);
  const auto send_scan = [&](auto&& damage) {
    LaserScan s = good;
    ros::LaserScan m = to_ros_scan(s, frame);
    std::vector<float> ranges = s.ranges;
    damage(m, ranges);
    borrow(m.ranges, ranges);
    scan.write(m);
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  send_scan([&](ros::LaserScan& m, std::vector<float>&) { m.angle_increment = nan; });
  send_scan([&](ros::LaserScan& m, std::vector<float>&) { m.angle_increment = 0.0f; });
  send_scan([&](ros::LaserScan& m, std::vector<float>&) { m.range_max = -1.0f; });
  send_scan([&](ros::LaserScan&, std::vector<float>& r) { r.assign(100000, 1.0f); });  // a huge beam count
  send_scan([&](ros::LaserScan&, std::vector<float>& r) { r.clear(); });
  send_scan([&](ros::LaserScan& m, std::vector<float>&) { m.header.stamp.nanosec = 2'000'000'000u; });

  ros::Odometry o{};
  o.header.stamp = to_ros_time(kStart);
  o.pose.pose = to_ros_pose(Pose2(1.0, 2.0, 0.0));
  o.pose.pose.position.x = std::numeric_limits<double>::infinity();
  odom.write(o);
  o.pose.pose = to_ros_pose(Pose2(1.0, 2.0, 0.0));
  o.pose.pose.orientation = {0.0, 0.0, 0.0, 0.0};  // not a rotation
  odom.write(o);

  ros::TransformStamped t = to_ros_transform_stamped(kStart, frame, laser, Pose2());
  t.transform.translation.y = std::numeric_limits<double>::quiet_NaN();
  ros::TFMessage statics{};
  statics.transforms = {1, 1, &t, false};
  tf_static.write(statics);

  send_scan([](ros::LaserScan&, std::vector<float>&) {});  // a good one: still served
  const std::optional<LaserScan> got = input.next(kTimeout);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(bits(got->ranges), bits(good.ranges));
  EXPECT_TRUE(eventually([&] {
    const LiveInputStats s = input.stats();
    return s.odometry_rejected + s.transforms_rejected == 3;
  }));
  const LiveInputStats stats = input.stats();
  EXPECT_EQ(stats.scans_rejected, 6u);
  EXPECT_EQ(stats.scans_received, 1u);
  EXPECT_EQ(stats.odometry_rejected, 2u);
  EXPECT_EQ(stats.odometry_received, 0u);
  EXPECT_EQ(stats.transforms_rejected, 1u);
}

}  // namespace
}  // namespace dsswarm::net
