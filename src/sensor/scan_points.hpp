#pragma once
// Converts the valid beams of a scan into 2D points in the robot base frame,
// each with a matching weight. Points ahead of the robot weigh more: in a
// corridor the side walls pin only the lateral position, and only the few
// returns from the end of the corridor pin the position along it.
#include <vector>

#include "sensor/laser_scan.hpp"

namespace dsswarm {

struct ScanPoint {
  float x = 0.0f;  // metres, robot base frame
  float y = 0.0f;
  float weight = 1.0f;
};

struct PointWeightConfig {
  // w = 1 + forward_gain * max(0, cos(bearing))^forward_power, bearing measured
  // in the base frame (0 = straight ahead).
  double forward_gain = 1.0;
  double forward_power = 4.0;
  // Skip hits closer than this to the laser (robot's own body, dust).
  double min_range = 0.05;
  // Hits further than this are not used for matching (angular noise grows with range).
  double max_range = 40.0;
};

std::vector<ScanPoint> scan_to_points(const LaserScan& scan, const PointWeightConfig& config = {});

// The weight of a point at (x, y) in the robot base frame.
double point_weight(double x, double y, const PointWeightConfig& config);

// `points` with each run of consecutive points lying within `distance` of the
// run's first point made one point, at their weighted centroid and with
// their summed weight (the total weight is kept). Near the lidar its beams
// fall several to a grid cell; scoring them one by one costs time and tells
// the matcher nothing a single point there does not. `distance` <= 0 keeps
// every point.
std::vector<ScanPoint> merge_close_points(const std::vector<ScanPoint>& points, double distance);

}  // namespace dsswarm
