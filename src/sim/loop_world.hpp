#pragma once
// A long loop for loop-closure tests and benchmarks: a rectangular ring of
// corridors around a solid block, with pillars and niches at irregular
// places along the walls (so each stretch looks a little different), and a
// tour that drives around the ring more than once. With a short-range lidar a
// robot sees only its stretch of corridor, so local SLAM drifts over a lap
// and only a loop closure at the start can take the drift out.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "sim/robot.hpp"
#include "sim/world.hpp"

namespace dsswarm {

struct LoopWorldConfig {
  double width = 40.0;     // m, outer walls
  double height = 24.0;
  double corridor = 2.4;   // m between outer and inner walls
  double laps = 1.3;       // times around the ring
  std::uint64_t seed = 1;  // where the pillars and niches go
};

struct LoopWorld {
  World world;
  std::vector<Eigen::Vector2d> tour;  // waypoints along the ring's centre line, counter-clockwise
  Pose2 start;
};

// Throws ConfigError when the ring leaves no corridor to drive in.
LoopWorld make_loop_world(const LoopWorldConfig& config);

}  // namespace dsswarm
