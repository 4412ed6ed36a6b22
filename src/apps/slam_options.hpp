#pragma once
// Command-line options shared by every command that runs SLAM.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "slam/slam.hpp"
#include "swarm/swarm_config.hpp"

namespace dsswarm {

struct SlamOptions {
  std::string config_file;           // JSON, see `dsswarm config`
  std::optional<std::uint64_t> seed;
  bool no_odometry = false;
  bool filter = false;
  std::optional<int> evaluations;
  std::optional<double> resolution;

  // Defaults, then the config file, then the flags given on the command line.
  SlamConfig resolve() const;
  // The same with the config file's swarm sections (encounter, swarm).
  SwarmConfig resolve_swarm() const;

 private:
  SwarmConfig resolve(SwarmConfig defaults) const;  // the file, then the flags, over `defaults`
};

void add_slam_options(CLI::App& command, SlamOptions& options);

// For unsigned options (seeds): a whole number >= 0. CLI11 alone would wrap
// "-1" around to 18446744073709551615.
CLI::Validator non_negative_integer();

// The three numbers x y theta (metres, metres, radians) of a pose option
// (`--start-pose`, `--laser-offset`). Throws ConfigError naming `option`
// unless they are exactly three finite numbers.
Pose2 pose_option(const std::vector<double>& values, const std::string& option);

}  // namespace dsswarm
