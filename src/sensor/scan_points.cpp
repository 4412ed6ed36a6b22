#include "sensor/scan_points.hpp"

#include <algorithm>
#include <cmath>

namespace dsswarm {

std::vector<ScanPoint> scan_to_points(const LaserScan& scan, const PointWeightConfig& config) {
  std::vector<ScanPoint> points;
  points.reserve(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (!scan.is_valid(r) || r < config.min_range || r > config.max_range) continue;
    const double a = scan.beam_angle(i);
    const Eigen::Vector2d p = scan.laser_offset * Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
    const double bearing = std::atan2(p.y(), p.x());
    const double ahead = std::max(0.0, std::cos(bearing));
    const double w = 1.0 + config.forward_gain * std::pow(ahead, config.forward_power);
    points.push_back({static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(w)});
  }
  return points;
}

}  // namespace dsswarm
