#include "slam/compact_scan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dsswarm {
namespace {
std::int16_t quantize(float v) {
  constexpr double lo = std::numeric_limits<std::int16_t>::min(), hi = std::numeric_limits<std::int16_t>::max();
  return static_cast<std::int16_t>(std::clamp(std::round(v / CompactScan::kUnit), lo, hi));
}
}  // namespace

CompactScan::CompactScan(const std::vector<ScanPoint>& points) {
  xy_.reserve(points.size());
  for (const ScanPoint& p : points) xy_.push_back({quantize(p.x), quantize(p.y)});
}

std::vector<ScanPoint> CompactScan::points(const PointWeightConfig& weights) const {
  std::vector<ScanPoint> out;
  out.reserve(xy_.size());
  for (const auto& q : xy_) {
    const double x = q[0] * kUnit, y = q[1] * kUnit;
    out.push_back({static_cast<float>(x), static_cast<float>(y), static_cast<float>(point_weight(x, y, weights))});
  }
  return out;
}

}  // namespace dsswarm
