#include "sensor/scan_points.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace dsswarm {
namespace {

LaserScan make_scan(std::vector<float> ranges) {
  LaserScan s;
  s.angle_min = -std::numbers::pi / 2;
  s.angle_increment = std::numbers::pi / static_cast<double>(ranges.size() - 1);
  s.range_min = 0.1;
  s.range_max = 10.0;
  s.ranges = std::move(ranges);
  return s;
}

TEST(LaserScan, InvalidRangesAreNotHits) {
  const LaserScan s = make_scan({1.0f, std::numeric_limits<float>::quiet_NaN(),
                                 std::numeric_limits<float>::infinity(), 0.05f, 10.0f, 12.0f, 2.0f});
  EXPECT_EQ(s.valid_count(), 2u);
  EXPECT_EQ(scan_to_points(s).size(), 2u);
}

TEST(ScanPoints, BeamsLandWhereTheirAnglesPoint) {
  const LaserScan s = make_scan({2.0f, 3.0f, 4.0f});  // -90°, 0°, +90°
  const auto pts = scan_to_points(s);
  ASSERT_EQ(pts.size(), 3u);
  EXPECT_NEAR(pts[0].x, 0.0, 1e-6);
  EXPECT_NEAR(pts[0].y, -2.0, 1e-6);
  EXPECT_NEAR(pts[1].x, 3.0, 1e-6);
  EXPECT_NEAR(pts[1].y, 0.0, 1e-6);
  EXPECT_NEAR(pts[2].y, 4.0, 1e-6);
}

TEST(ScanPoints, LaserOffsetShiftsPointsIntoBaseFrame) {
  LaserScan s = make_scan({2.0f, 3.0f, 4.0f});
  s.laser_offset = Pose2(0.5, 0.0, 0.0);
  const auto pts = scan_to_points(s);
  EXPECT_NEAR(pts[1].x, 3.5, 1e-6);
}

TEST(ScanPoints, PointsAheadWeighMoreThanPointsAside) {
  const LaserScan s = make_scan({2.0f, 2.0f, 2.0f});
  const auto pts = scan_to_points(s);
  EXPECT_GT(pts[1].weight, pts[0].weight);
  EXPECT_NEAR(pts[0].weight, pts[2].weight, 1e-6);
  EXPECT_NEAR(pts[0].weight, 1.0, 1e-6);
}

TEST(ScanPoints, WeightFollowsThePowerOfTheBearingsCosine) {
  const PointWeightConfig c{.forward_gain = 2.0, .forward_power = 3.0};
  EXPECT_NEAR(point_weight(5.0, 0.0, c), 3.0, 1e-12);                         // ahead
  EXPECT_NEAR(point_weight(1.0, std::sqrt(3.0), c), 1.0 + 2.0 / 8.0, 1e-12);  // 60°: cos 0.5
  EXPECT_NEAR(point_weight(0.0, -4.0, c), 1.0, 1e-12);                        // aside
  EXPECT_NEAR(point_weight(-3.0, 1.0, c), 1.0, 1e-12);                        // behind
  EXPECT_NEAR(point_weight(0.0, 0.0, c), 3.0, 1e-12);  // on the laser: bearing 0 by convention
}

TEST(ScanPoints, WholeAndFractionalPowersAgreeWithPow) {
  for (const double power : {0.0, 1.0, 4.0, 7.0, 2.5}) {
    const PointWeightConfig c{.forward_gain = 1.5, .forward_power = power};
    const double ahead = 0.8;  // cos(bearing) of (0.8, 0.6)
    EXPECT_NEAR(point_weight(0.8, 0.6, c), 1.0 + 1.5 * std::pow(ahead, power), 1e-12) << power;
  }
}

TEST(ScanPoints, ALidarWhoseBeamsChangeAngleIsFollowed) {
  // The beams' directions are kept between scans: a scan with other angles
  // (another lidar, a reconfigured driver) must not reuse the last ones.
  LaserScan s = make_scan({2.0f, 3.0f, 4.0f});
  EXPECT_NEAR(scan_to_points(s)[0].y, -2.0, 1e-6);
  s.angle_min = 0.0;  // now 0°, 90°, 180°
  const auto turned = scan_to_points(s);
  EXPECT_NEAR(turned[0].x, 2.0, 1e-6);
  EXPECT_NEAR(turned[1].y, 3.0, 1e-6);
  s.ranges = {2.0f, 3.0f};  // fewer beams, same angles
  EXPECT_NEAR(scan_to_points(s)[1].y, 3.0, 1e-6);
  s.angle_increment = std::numbers::pi / 4;
  EXPECT_NEAR(scan_to_points(s)[1].x, 3.0 * std::cos(std::numbers::pi / 4), 1e-6);
}

TEST(MergeClosePoints, RunsWithinTheDistanceBecomeTheirWeightedCentroid) {
  const std::vector<ScanPoint> points = {{1.00f, 0.0f, 1.0f}, {1.01f, 0.0f, 3.0f}, {1.02f, 0.0f, 1.0f},
                                         {2.00f, 0.0f, 2.0f}, {3.00f, 0.0f, 1.0f}, {3.03f, 0.0f, 1.0f}};
  const auto merged = merge_close_points(points, 0.025);
  ASSERT_EQ(merged.size(), 4u);  // {1.00, 1.01, 1.02}, {2.00}, {3.00}, {3.03}
  EXPECT_NEAR(merged[0].x, (1.00 + 3 * 1.01 + 1.02) / 5, 1e-6);
  EXPECT_NEAR(merged[0].weight, 5.0, 1e-6);
  EXPECT_NEAR(merged[1].x, 2.0, 1e-6);
  EXPECT_NEAR(merged[1].weight, 2.0, 1e-6);
  EXPECT_NEAR(merged[3].x, 3.03, 1e-6);
  double total = 0.0;
  for (const ScanPoint& p : merged) total += p.weight;
  EXPECT_NEAR(total, 9.0, 1e-6);
}

TEST(MergeClosePoints, ARunIsMeasuredFromItsFirstPointNotChained) {
  // Each step is 0.02 m, under the distance, but the run may not creep along a wall.
  std::vector<ScanPoint> points;
  for (int i = 0; i < 10; ++i) points.push_back({0.02f * static_cast<float>(i), 1.0f, 1.0f});
  EXPECT_EQ(merge_close_points(points, 0.05).size(), 4u);  // runs of 3, 3, 3, 1
}

TEST(MergeClosePoints, NoDistanceKeepsEveryPoint) {
  const std::vector<ScanPoint> points = {{1.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 1.0f}};
  EXPECT_EQ(merge_close_points(points, 0.0).size(), 2u);
  EXPECT_TRUE(merge_close_points({}, 0.05).empty());
}

}  // namespace
}  // namespace dsswarm
