#include "apps/sim_swarm_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "sim/proximity.hpp"

namespace dsswarm {
namespace {

// The run's first `duration` seconds (robots scan on one clock from 0).
void cut(SimSwarmRun& run, double duration) {
  for (AgentStream& s : run.streams) {
    const auto end = std::upper_bound(s.clock.begin(), s.clock.end(), duration);
    const auto kept = static_cast<std::size_t>(end - s.clock.begin());
    s.clock.resize(kept);
    s.scans.resize(kept);
  }
  for (Trajectory& t : run.truth.world_poses)
    t.erase(std::upper_bound(t.begin(), t.end(), duration,
                             [](double d, const StampedPose& p) { return d < p.timestamp; }),
            t.end());
  std::erase_if(run.events, [&](const EncounterEvent& e) { return e.time > duration; });
}

}  // namespace

SimSwarmRun simulate_swarm_run(const SimSwarmSettings& settings) {
  if (!(std::isfinite(settings.duration) && settings.duration >= 0.0))
    throw ConfigError(fmt::format("--duration {} is not a number of seconds >= 0", settings.duration));
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
  if (settings.duration > 0.0) cut(run, settings.duration);
  return run;
}

}  // namespace dsswarm
