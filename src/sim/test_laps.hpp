#pragma once
// Test runs in the corridor ring of loop_world.hpp: a lap with an 8 m lidar,
// for tests of loop closure between robots (slam, swarm).
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

}  // namespace dsswarm::test
