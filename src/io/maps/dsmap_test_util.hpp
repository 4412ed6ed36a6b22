#pragma once
// Maps shared by the .dsmap tests (dsmap_test.cpp, dsmap_reject_test.cpp): a
// small room mapped from a few poses, and a two-layer snapshot of it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include "grid/multires_map.hpp"
#include "io/maps/dsmap.hpp"
#include "sensor/scan_points.hpp"

namespace dsswarm::dsmap_test {

// Beams from `pose` to the walls of the room [-3, 3] × [-2, 2], in the base frame.
inline std::vector<ScanPoint> room_scan(const Pose2& pose) {
  std::vector<ScanPoint> pts;
  for (int i = 0; i < 360; ++i) {
    const double a = (i - 180) * std::numbers::pi / 180.0;
    const double dx = std::cos(pose.theta + a), dy = std::sin(pose.theta + a);
    double t = std::numeric_limits<double>::infinity();
    if (dx > 1e-9) t = std::min(t, (3.0 - pose.x) / dx);
    if (dx < -1e-9) t = std::min(t, (-3.0 - pose.x) / dx);
    if (dy > 1e-9) t = std::min(t, (2.0 - pose.y) / dy);
    if (dy < -1e-9) t = std::min(t, (-2.0 - pose.y) / dy);
    pts.push_back({static_cast<float>(t * std::cos(a)), static_cast<float>(t * std::sin(a)), 1.0f});
  }
  return pts;
}

inline std::shared_ptr<MultiResMap> room_map(const MapConfig& config) {
  auto map = std::make_shared<MultiResMap>(config);
  for (int s = 0; s < 5; ++s) {
    const Pose2 pose(-1.0 + 0.4 * s, -0.5 + 0.2 * s, 0.3 * s);
    map->insert_scan(pose, Pose2(0.1, 0.0, 0.0), room_scan(pose));
  }
  return map;
}

inline MapSnapshot two_layer_snapshot() {
  MapConfig config;
  config.resolution = 0.05;
  config.levels = 3;
  config.evidence.hit_occupied = 0.35f;
  config.evidence.pass_free = 0.07f;
  config.evidence.min_unknown = 0.03f;
  config.free_space_on_coarse_levels = true;  // coarse levels carry free mass too: every plane is exercised
  MapSnapshot s;
  s.sender = "alpha";
  s.layers.push_back({"alpha", 42, Pose2(), 0, room_map(config), {}});
  auto other = std::make_shared<MultiResMap>(config);
  other->insert_scan(Pose2(0.5, 0.2, -0.4), Pose2(), room_scan(Pose2(0.5, 0.2, -0.4)));
  s.layers.push_back({"bravo", 7, Pose2(12.5, -3.25, 2.5), 2, other, {}});
  return s;
}


}  // namespace dsswarm::dsmap_test
