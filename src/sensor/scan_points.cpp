#include "sensor/scan_points.hpp"

#include <algorithm>
#include <cmath>

namespace dsswarm {

double point_weight(double x, double y, const PointWeightConfig& config) {
  const double bearing = std::atan2(y, x);
  const double ahead = std::max(0.0, std::cos(bearing));
  return 1.0 + config.forward_gain * std::pow(ahead, config.forward_power);
}

std::vector<ScanPoint> scan_to_points(const LaserScan& scan, const PointWeightConfig& config) {
  std::vector<ScanPoint> points;
  points.reserve(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (!scan.is_valid(r) || r < config.min_range || r > config.max_range) continue;
    const double a = scan.beam_angle(i);
    const Eigen::Vector2d p = scan.laser_offset * Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
    points.push_back({static_cast<float>(p.x()), static_cast<float>(p.y()),
                      static_cast<float>(point_weight(p.x(), p.y(), config))});
  }
  return points;
}

}  // namespace dsswarm
