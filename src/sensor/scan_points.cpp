#include "sensor/scan_points.hpp"

#include <algorithm>
#include <cmath>

namespace dsswarm {

double point_weight(double x, double y, const PointWeightConfig& config) {
  // cos(bearing) is x / r: no atan2 and cos per point.
  const double r = std::sqrt(x * x + y * y);
  const double ahead = r > 0.0 ? std::max(0.0, x / r) : 1.0;
  return 1.0 + config.forward_gain * std::pow(ahead, config.forward_power);
}

std::vector<ScanPoint> scan_to_points(const LaserScan& scan, const PointWeightConfig& config) {
  std::vector<ScanPoint> points;
  points.reserve(scan.ranges.size());
  const PointTransform to_base(scan.laser_offset);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (!scan.is_valid(r) || r < config.min_range || r > config.max_range) continue;
    const double a = scan.beam_angle(i);
    const Eigen::Vector2d p = to_base(r * std::cos(a), r * std::sin(a));
    points.push_back({static_cast<float>(p.x()), static_cast<float>(p.y()),
                      static_cast<float>(point_weight(p.x(), p.y(), config))});
  }
  return points;
}

}  // namespace dsswarm
