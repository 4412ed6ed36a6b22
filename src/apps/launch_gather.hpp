#pragma once
// After `dsswarm launch`: what each robot process left in OUT/agents/<name>/
// (agent_files.hpp, checkpoint.hpp) turned back into one SwarmRunResult, so
// the run is written and evaluated exactly as an in-process run is. Both
// robots' sides of an encounter pair up into the record the in-process swarm
// makes (make_record); an encounter only one side finished (the other died)
// keeps that side's view.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "eval/swarm_run.hpp"

namespace dsswarm {

struct GatheredRun {
  SwarmRunResult run;
  std::vector<nlohmann::json> agent_stats;  // each robot's own stats.json (empty object if it left none)
  std::vector<std::string> problems;        // robots that left no outputs, unpaired encounters...
};

// `event_times`: session time of each encounter id (the schedule's), for the records.
// Throws InputError naming the file when a robot's outputs are unreadable.
GatheredRun gather_launch(const std::filesystem::path& out, const std::vector<std::string>& names,
                          const SwarmConfig& config, const std::map<std::uint64_t, double>& event_times);

}  // namespace dsswarm
