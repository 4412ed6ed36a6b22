#pragma once
// Test runs in the corridor ring of loop_world.hpp with an 8 m lidar, for
// tests of loop closure (slam, swarm).
#include <cstdint>
#include <vector>

#include "sim/loop_world.hpp"

namespace dsswarm::test {

// A lap of the corridor ring: from the middle of a long side (corner 0), or
// from corner `corner` (1-3) round to the same corner.
inline SimulatedRun lap(int corner, std::uint64_t seed) {
  LoopWorldConfig config;
  config.laps = 2.0;
  const LoopWorld w = make_loop_world(config);
  LidarConfig lidar;
  lidar.range_max = 8.0;
  lidar.noise_std = 0.02;
  if (corner == 0) {
    const std::vector<Eigen::Vector2d> tour(w.tour.begin(), w.tour.begin() + 5);
    return simulate_run(w.world, tour, w.start, RobotConfig{}, lidar, seed);
  }
  const std::vector<Eigen::Vector2d> tour(w.tour.begin() + corner - 1, w.tour.begin() + corner + 4);
  return simulate_run(w.world, tour, tour_start_pose(tour), RobotConfig{}, lidar, seed);
}

// `laps` laps of the 40 m × 24 m ring from the middle of a long side, odometry turning
// 0.05 rad too much per metre: a drift that only loop closure takes out.
inline SimulatedRun long_loop(double laps = 1.3, std::uint64_t seed = 1) {
  LoopWorldConfig config;
  config.laps = laps;
  const LoopWorld w = make_loop_world(config);
  LidarConfig lidar;
  lidar.range_max = 8.0;
  lidar.noise_std = 0.02;
  RobotConfig robot;
  robot.odom_drift = 0.05;
  return simulate_run(w.world, w.tour, w.start, robot, lidar, seed);
}

}  // namespace dsswarm::test
