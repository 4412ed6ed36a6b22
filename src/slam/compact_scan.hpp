#pragma once
// A trajectory node's scan points, kept for loop closure at 4 bytes a point:
// coordinates in the robot base frame as 16-bit integers of 2 mm (±65 m, an
// error of at most 1 mm, far below a cell); weights are recomputed from them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sensor/scan_points.hpp"

namespace dsswarm {

class CompactScan {
 public:
  CompactScan() = default;
  explicit CompactScan(const std::vector<ScanPoint>& points);

  // The points back, weighted as scan_to_points weighs them.
  std::vector<ScanPoint> points(const PointWeightConfig& weights) const;
  std::size_t size() const { return xy_.size(); }
  std::size_t memory_bytes() const { return xy_.capacity() * sizeof(xy_[0]); }

  static constexpr double kUnit = 0.002;  // m per step

 private:
  std::vector<std::array<std::int16_t, 2>> xy_;
};

}  // namespace dsswarm
