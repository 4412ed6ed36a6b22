#include "sensor/scan_points.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dsswarm {

namespace {

// A whole power by repeated squaring: the default power is 4, and libm's pow
// is a long call for what is two multiplications.
double whole_power(double base, unsigned exponent) {
  double result = 1.0;
  for (; exponent > 0; exponent >>= 1, base *= base)
    if (exponent & 1u) result *= base;
  return result;
}

// The cosine and sine of every beam's angle, kept from one scan to the next:
// a lidar's beams keep their angles, so each scan's trigonometry is a lookup.
// Per thread, so concurrent callers (one Slam per robot) never share it.
class BeamDirections {
 public:
  void update(const LaserScan& scan) {
    if (scan.angle_min == angle_min_ && scan.angle_increment == increment_ && cos_.size() == scan.ranges.size())
      return;
    angle_min_ = scan.angle_min;
    increment_ = scan.angle_increment;
    cos_.resize(scan.ranges.size());
    sin_.resize(scan.ranges.size());
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      const double a = scan.beam_angle(i);
      cos_[i] = std::cos(a);
      sin_[i] = std::sin(a);
    }
  }
  double cos(std::size_t i) const { return cos_[i]; }
  double sin(std::size_t i) const { return sin_[i]; }

 private:
  double angle_min_ = std::numeric_limits<double>::quiet_NaN(), increment_ = angle_min_;  // NaN: nothing kept yet
  std::vector<double> cos_, sin_;
};

}  // namespace

double point_weight(double x, double y, const PointWeightConfig& config) {
  // cos(bearing) is x / r: no atan2 and cos per point.
  const double r = std::sqrt(x * x + y * y);
  const double ahead = r > 0.0 ? std::max(0.0, x / r) : 1.0;
  const double power = config.forward_power;
  const bool whole = power >= 0.0 && power <= 64.0 && power == std::floor(power);
  return 1.0 + config.forward_gain *
                   (whole ? whole_power(ahead, static_cast<unsigned>(power)) : std::pow(ahead, power));
}

std::vector<ScanPoint> scan_to_points(const LaserScan& scan, const PointWeightConfig& config) {
  thread_local BeamDirections directions;
  directions.update(scan);
  std::vector<ScanPoint> points;
  points.reserve(scan.ranges.size());
  const PointTransform to_base(scan.laser_offset);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (!scan.is_valid(r) || r < config.min_range || r > config.max_range) continue;
    const Eigen::Vector2d p = to_base(r * directions.cos(i), r * directions.sin(i));
    points.push_back({static_cast<float>(p.x()), static_cast<float>(p.y()),
                      static_cast<float>(point_weight(p.x(), p.y(), config))});
  }
  return points;
}

std::vector<ScanPoint> merge_close_points(const std::vector<ScanPoint>& points, double distance) {
  if (distance <= 0.0 || points.empty()) return points;
  std::vector<ScanPoint> merged;
  merged.reserve(points.size());
  const double squared = distance * distance;
  const ScanPoint* first = &points.front();  // of the current run
  double sx = 0.0, sy = 0.0, sw = 0.0;       // the run's weighted sums
  const auto close_run = [&] {
    // A run of weightless points keeps its first point's place.
    if (sw > 0.0) merged.push_back({static_cast<float>(sx / sw), static_cast<float>(sy / sw), static_cast<float>(sw)});
    else merged.push_back({first->x, first->y, 0.0f});
  };
  for (const ScanPoint& p : points) {
    const double dx = p.x - first->x, dy = p.y - first->y;
    if (dx * dx + dy * dy >= squared) {
      close_run();
      first = &p;
      sx = sy = sw = 0.0;
    }
    sx += static_cast<double>(p.weight) * p.x;
    sy += static_cast<double>(p.weight) * p.y;
    sw += p.weight;
  }
  close_run();
  return merged;
}

}  // namespace dsswarm
