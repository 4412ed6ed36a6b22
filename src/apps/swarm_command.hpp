#pragma once
#include <CLI/CLI.hpp>

#include <filesystem>
#include <vector>

#include "eval/relations.hpp"

namespace dsswarm {

// `dsswarm demo`: a simulated swarm in a generated building, scored against ground truth.
void add_swarm_demo_command(CLI::App& app);
// `dsswarm swarm SCENARIO.yaml --out DIR`: several robots from recorded logs.
void add_swarm_command(CLI::App& app);

// Scores a swarm output folder against relations (as `eval swarm`), writes
// evaluation.json there and prints the table.
void evaluate_scenario_run(const std::filesystem::path& out, const std::vector<Relation>& relations);

}  // namespace dsswarm
