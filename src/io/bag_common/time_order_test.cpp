#include "io/bag_common/time_order.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "io/bag_common/odometry_track.hpp"

namespace dsswarm {
namespace {

TEST(TimeOrder, CountsBackwardSteps) {
  EXPECT_EQ(count_backward_steps(std::vector<double>{}), 0U);
  EXPECT_EQ(count_backward_steps(std::vector<double>{1.0, 1.0, 2.0}), 0U);
  EXPECT_EQ(count_backward_steps(std::vector<double>{1.0, 3.0, 2.0, 4.0, 0.5}), 2U);
}

TEST(TimeOrder, LongestNondecreasingDropsAStampThatJumpsAhead) {
  // The intel pattern: one stamp jumps ahead, the next ones continue normally.
  const std::vector<double> stamps{0.0, 0.1, 0.56, 0.3, 0.4, 0.5, 0.6};
  const std::vector<bool> expected{true, true, false, true, true, true, true};
  EXPECT_EQ(longest_nondecreasing(stamps), expected);
}

TEST(TimeOrder, LongestNondecreasingDropsAStampThatFallsBehind) {
  const std::vector<double> stamps{0.0, 0.1, 0.2, -0.5, 0.3, 0.3};
  const std::vector<bool> expected{true, true, true, false, true, true};
  EXPECT_EQ(longest_nondecreasing(stamps), expected);
  EXPECT_TRUE(longest_nondecreasing(std::vector<double>{}).empty());
}

TEST(TimeOrder, LookupTimesInterpolateOutOfOrderRecordsByPosition) {
  const std::vector<double> stamps{5.0, 1.0, 2.0, 9.0, 9.5, 3.5, 4.0, 0.0};
  const std::vector<bool> in_order = longest_nondecreasing(stamps);
  const std::vector<bool> expected_order{false, true, true, false, false, true, true, false};
  ASSERT_EQ(in_order, expected_order);
  const std::vector<double> times = lookup_times(stamps, in_order);
  ASSERT_EQ(times.size(), stamps.size());
  EXPECT_DOUBLE_EQ(times[0], 1.0);  // before the first in-order record: its stamp
  EXPECT_DOUBLE_EQ(times[1], 1.0);
  EXPECT_DOUBLE_EQ(times[2], 2.0);
  EXPECT_DOUBLE_EQ(times[3], 2.5);  // a third of the way from 2.0 (index 2) to 3.5 (index 5)
  EXPECT_DOUBLE_EQ(times[4], 3.0);
  EXPECT_DOUBLE_EQ(times[5], 3.5);
  EXPECT_DOUBLE_EQ(times[7], 4.0);  // after the last: its stamp
}

TEST(OdometryTrack, InterpolatesLinearlyAndAlongTheShortestArc) {
  const double pi = std::numbers::pi;
  const OdometryTrack track(
      {{10.0, Pose2(0.0, 0.0, pi - 0.1)}, {12.0, Pose2(2.0, -4.0, -pi + 0.1)}});
  const auto mid = track.at(11.0, 0.5);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR(mid->x, 1.0, 1e-12);
  EXPECT_NEAR(mid->y, -2.0, 1e-12);
  EXPECT_NEAR(std::abs(mid->theta), pi, 1e-9);  // through ±pi, not through 0
  const auto quarter = track.at(10.5, 0.5);
  ASSERT_TRUE(quarter.has_value());
  EXPECT_NEAR(quarter->theta, pi - 0.05, 1e-9);
}

TEST(OdometryTrack, HoldsTheEndPosesWithinTheToleranceOnly) {
  const OdometryTrack track(
      {{10.0, Pose2(1.0, 0.0, 0.0)}, {11.0, Pose2(2.0, 0.0, 0.0)}, {11.0, Pose2(3.0, 0.0, 0.0)}});
  ASSERT_TRUE(track.at(9.6, 0.5).has_value());
  EXPECT_DOUBLE_EQ(track.at(9.6, 0.5)->x, 1.0);
  EXPECT_DOUBLE_EQ(track.at(11.4, 0.5)->x, 3.0);
  EXPECT_DOUBLE_EQ(track.at(11.0, 0.5)->x, 3.0);  // equal stamps: the later record
  EXPECT_FALSE(track.at(9.4, 0.5).has_value());
  EXPECT_FALSE(track.at(11.6, 0.5).has_value());
  EXPECT_FALSE(OdometryTrack({}).at(0.0, 0.5).has_value());
}

}  // namespace
}  // namespace dsswarm
