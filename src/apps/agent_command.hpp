#pragma once
#include <CLI/CLI.hpp>

namespace dsswarm {

// `dsswarm agent`: one robot of the swarm as its own program.
void add_agent_command(CLI::App& app);

}  // namespace dsswarm
