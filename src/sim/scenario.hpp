#pragma once
// The built-in default dataset: one robot touring the default generated
// building for a few minutes, with exact ground truth to score SLAM against.
#include <cstdint>

#include "sim/lidar.hpp"
#include "sim/robot.hpp"
#include "sim/world.hpp"

namespace dsswarm {

struct DemoConfig {
  WorldConfig world;
  LidarConfig lidar;
  RobotConfig robot;
  std::uint64_t seed = 7;  // tour and sensor noise (the building comes from world.seed)
};

// Generates the world, tours it from the first corridor's start and returns
// the log (about 1500-3000 scans with the defaults) and the ground truth.
SimulatedRun simulate_demo(const DemoConfig& config);

}  // namespace dsswarm
