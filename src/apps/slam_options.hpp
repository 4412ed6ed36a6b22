#pragma once
// Command-line options shared by every command that runs SLAM.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

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
};

void add_slam_options(CLI::App& command, SlamOptions& options);

// "x,y,theta" (metres, metres, radians) as given to `--start-pose`. Throws
// ConfigError naming `option` unless it is exactly three finite numbers.
Pose2 parse_pose_option(const std::string& text, const std::string& option);

}  // namespace dsswarm
