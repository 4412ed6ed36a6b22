#include "apps/sim_swarm_run.hpp"

#include "sim/proximity.hpp"

namespace dsswarm {

SimSwarmRun simulate_swarm_run(const SimSwarmSettings& settings) {
  SwarmSimConfig sim;
  sim.robots = settings.robots;
  sim.seed = settings.seed;
  sim.world = swarm_world_config(settings.robots);
  sim.world.seed = settings.world_seed;
  const SimulatedSwarm swarm = simulate_swarm(sim);
  ProximityConfig proximity;
  proximity.range = settings.range;
  SimSwarmRun run;
  for (std::size_t i = 0; i < swarm.runs.size(); ++i) {
    AgentStream s{swarm.names[i], swarm.runs[i].log.scans, {}};
    for (const LaserScan& scan : s.scans) s.clock.push_back(scan.timestamp);
    run.streams.push_back(std::move(s));
    Trajectory t;
    for (const auto& [time, pose] : swarm.runs[i].ground_truth) t.push_back({time, pose});
    run.truth.world_poses.push_back(std::move(t));
  }
  for (const ProximityEvent& e : proximity_events(swarm.world, swarm, proximity))
    run.events.push_back({e.time, static_cast<std::size_t>(e.a), static_cast<std::size_t>(e.b)});
  return run;
}

}  // namespace dsswarm
