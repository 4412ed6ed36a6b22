#pragma once
#include <CLI/CLI.hpp>

namespace dsswarm {

// `dsswarm launch`: a whole swarm on this machine as separate processes.
void add_launch_command(CLI::App& app);

}  // namespace dsswarm
