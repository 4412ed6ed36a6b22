#include "sim/scenario.hpp"

#include <string>

namespace dsswarm {

SimulatedRun simulate_demo(const DemoConfig& config) {
  const World world = generate_world(config.world);
  const std::vector<Eigen::Vector2d> tour = world.waypoint_tour(config.seed);
  SimulatedRun run = simulate_run(world, tour, tour_start_pose(tour), config.robot, config.lidar, config.seed);
  run.log.source = "simulated demo (world seed " + std::to_string(config.world.seed) + ", run seed " +
                   std::to_string(config.seed) + ")";
  return run;
}

}  // namespace dsswarm
