#include "apps/slam_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

#include "common/errors.hpp"
#include "config/config_json.hpp"

namespace dsswarm {

void add_slam_options(CLI::App& command, SlamOptions& o) {
  // The defaults shown are the configuration's (`dsswarm config`); a --config file overrides them.
  const SlamConfig defaults;
  command.add_option("--config", o.config_file, "Configuration (JSON; `dsswarm config` prints the defaults)")
      ->check(CLI::ExistingFile);
  command.add_option("--seed", o.seed, "Seed of the matcher's random search (same seed, same result)")
      ->check(non_negative_integer())
      ->default_str(std::to_string(defaults.seed));
  command.add_flag("--no-odometry", o.no_odometry, "Ignore odometry (constant-velocity motion prior)");
  command.add_flag("--filter", o.filter, "Drop redundant scans before matching (scan filter; config key filter.enabled)");
  command.add_option("--evaluations", o.evaluations, "Pose evaluations per scan (matcher budget)")
      ->check(CLI::Range(1, 100000))
      ->default_str(std::to_string(defaults.matcher.evaluations));
  command.add_option("--resolution", o.resolution, "Map cell size, metres")
      ->check(CLI::Range(0.005, 2.0))
      ->default_str(fmt::format("{}", defaults.map.resolution));
}

CLI::Validator non_negative_integer() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, ec] = std::from_chars(text.data(), end, value);
        if (ec != std::errc() || stop != end) return "must be a whole number >= 0, got '" + text + "'";
        return {};
      },
      "");
}

SlamConfig SlamOptions::resolve() const {
  SwarmConfig single;
  single.slam = SlamConfig{};  // one robot: run's rounds (the swarm's are shorter, swarm_config.hpp)
  return resolve(std::move(single)).slam;
}

SwarmConfig SlamOptions::resolve_swarm() const { return resolve(SwarmConfig{}); }

SwarmConfig SlamOptions::resolve(SwarmConfig swarm) const {
  if (!config_file.empty()) load_config(config_file, swarm);
  SlamConfig& c = swarm.slam;
  if (seed) c.seed = *seed;
  if (no_odometry) c.use_odometry = false;
  if (filter) c.use_filter = true;
  if (evaluations) c.matcher.evaluations = *evaluations;
  if (resolution) c.map.resolution = *resolution;
  swarm.validate();
  return swarm;
}

Pose2 pose_option(const std::vector<double>& values, const std::string& option) {
  if (values.size() != 3 || !std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); }))
    throw ConfigError(option + ": expected X Y THETA (metres, metres, radians; three finite numbers)");
  return {values[0], values[1], values[2]};
}

}  // namespace dsswarm
