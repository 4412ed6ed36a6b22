#include "slam/jump_guard.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

// Feeds `n` matches that each moved `moved` metres off their prediction.
void feed(JumpGuard& guard, int n, double moved) {
  for (int i = 0; i < n; ++i) ASSERT_FALSE(guard.holds_at_prior(Pose2(), Pose2(moved, 0.0, 0.0), 0.01));
}

TEST(JumpGuard, HoldsALeapManyTimesTheUsualCorrectionThatScoresLittleBetter) {
  JumpGuard guard(JumpConfig{});
  feed(guard, 100, 0.004);  // good odometry: corrections of a few millimetres
  EXPECT_TRUE(guard.holds_at_prior(Pose2(1.0, 2.0, 0.3), Pose2(1.0, 2.1, 0.3), 0.02));
  EXPECT_EQ(guard.holds(), 1u);
  // The next ordinary match is taken as found.
  EXPECT_FALSE(guard.holds_at_prior(Pose2(), Pose2(0.003, 0.0, 0.0), 0.01));
}

TEST(JumpGuard, BelievesALeapThatScoresMuchBetter) {
  JumpGuard guard(JumpConfig{});
  feed(guard, 100, 0.004);
  EXPECT_FALSE(guard.holds_at_prior(Pose2(), Pose2(0.1, 0.0, 0.0), 0.2));
  EXPECT_EQ(guard.holds(), 0u);
}

TEST(JumpGuard, ScalesWithTheCorrectionsPoorOdometryNeeds) {
  JumpGuard guard(JumpConfig{});
  feed(guard, 100, 0.03);  // real logs: centimetres per scan
  EXPECT_FALSE(guard.holds_at_prior(Pose2(), Pose2(0.1, 0.0, 0.0), 0.0));
  EXPECT_TRUE(guard.holds_at_prior(Pose2(), Pose2(0.35, 0.0, 0.0), 0.0));
}

TEST(JumpGuard, TheTypicalCorrectionIsTheConfiguredPercentile) {
  // Three in ten matches need a few centimetres: the 90th percentile is one
  // of those, the median is not.
  JumpGuard p90(JumpConfig{});
  JumpGuard p50(JumpConfig{.percentile = 0.5});
  for (JumpGuard* g : {&p90, &p50})
    for (int i = 0; i < 100; ++i) ASSERT_FALSE(g->holds_at_prior(Pose2(), Pose2(i % 10 < 3 ? 0.03 : 0.004, 0.0, 0.0), 0.01));
  EXPECT_FALSE(p90.holds_at_prior(Pose2(), Pose2(0.1, 0.0, 0.0), 0.0));
  EXPECT_TRUE(p50.holds_at_prior(Pose2(), Pose2(0.1, 0.0, 0.0), 0.0));
}

TEST(JumpGuard, NeverHoldsBelowItsMinimumDistance) {
  JumpGuard guard(JumpConfig{});
  feed(guard, 100, 0.0);  // a perfect prediction every time
  EXPECT_FALSE(guard.holds_at_prior(Pose2(), Pose2(0.05, 0.0, 0.0), 0.0));
  EXPECT_TRUE(guard.holds_at_prior(Pose2(), Pose2(0.07, 0.0, 0.0), 0.0));
}

TEST(JumpGuard, JudgesOnlyOnceItHasSeenEnoughCorrections) {
  JumpGuard guard(JumpConfig{});
  feed(guard, JumpConfig{}.min_history - 1, 0.004);
  EXPECT_FALSE(guard.holds_at_prior(Pose2(), Pose2(0.1, 0.0, 0.0), 0.0));  // the 50th: not yet judged
  EXPECT_TRUE(guard.holds_at_prior(Pose2(), Pose2(0.1, 0.0, 0.0), 0.0));
}

TEST(JumpGuard, BelievesALeapTheNextScansKeepAskingFor) {
  const JumpConfig config;
  JumpGuard guard(config);
  feed(guard, 100, 0.004);
  for (int i = 1; i < config.confirm; ++i) EXPECT_TRUE(guard.holds_at_prior(Pose2(), Pose2(0.1, 0.0, 0.0), 0.0));
  EXPECT_FALSE(guard.holds_at_prior(Pose2(), Pose2(0.1, 0.0, 0.0), 0.0));  // drift the odometry missed
  // A prediction not trusted breaks a run of leaps.
  EXPECT_TRUE(guard.holds_at_prior(Pose2(), Pose2(0.1, 0.0, 0.0), 0.0));
  guard.reset();
  for (int i = 1; i < config.confirm; ++i) EXPECT_TRUE(guard.holds_at_prior(Pose2(), Pose2(0.1, 0.0, 0.0), 0.0));
}

TEST(JumpGuard, OffWhenConfirmIsZero) {
  JumpGuard guard(JumpConfig{.confirm = 0});
  feed(guard, 100, 0.004);
  EXPECT_FALSE(guard.holds_at_prior(Pose2(), Pose2(0.5, 0.0, 0.0), 0.0));
}

TEST(JumpGuard, ConfigErrorsNameTheField) {
  EXPECT_THROW(JumpConfig{.factor = 0.0}.validate(), ConfigError);
  EXPECT_THROW(JumpConfig{.min_gain = -1.0}.validate(), ConfigError);
  EXPECT_THROW(JumpConfig{.percentile = 1.5}.validate(), ConfigError);
  try {
    JumpConfig{.history = 10, .min_history = 20}.validate();
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("slam.jump_min_history"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(JumpConfig{}.validate());
}

}  // namespace
}  // namespace dsswarm
