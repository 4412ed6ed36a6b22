#pragma once
// `dsswarm replay LOG`: publishes a recorded log (CARMEN or ROS1 bag, through
// read_log) as a live ROS 2 robot would, like `ros2 bag play`: LaserScan on
// <ns>/scan, Odometry on <ns>/odom, odom → base_link on /tf, base_link →
// laser on /tf_static; header stamps are the log's own timestamps, pacing is
// real time × --rate.
//
// `--scenario FILE --agent NAME` plays that agent's stream of a scenario
// instead (its segment, direction and start offset): scan i at
// start_at + clock[i] / rate on the scenario's session clock, so the replays
// of a launch, started with one --start-at, play as `dsswarm swarm` does. A
// backward segment goes out last scan first, with its own (decreasing)
// stamps, each scan's odometry at its stamp.
#include <CLI/CLI.hpp>

#include <optional>
#include <vector>

namespace dsswarm {

// Registers the `replay` subcommand. Problems surface as exceptions
// (InputError, ConfigError) from its callback, for main() to report.
void add_replay_command(CLI::App& app);

// When each record goes out, in seconds after the first one published (nullopt:
// skipped by `start`). The log clock is the running maximum of the stamps in
// file order, so a stamp that runs backwards goes out at once instead of
// stalling the replay; `start` seconds of that clock are skipped; `rate`
// divides the rest.
std::vector<std::optional<double>> replay_schedule(const std::vector<double>& stamps, double rate, double start);

}  // namespace dsswarm
