#pragma once
// Small simulated scenes for the swarm tests: a world, scans taken in it, and
// maps built from them in a frame of one's choice.
#include <vector>

#include "common/rng.hpp"
#include "grid/multires_map.hpp"
#include "sensor/scan_points.hpp"
#include "sim/lidar.hpp"
#include "sim/world.hpp"

namespace dsswarm::test {

inline LidarConfig full_circle_lidar() {
  LidarConfig l;
  l.beams = 360;
  l.fov = 2.0 * std::numbers::pi;
  l.noise_std = 0.005;
  return l;
}

// Points of a scan taken by a robot whose base is at `world_pose` (laser at the base).
inline std::vector<ScanPoint> scan_at(const World& world, const Pose2& world_pose, Rng& rng,
                                      const LidarConfig& lidar = full_circle_lidar()) {
  return scan_to_points(simulate_scan(world, world_pose, lidar, rng));
}

// A map of the scans taken at `world_poses`, built in a frame whose origin
// sits at `frame_in_world` (as a robot that started there would build it).
inline MultiResMap map_from(const World& world, const std::vector<Pose2>& world_poses, const Pose2& frame_in_world,
                            Rng& rng, const LidarConfig& lidar = full_circle_lidar()) {
  MultiResMap map;
  for (const Pose2& p : world_poses)
    map.insert_scan(frame_in_world.inverse() * p, Pose2{}, scan_at(world, p, rng, lidar));
  return map;
}

// A room with a few asymmetric features: one unambiguous place to be.
inline World l_shaped_office() {
  std::vector<Segment> w{
      {{0, 0}, {10, 0}}, {{10, 0}, {10, 4}}, {{10, 4}, {4, 4}}, {{4, 4}, {4, 9}}, {{4, 9}, {0, 9}}, {{0, 9}, {0, 0}}};
  std::vector<Box> solids{{{7.0, 1.0}, {7.6, 1.4}}, {{1.0, 6.0}, {1.5, 7.2}}, {{2.2, 2.0}, {2.5, 2.3}}};
  return World(std::move(w), std::move(solids));
}

}  // namespace dsswarm::test
