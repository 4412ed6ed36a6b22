#pragma once
// Runs a SwarmSession with progress on stderr and writes what `dsswarm swarm`
// and `dsswarm demo` promise (README, "Swarm outputs"):
//   agents/<name>/trajectory.tum       poses in the agent's own map frame, play order
//   agents/<name>/map.{yaml,pgm}       the agent's own map (ROS map_server)
//   agents/<name>/merged_map.{yaml,pgm,png}  own ⊕ everything it received
//   joint/<name>.tum                   every agent the first agent knows, in the first agent's frame
//   encounters.json                    one entry per encounter (and, simulated, its true error)
//   swarm.png                          first agent's merged map, all trajectories, encounters
//   stats.json                         per-agent and per-encounter figures
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/trajectory/tum.hpp"
#include "protocol/swarm_session.hpp"

namespace dsswarm {

// Ground truth of a simulated swarm: per agent, the true world pose at each
// scan timestamp. Enables transform errors, coverage and ATE in the outputs.
struct SwarmTruth {
  std::vector<Trajectory> world_poses;
};

// Plays the session; returns the wall-clock seconds it took.
double run_swarm_session(SwarmSession& session, const std::string& label);

// Writes every output into `dir` (atomically, file by file) and returns stats.json's content.
nlohmann::json write_swarm_outputs(const std::filesystem::path& dir, const SwarmSession& session,
                                   double wall_seconds, const SwarmTruth* truth = nullptr);

}  // namespace dsswarm
