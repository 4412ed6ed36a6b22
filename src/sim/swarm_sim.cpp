#include "sim/swarm_sim.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "common/errors.hpp"
#include "common/rng.hpp"
#include "sim/swarm_plan.hpp"

namespace dsswarm {
namespace {

constexpr int kMaxRobots = 64;

}  // namespace

void validate(const SwarmSimConfig& c) {
  require_config("swarm config", c.robots >= 1 && c.robots <= kMaxRobots, "robots must be in [1, " + std::to_string(kMaxRobots) + "]");
  validate(c.world);
  validate(c.lidar);
  validate(c.robot);
}

WorldConfig swarm_world_config(int robots) {
  require_config("swarm config", robots >= 1 && robots <= kMaxRobots, "robots must be in [1, " + std::to_string(kMaxRobots) + "]");
  WorldConfig config;
  constexpr double kRoomWidth = 7.5, kRoomDepth = 9.0;  // as in the default building
  if (robots <= 3) {
    // The default building. Its 30 m corridors stay within the lidar's range
    // (30 m): in a longer featureless corridor a scan cannot tell how far the
    // robot has driven, and single-robot SLAM leans on odometry alone there.
  } else {
    // About 2 rooms per robot, a corridor per 4 robots; rooms as in the
    // default building. 3 m corridors leave a 3x3 grid of parking spots 1 m
    // apart at the rendezvous (all within 3 m of each other).
    const int corridors = (robots + 3) / 4;
    config.rooms_y = 2 * corridors;
    config.rooms_x = std::max(4, (2 * robots + config.rooms_y - 1) / config.rooms_y);
    config.corridor_width = 3.0;
    const double spine = corridors > 1 ? config.corridor_width : 0.0;
    config.width = spine + config.rooms_x * kRoomWidth;
    config.height = config.rooms_y * kRoomDepth + corridors * config.corridor_width;
  }
  validate(config);
  return config;
}

namespace {

// Robot `r`'s log along its path (poses at every lidar step): odometry and
// scans from its own random streams.
SimulatedRun record_robot(const World& world, const DrivenPath& path, const SwarmSimConfig& config,
                          std::size_t r, const std::string& name) {
  const std::size_t steps = path.poses.size();
  const std::uint64_t robot_seed = stream_seed(config.seed, 1 + r);
  Rng odometry_rng(stream_seed(robot_seed, 1));
  Rng lidar_rng(stream_seed(robot_seed, 2));
  const std::vector<Pose2> odometry = simulate_odometry(path.poses, config.robot, odometry_rng);

  SimulatedRun run;
  run.log.source = "simulated swarm, " + name + " of " + std::to_string(config.robots) + " (world seed " +
                   std::to_string(config.world.seed) + ", swarm seed " + std::to_string(config.seed) + ")";
  if (!path.reached_goal) run.log.warnings.push_back(name + " ran out of time before its parking spot");
  run.log.scans.reserve(steps);
  run.ground_truth.reserve(steps);
  for (std::size_t k = 0; k < steps; ++k) {
    LaserScan scan = simulate_scan(world, path.poses[k] * config.robot.laser_offset, config.lidar, lidar_rng);
    scan.timestamp = static_cast<double>(k) / config.lidar.rate_hz;
    scan.odometry = odometry[k];
    scan.laser_offset = config.robot.laser_offset;
    run.ground_truth.emplace_back(scan.timestamp, path.poses[k]);
    run.log.scans.push_back(std::move(scan));
  }
  return run;
}

}  // namespace

SimulatedSwarm simulate_swarm(const SwarmSimConfig& config) {
  validate(config);
  SimulatedSwarm swarm{generate_world(config.world), {}, {}, {}, {}, {}};
  const World& world = swarm.world;
  using namespace sim_detail;  // the plan's pieces (swarm_plan.hpp)
  const CorridorNetwork network(world.layout().corridors);
  require_config("swarm config", !world.layout().corridors.empty(), "world: the building has no corridors");
  const auto robots = static_cast<std::size_t>(config.robots);
  Rng plan_rng(stream_seed(config.seed, 0));

  swarm.parking_spots = parking_spots(world, world.layout().corridors.front().begin, config.robots);
  const std::vector<StartSpot> starts = pick_starts(world, network, swarm.parking_spots, config.robots, plan_rng);
  const std::vector<std::vector<int>> visits = split_rooms(world, network, starts, plan_rng);

  const double dt = 1.0 / config.lidar.rate_hz;
  std::vector<DrivenPath> paths;
  std::size_t longest = 0;
  for (std::size_t r = 0; r < robots; ++r) {
    const Pose2 start(starts[r].position.x(), starts[r].position.y(),
                      plan_rng.uniform(-std::numbers::pi, std::numbers::pi));
    const auto route = plan_route(world, network, starts[r], visits[r], swarm.parking_spots[r], plan_rng);
    paths.push_back(drive_waypoints(route, start, config.robot, dt));
    longest = std::max(longest, paths.back().poses.size());
  }
  // One clock for all: everyone scans until the last arrival plus a wait.
  const std::size_t steps = longest + static_cast<std::size_t>(std::ceil(kSwarmWaitAfterLastArrival / dt));

  swarm.rendezvous_area = {swarm.parking_spots.front(), swarm.parking_spots.front()};
  for (const Eigen::Vector2d& p : swarm.parking_spots)
    swarm.rendezvous_area = {swarm.rendezvous_area.min.cwiseMin(p), swarm.rendezvous_area.max.cwiseMax(p)};
  swarm.rendezvous_area = swarm.rendezvous_area.expanded(0.5);

  for (std::size_t r = 0; r < robots; ++r) {
    swarm.arrival_times.push_back(static_cast<double>(paths[r].poses.size() - 1) / config.lidar.rate_hz);
    paths[r].poses.resize(steps, paths[r].poses.back());  // parked: standing still, odometry too
    swarm.names.push_back("robot" + std::to_string(r + 1));
    swarm.runs.push_back(record_robot(world, paths[r], config, r, swarm.names.back()));
  }
  return swarm;
}

}  // namespace dsswarm
