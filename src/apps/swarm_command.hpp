#pragma once
#include <CLI/CLI.hpp>

namespace dsswarm {

// `dsswarm demo`: a simulated swarm in a generated building, scored against ground truth.
void add_swarm_demo_command(CLI::App& app);
// `dsswarm swarm SCENARIO.yaml --out DIR`: several robots from recorded logs.
void add_swarm_command(CLI::App& app);

}  // namespace dsswarm
