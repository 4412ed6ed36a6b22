#pragma once
// Console lines of `dsswarm swarm` and `dsswarm demo` that need more than one
// format call.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/swarm_run.hpp"

namespace dsswarm {

// What became of the encounter events a session was given, e.g.
// "3 scripted encounters: 2 run, 1 skipped (robot2 had not started)".
// `what` names the events ("scripted encounters", "proximity events");
// `skipped` holds why each event that did not run was skipped (SwarmSession::skipped).
std::string describe_encounter_events(const std::string& what, std::size_t events, std::size_t run,
                                      const std::vector<std::string>& skipped);

// What a simulated run's stats.json says of the robots and the merges: one
// line per robot (ATE, coverage, peers known), then the worst accepted error
// and the wrong merges, or that nothing was merged.
std::string describe_simulated_outcome(const nlohmann::json& stats);

// A launch's robot processes, one line each: scans processed / skipped, CPU
// seconds, the largest gap between two scans during an encounter, and the
// proximity-event-to-merged-map latency; then the latency over all robots.
std::string describe_robot_processes(const SwarmRunResult& run, const std::vector<nlohmann::json>& agent_stats);

}  // namespace dsswarm
