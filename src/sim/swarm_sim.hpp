#pragma once
// Several robots in one generated building, for decentralized multi-robot
// SLAM. Each robot starts somewhere else with a random heading and its
// odometry at identity there (its map frame is its own start pose, so the
// robots do not know where the others are), explores its share of the rooms
// along shared corridors, and finally drives to a common rendezvous area (at
// the begin end of the first corridor) and parks there, scanning, until the
// last robot has arrived plus 10 s. Robots are not in each other's lidar
// and may pass through each other.
// All robots scan on one clock, so every log has the same timestamps.
#include <cstdint>
#include <string>
#include <vector>

#include "sim/lidar.hpp"
#include "sim/robot.hpp"
#include "sim/world.hpp"

namespace dsswarm {

// A building sized for `robots` robots: for up to 3 the default building
// (30 x 20 m, 8 rooms, one corridor within the lidar's 30 m); for more,
// about 2 rooms per robot and a corridor per 4 robots (joined by a spine),
// with 3 m corridors so that up to 9 robots park within 3 m of each other.
// Throws ConfigError when robots is outside [1, 64].
WorldConfig swarm_world_config(int robots);

// Seconds the robots keep scanning together once the last one has parked:
// long enough for a proximity sensor to raise two events (a merge is
// confirmed by a second encounter) before the run ends.
inline constexpr double kSwarmWaitAfterLastArrival = 30.0;

struct SwarmSimConfig {
  WorldConfig world = swarm_world_config(3);  // for other robot counts use swarm_world_config(robots)
  LidarConfig lidar;
  RobotConfig robot;
  int robots = 3;
  std::uint64_t seed = 1;  // starts, headings, room split and sensor noise (the building comes from world.seed)
};

// Throws ConfigError naming the field.
void validate(const SwarmSimConfig& config);

struct SimulatedSwarm {
  World world;
  std::vector<std::string> names;  // "robot1".."robotN"
  std::vector<SimulatedRun> runs;  // per robot; identical timestamps k / rate_hz, k = 0..n-1
  // Ground truth of the plan, for tests and evaluation (the robots do not know it):
  std::vector<Eigen::Vector2d> parking_spots;  // per robot, in the rendezvous area
  std::vector<double> arrival_times;           // per robot: when it reached its parking spot
  Box rendezvous_area;                         // bounding box of the parking spots, grown by 0.5 m
};

// Deterministic from config.seed and config.world.seed.
SimulatedSwarm simulate_swarm(const SwarmSimConfig& config);

}  // namespace dsswarm
