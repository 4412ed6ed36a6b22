#pragma once
// Runs a SwarmSession with progress on stderr and writes what `dsswarm swarm`,
// `dsswarm demo` and `dsswarm launch` promise (README, "Swarm outputs"):
//   agents/<name>/trajectory.tum       poses in the agent's own map frame, play order
//   agents/<name>/map.{yaml,pgm}       the agent's own map (ROS map_server)
//   agents/<name>/merged_map.{yaml,pgm,png}  own ⊕ everything it received
//   joint/<name>.tum                   every agent the first agent knows, in the first agent's frame
//   encounters.json                    one entry per encounter (and, simulated, its true error)
//   swarm.png                          first agent's merged map, all trajectories, encounters
//   stats.json                         per-agent and per-encounter figures
// A reused folder keeps no files of agents the earlier run had and this one
// has not (stale_outputs.hpp); files dsswarm did not write stay.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/swarm_run.hpp"
#include "protocol/swarm_session.hpp"

namespace dsswarm {

// Plays the session; returns the wall-clock seconds it took.
double run_swarm_session(SwarmSession& session, const std::string& label);

// The session's results (maps shared, not copied: valid while it lives).
SwarmRunResult run_result(const SwarmSession& session);

struct SwarmOutputOptions {
  double wall_seconds = 0.0;
  const SwarmTruth* truth = nullptr;  // simulated runs: ATE, coverage, transform errors
  // false: the agents wrote agents/<name>/ themselves (robot processes); only
  // ground_truth.tum is added there.
  bool agent_files = true;
};

// Writes every output into `dir` (all of them or, on an error, none) and returns stats.json's content.
nlohmann::json write_swarm_outputs(const std::filesystem::path& dir, const SwarmRunResult& run,
                                   const SwarmOutputOptions& options);

}  // namespace dsswarm
