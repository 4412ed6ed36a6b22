#pragma once
// The built-in simulated swarm (the demo's data): N robots in a generated
// building, their scans on one clock, the proximity sensor's encounter events
// and the ground truth. The demo plays it in one process; `agent --sim` plays
// one robot of it, and `launch --sim` all of them, as separate processes.
#include <cstdint>
#include <vector>

#include "apps/swarm_runner.hpp"
#include "protocol/swarm_session.hpp"
#include "sim/swarm_sim.hpp"

namespace dsswarm {

struct SimSwarmSettings {
  int robots = 3;
  std::uint64_t seed = 1;        // starts, routes, sensor noise
  std::uint64_t world_seed = 1;  // the building
  double range = 3.0;            // proximity sensor range, m
};

struct SimSwarmRun {
  std::vector<AgentStream> streams;   // per robot, clock = scan time
  std::vector<EncounterEvent> events; // the proximity sensor's events
  SwarmTruth truth;
};

// Deterministic from the settings. Throws ConfigError naming the setting.
SimSwarmRun simulate_swarm_run(const SimSwarmSettings& settings);

}  // namespace dsswarm
