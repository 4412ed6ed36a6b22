#pragma once
#include <CLI/CLI.hpp>

namespace dsswarm {
// `dsswarm run LOG --out DIR`: single-robot SLAM on a recorded log.
void add_run_command(CLI::App& app);
// `dsswarm config`: print the default configuration as JSON.
void add_config_command(CLI::App& app);
}  // namespace dsswarm
