#pragma once
// What a robot process leaves in its --out folder when it stops (the same
// per-robot files `dsswarm swarm` writes under agents/<name>/, so `launch`
// can gather them into a swarm output folder):
//   trajectory.tum                its poses, own map frame, every scan
//   map.{yaml,pgm}                its own map (ROS map_server)
//   merged_map.{yaml,pgm,png}     own ⊕ everything received
//   encounters.json               its side of every encounter (outcome_json.hpp)
//   stats.json                    scans, skips, CPU, gaps, latencies, rejections, what it knows
// plus checkpoint.{dsmap,json} (checkpoint.hpp).
#include <filesystem>

#include "agent/agent_runtime.hpp"

namespace dsswarm::agent {

void write_agent_files(const std::filesystem::path& dir, const SwarmAgent& agent, const Trajectory& trajectory,
                       const AgentReport& report, const SwarmConfig& config);

// stats.json's content.
nlohmann::json agent_stats(const SwarmAgent& agent, const Trajectory& trajectory, const AgentReport& report,
                           const SwarmConfig& config);

}  // namespace dsswarm::agent
