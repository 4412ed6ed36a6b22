#pragma once
#include <CLI/CLI.hpp>

#include <cstddef>

namespace dsswarm {

// `dsswarm launch`: a whole swarm on this machine as separate processes.
void add_launch_command(CLI::App& app);

// Seconds the robot processes get before clock 0: at least `requested`, and
// with --sim enough for each of them to simulate the whole swarm first (it
// took this launch `simulate_seconds`), `processes` of them sharing `cores`,
// with a margin for a machine busy with other work. A process that comes up
// after clock 0 never sees its first scans: its map starts from odometry that
// drifted meanwhile, and its transforms to the others' maps are off by that.
double launch_startup_seconds(double requested, double simulate_seconds, std::size_t processes, unsigned cores);

}  // namespace dsswarm
