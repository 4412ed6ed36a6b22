#include "slam/stall_guard.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dsswarm {
namespace {

// Drives `steps` odometry steps of `step` metres along the heading `theta`;
// each match moves the robot by `share` of the step. Returns the last result.
struct StallDrive {
  StallGuard guard;
  Pose2 pose;

  Pose2 go(int steps, double step, double theta, double share) {
    Pose2 result = pose;
    for (int i = 0; i < steps; ++i) {
      const Pose2 prior = Pose2(pose.x, pose.y, theta) * Pose2(step, 0.0, 0.0);
      const Pose2 raw = Pose2(pose.x, pose.y, theta) * Pose2(share * step, 0.0, 0.0);
      result = guard.check(pose, prior, raw, raw);
      pose = result;
    }
    return result;
  }
};

TEST(StallGuard, AMapThatHoldsTheRobotBackIsOverruledAlongTheMotion) {
  StallDrive d{StallGuard(StallConfig{}), Pose2(1.0, 2.0, 0.5)};
  // Driving 3 m at 6 cm per scan while the matches move it 2 mm a scan.
  const Pose2 end = d.go(50, 0.06, 0.5, 0.03);
  const double covered = std::hypot(end.x - 1.0, end.y - 2.0);
  EXPECT_GT(covered, 2.7);  // the matches alone: 0.1 m
  EXPECT_GT(d.guard.holds(), 45u);
  // Along the motion only: the heading the matches gave stays.
  EXPECT_NEAR(end.theta, 0.5, 1e-9);
}

TEST(StallGuard, WhenItStepsInTheRobotIsMovedOnByWhatTheMatchesFellShort) {
  // Driving 3 m at 6 cm per scan from the start while the matches stand still.
  StallDrive d{StallGuard(StallConfig{}), Pose2(1.0, 2.0, 0.5)};
  const Pose2 end = d.go(50, 0.06, 0.5, 0.0);
  EXPECT_NEAR(std::hypot(end.x - 1.0, end.y - 2.0), 3.0, 1e-9);
  EXPECT_NEAR(std::atan2(end.y - 2.0, end.x - 1.0), 0.5, 1e-9);  // along the motion
  // Without catching up, the 0.18 m before it stepped in stay lost.
  StallConfig config;
  config.catch_up = false;
  StallDrive behind{StallGuard(config), Pose2(1.0, 2.0, 0.5)};
  const Pose2 lagging = behind.go(50, 0.06, 0.5, 0.0);
  EXPECT_NEAR(std::hypot(lagging.x - 1.0, lagging.y - 2.0), 3.0 - 0.18, 1e-9);
}

TEST(StallGuard, MatchesThatKeepUpAreLeftAlone) {
  StallDrive d{StallGuard(StallConfig{}), Pose2()};
  const Pose2 end = d.go(50, 0.06, 0.0, 0.9);
  EXPECT_EQ(d.guard.holds(), 0u);
  EXPECT_NEAR(end.x, 50 * 0.054, 1e-9);
}

TEST(StallGuard, OnlyWhileTheMapIsYoung) {
  StallConfig config;
  config.young_travel = 1.0;
  StallDrive d{StallGuard(config), Pose2()};
  d.go(50, 0.06, 0.0, 0.9);  // 3 m of travel that kept up
  d.go(50, 0.06, 0.0, 0.0);  // then a stall: the map is no longer young
  EXPECT_EQ(d.guard.holds(), 0u);
  config.window = 0.0;  // off
  StallDrive off{StallGuard(config), Pose2()};
  off.go(50, 0.06, 0.0, 0.0);
  EXPECT_EQ(off.guard.holds(), 0u);
}

TEST(StallGuard, AResetForgetsTheWindow) {
  StallDrive d{StallGuard(StallConfig{}), Pose2()};
  d.go(3, 0.06, 0.0, 0.0);  // 0.18 m: under the 0.2 m window
  d.guard.reset();
  d.go(3, 0.06, 0.0, 0.0);  // another 0.18 m after it: still under
  EXPECT_EQ(d.guard.holds(), 0u);
  d.go(1, 0.06, 0.0, 0.0);
  EXPECT_GT(d.guard.holds(), 0u);
}

TEST(StallGuard, ABadConfigNamesTheField) {
  try {
    StallConfig{.min_progress = 1.5}.validate();
    FAIL() << "accepted min_progress 1.5";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("slam.stall_min_progress"), std::string::npos) << e.what();
  }
  EXPECT_THROW(StallConfig{.window = -1.0}.validate(), std::exception);
  EXPECT_NO_THROW(StallConfig{}.validate());
}

}  // namespace
}  // namespace dsswarm
