#include "net/ros_names.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"

namespace dsswarm::net {
namespace {

TEST(RosNames, NamespacesAreNormalised) {
  EXPECT_EQ(normalize_namespace(""), "/");
  EXPECT_EQ(normalize_namespace("/"), "/");
  EXPECT_EQ(normalize_namespace("robot1"), "/robot1");
  EXPECT_EQ(normalize_namespace("/robot1/"), "/robot1");
  EXPECT_EQ(normalize_namespace("/swarm/robot_1"), "/swarm/robot_1");
}

TEST(RosNames, InvalidNamespacesAreRejected) {
  EXPECT_THROW(normalize_namespace("/a//b"), ConfigError);
  EXPECT_THROW(normalize_namespace("/1robot"), ConfigError);
  EXPECT_THROW(normalize_namespace("/a b"), ConfigError);
  EXPECT_THROW(normalize_namespace("/robot-1"), ConfigError);
}

TEST(RosNames, RelativeNamesGoUnderTheNamespaceAbsoluteOnesStay) {
  EXPECT_EQ(ros_topic_name("/robot1", "scan"), "rt/robot1/scan");
  EXPECT_EQ(ros_topic_name("robot1/", "scan"), "rt/robot1/scan");
  EXPECT_EQ(ros_topic_name("", "scan"), "rt/scan");
  EXPECT_EQ(ros_topic_name("/", "laser/scan"), "rt/laser/scan");
  EXPECT_EQ(ros_topic_name("/robot1", "/map"), "rt/map");
  EXPECT_EQ(ros_topic_name("/robot1", "/tf"), "rt/tf");
}

TEST(RosNames, InvalidTopicNamesAreRejected) {
  EXPECT_THROW(ros_topic_name("/robot1", ""), ConfigError);
  EXPECT_THROW(ros_topic_name("/robot1", "~/scan"), ConfigError);
  EXPECT_THROW(ros_topic_name("/robot1", "scan/"), ConfigError);
  EXPECT_THROW(ros_topic_name("/robot1", "//scan"), ConfigError);
  EXPECT_THROW(ros_topic_name("/robot1", "2scan"), ConfigError);
}

TEST(RosNames, FramesLoseTheirLeadingSlash) {
  EXPECT_EQ(strip_frame_slash("/base_link"), "base_link");
  EXPECT_EQ(strip_frame_slash("laser"), "laser");
  EXPECT_EQ(strip_frame_slash(""), "");
}

}  // namespace
}  // namespace dsswarm::net
