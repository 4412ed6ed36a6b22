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

}  // namespace
}  // namespace dsswarm
