#pragma once
// A reused `--out` folder of `dsswarm swarm` / `demo` must not keep the files
// of robots that are no longer in the run. What dsswarm wrote there before is
// known from the earlier run's stats.json (the agents it names); only those
// files are ever removed, never anything else in the folder.
#include <filesystem>
#include <vector>

#include "io/atomic_file.hpp"

namespace dsswarm {

// The files an earlier run wrote into `dir`: for every agent its stats.json
// names, agents/<name>/{trajectory.tum, map.*, merged_map.*, ground_truth.tum}
// and joint/<name>.tum; and evaluation.json. Empty without a readable
// stats.json naming agents.
std::vector<std::filesystem::path> previous_swarm_outputs(const std::filesystem::path& dir);

// Removes the files of `previous` that `written` does not hold, then the
// agents/<name>, agents and joint folders that this leaves empty.
void remove_stale_outputs(const std::filesystem::path& dir, const std::vector<std::filesystem::path>& previous,
                          const OutputFiles& written);

}  // namespace dsswarm
