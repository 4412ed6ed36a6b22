#include "net/ros2_output.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/errors.hpp"
#include "io/maps/map_server.hpp"
#include "net/net_test_util.hpp"
#include "net/qos.hpp"
#include "net/ros_names.hpp"

namespace dsswarm::net {
namespace {

using namespace std::chrono_literals;
using test::loopback_config;
using test::test_namespace;

constexpr auto kMapTimeout = 5s;

// A received map, copied out of the loaned sample.
struct ReceivedMap {
  std::string frame;
  double stamp = 0.0;
  float resolution = 0.0f;
  std::uint32_t width = 0, height = 0;
  Pose2 origin;
  std::vector<std::int8_t> data;
};

std::optional<ReceivedMap> take_map(const Reader<ros::OccupancyGrid>& reader, std::chrono::milliseconds timeout) {
  std::optional<ReceivedMap> got;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!got && std::chrono::steady_clock::now() < deadline) {
    reader.wait(10ms);
    reader.take(1, [&](const ros::OccupancyGrid& m, const dds_sample_info_t&) {
      got = ReceivedMap{m.header.frame_id, to_seconds(m.header.stamp), m.info.resolution, m.info.width,
                        m.info.height, to_pose2(m.info.origin),
                        std::vector<std::int8_t>(m.data._buffer, m.data._buffer + m.data._length)};
    });
  }
  return got;
}

// A 3x2 raster with one occupied, one free, one unknown and in-between cells.
GridRaster small_raster(float occupied_mass) {
  GridRaster r;
  r.width = 3;
  r.height = 2;
  r.resolution = 0.05;
  r.origin = {-1.0, 2.5};
  r.cells = {{occupied_mass, 0.0f}, {0.0f, 0.9f}, DsMass::vacuous(), {0.2f, 0.1f}, {0.0f, 0.5f}, {0.5f, 0.3f}};
  return r;
}

MapPublisherConfig map_config() {
  MapPublisherConfig c;
  c.ns = test_namespace();
  c.topic = "map";
  return c;
}

TEST(MapPublisher, ALateJoinerGetsTheNewestMapOnlyAsNav2Subscribes) {
  Participant agent(loopback_config());
  Participant viewer(loopback_config());
  MapPublisher maps(agent, map_config());
  maps.publish(small_raster(0.2f), 100.0);
  ASSERT_TRUE(maps.flush(kMapTimeout));
  maps.publish(small_raster(0.9f), 101.0);
  ASSERT_TRUE(maps.flush(kMapTimeout));

  Topic<ros::OccupancyGrid> topic(viewer, ros_topic_name(test_namespace(), "map"));
  Reader<ros::OccupancyGrid> nav2(topic, ros_transient_local(1));
  const std::optional<ReceivedMap> got = take_map(nav2, kMapTimeout);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->stamp, 101.0);
  EXPECT_EQ(got->frame, "map");
  EXPECT_EQ(got->width, 3u);
  EXPECT_EQ(got->height, 2u);
  EXPECT_FLOAT_EQ(got->resolution, 0.05f);
  EXPECT_EQ(got->origin.x, -1.0);
  EXPECT_EQ(got->origin.y, 2.5);
  EXPECT_EQ(got->origin.theta, 0.0);
  // occupancy = 0.5 + (occupied - free) / 2 against 0.65 / 0.196.
  EXPECT_EQ(got->data, (std::vector<std::int8_t>{100, 0, -1, -1, -1, -1}));
  EXPECT_FALSE(take_map(nav2, 200ms).has_value()) << "only the newest map is latched";
  EXPECT_EQ(maps.stats().published, 2u);
}

TEST(MapPublisher, AVolatileViewerGetsMapsPublishedAfterItJoined) {
  Participant agent(loopback_config());
  Participant viewer(loopback_config());
  MapPublisher maps(agent, map_config());
  Topic<ros::OccupancyGrid> topic(viewer, ros_topic_name(test_namespace(), "map"));
  Reader<ros::OccupancyGrid> rviz(topic, ros_default(5));
  ASSERT_TRUE(rviz.wait_for_writers(1, kMapTimeout));
  maps.publish(small_raster(0.9f), 7.0);
  const std::optional<ReceivedMap> got = take_map(rviz, kMapTimeout);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->stamp, 7.0);
}

TEST(MapPublisher, CellsReadAsMapServerReadsOurSavedMap) {
  Participant agent(loopback_config());
  MapPublisher maps(agent, map_config());
  Topic<ros::OccupancyGrid> topic(agent, ros_topic_name(test_namespace(), "map"));
  Reader<ros::OccupancyGrid> reader(topic, ros_transient_local(1));
  GridRaster raster;
  raster.width = 40;
  raster.height = 30;
  raster.origin = {3.0, -4.0};
  for (int i = 0; i < raster.width * raster.height; ++i) {
    const float o = static_cast<float>(i % 11) / 11.0f, f = static_cast<float>(i % 7) / 14.0f;
    raster.cells.push_back({o * (1.0f - f), f});
  }
  const std::filesystem::path dir = std::filesystem::path(DSSWARM_TEST_TMP) / ("net_map_" + test::test_id());
  std::filesystem::create_directories(dir);
  write_map_server(dir / "map.yaml", raster);
  const LoadedMap saved = read_map_server(dir / "map.yaml");
  std::filesystem::remove_all(dir);

  maps.publish(raster, 1.0);
  const std::optional<ReceivedMap> got = take_map(reader, kMapTimeout);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->data, saved.occupancy);
}

TEST(MapPublisher, PublishesAtMostOncePerPeriod) {
  Participant agent(loopback_config());
  MapPublisherConfig config = map_config();
  config.min_period = 1.0;
  MapPublisher maps(agent, config);
  const auto t0 = SteadyClock::now();
  int built = 0;
  const auto build = [&] {
    ++built;
    return small_raster(0.9f);
  };
  EXPECT_TRUE(maps.publish_if_due(t0, 1.0, build));
  EXPECT_FALSE(maps.publish_if_due(t0 + 500ms, 1.5, build));
  EXPECT_TRUE(maps.publish_if_due(t0 + 1000ms, 2.0, build));
  EXPECT_EQ(built, 2);
  EXPECT_TRUE(maps.flush(kMapTimeout));
  const MapPublisherStats stats = maps.stats();
  EXPECT_EQ(stats.published + stats.superseded, 2u);
}

TEST(MapPublisher, InconsistentRastersAndThresholdsAreRefused) {
  Participant agent(loopback_config());
  MapPublisher maps(agent, map_config());
  GridRaster bad = small_raster(0.9f);
  bad.cells.pop_back();
  EXPECT_THROW(maps.publish(bad, 1.0), InputError);
  MapPublisherConfig config = map_config();
  config.classes.free_thresh = 0.9;
  EXPECT_THROW(MapPublisher(agent, config), ConfigError);
}

// /tf, pose and path as rviz2 would read them.
struct PoseViewer {
  explicit PoseViewer(Participant& p)
      : tf_topic(p, ros_topic_name(test_namespace(), "tf")),
        pose_topic(p, ros_topic_name(test_namespace(), "pose")),
        path_topic(p, ros_topic_name(test_namespace(), "path")),
        tf(tf_topic, ros_tf()),
        pose(pose_topic, ros_default(10)),
        path(path_topic, ros_default(1)) {}
  Topic<ros::TFMessage> tf_topic;
  Topic<ros::PoseStamped> pose_topic;
  Topic<ros::Path> path_topic;
  Reader<ros::TFMessage> tf;
  Reader<ros::PoseStamped> pose;
  Reader<ros::Path> path;
};

PoseOutputConfig pose_config() {
  PoseOutputConfig c;
  c.ns = test_namespace();
  c.tf_topic = "tf";
  return c;
}

struct Transform {
  std::string parent, child;
  Pose2 pose;
};

std::optional<Transform> take_transform(const Reader<ros::TFMessage>& reader) {
  std::optional<Transform> got;
  const auto deadline = std::chrono::steady_clock::now() + kMapTimeout;
  while (!got && std::chrono::steady_clock::now() < deadline) {
    reader.wait(10ms);
    reader.take(1, [&](const ros::TFMessage& m, const dds_sample_info_t&) {
      if (m.transforms._length != 1) return;
      const auto& t = m.transforms._buffer[0];
      got = Transform{t.header.frame_id, t.child_frame_id, to_pose2(t.transform)};
    });
  }
  return got;
}

TEST(PoseOutput, MapToOdomComposesWithOdometryToTheMapPose) {
  Participant agent(loopback_config());
  Participant viewer_participant(loopback_config());
  PoseViewer viewer(viewer_participant);
  PoseOutput output(agent, pose_config());
  ASSERT_TRUE(viewer.tf.wait_for_writers(1, kMapTimeout));
  ASSERT_TRUE(viewer.pose.wait_for_writers(1, kMapTimeout));
  const Pose2 map_pose(4.0, -2.0, 2.5), odom_pose(1.0, 3.0, -0.7);
  EXPECT_TRUE(output.publish(10.0, map_pose, odom_pose));

  const std::optional<Transform> t = take_transform(viewer.tf);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->parent, "map");
  EXPECT_EQ(t->child, "odom");
  const Pose2 composed = t->pose * odom_pose;  // map → odom → base_link
  EXPECT_NEAR(composed.x, map_pose.x, 1e-9);
  EXPECT_NEAR(composed.y, map_pose.y, 1e-9);
  EXPECT_NEAR(normalize_angle(composed.theta - map_pose.theta), 0.0, 1e-9);

  std::optional<Pose2> pose;
  std::string frame;
  ASSERT_TRUE(viewer.pose.wait(kMapTimeout));
  viewer.pose.take(1, [&](const ros::PoseStamped& m, const dds_sample_info_t&) {
    pose = to_pose2(m.pose);
    frame = m.header.frame_id;
  });
  ASSERT_TRUE(pose.has_value());
  EXPECT_EQ(frame, "map");
  EXPECT_NEAR(pose->x, 4.0, 1e-12);
  EXPECT_NEAR(pose->theta, 2.5, 1e-12);
}

TEST(PoseOutput, WithoutOdometryTheMapPoseGoesToTheBaseFrame) {
  Participant agent(loopback_config());
  PoseViewer viewer(agent);
  PoseOutput output(agent, pose_config());
  ASSERT_TRUE(viewer.tf.wait_for_writers(1, kMapTimeout));
  output.publish(10.0, Pose2(1.0, 2.0, 0.5), std::nullopt);
  const std::optional<Transform> t = take_transform(viewer.tf);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->child, "base_link");
  EXPECT_NEAR(t->pose.x, 1.0, 1e-12);
}

TEST(PoseOutput, ThePathStaysBoundedAndWhole) {
  Participant agent(loopback_config());
  PoseViewer viewer(agent);
  PoseOutputConfig config = pose_config();
  config.path_max_poses = 8;
  config.path_period = 0.0;
  PoseOutput output(agent, config);
  ASSERT_TRUE(viewer.path.wait_for_writers(1, kMapTimeout));
  output.publish(0.0, Pose2(0.0, 0.0, 0.0), std::nullopt);
  output.publish(0.1, Pose2(0.01, 0.0, 0.0), std::nullopt);  // too close: not added
  EXPECT_EQ(output.path_size(), 1u);
  for (int i = 1; i < 40; ++i) output.publish(0.1 * i, Pose2(0.5 * i, 0.0, 0.0), std::nullopt);
  EXPECT_LE(output.path_size(), 8u);
  EXPECT_GE(output.path_size(), 4u);

  std::vector<double> xs;
  const auto deadline = std::chrono::steady_clock::now() + kMapTimeout;
  while (std::chrono::steady_clock::now() < deadline && (xs.empty() || xs.back() != 19.5)) {
    viewer.path.wait(10ms);
    viewer.path.take(1, [&](const ros::Path& m, const dds_sample_info_t&) {
      xs.clear();
      for (std::uint32_t i = 0; i < m.poses._length; ++i) xs.push_back(m.poses._buffer[i].pose.position.x);
    });
  }
  ASSERT_FALSE(xs.empty());
  EXPECT_EQ(xs.front(), 0.0) << "the start is kept";
  EXPECT_EQ(xs.back(), 19.5) << "the newest pose is there";
}

}  // namespace
}  // namespace dsswarm::net
