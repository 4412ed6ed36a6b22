#include "apps/slam_options.hpp"

#include <charconv>
#include <cmath>
#include <vector>

#include "common/errors.hpp"
#include "config/config_json.hpp"

namespace dsswarm {

void add_slam_options(CLI::App& command, SlamOptions& o) {
  command.add_option("--config", o.config_file, "Configuration (JSON; `dsswarm config` prints the defaults)")
      ->check(CLI::ExistingFile);
  command.add_option("--seed", o.seed, "Seed of the matcher's random search (same seed, same result)")
      ->check(non_negative_integer());
  command.add_flag("--no-odometry", o.no_odometry, "Ignore odometry (constant-velocity motion prior)");
  command.add_flag("--filter", o.filter, "Drop redundant scans before matching (scan filter; config key filter.enabled)");
  command.add_option("--evaluations", o.evaluations, "Pose evaluations per scan (matcher budget)")
      ->check(CLI::Range(1, 100000));
  command.add_option("--resolution", o.resolution, "Map cell size, metres")->check(CLI::Range(0.005, 2.0));
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

SlamConfig SlamOptions::resolve() const { return resolve_swarm().slam; }

SwarmConfig SlamOptions::resolve_swarm() const {
  SwarmConfig swarm;
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

Pose2 parse_pose_option(const std::string& text, const std::string& option) {
  std::vector<double> values;
  std::size_t start = 0;
  for (bool last = false; !last;) {
    const std::size_t comma = text.find(',', start);
    last = comma == std::string::npos;
    const char* stop = text.data() + (last ? text.size() : comma);
    double v = 0.0;
    const auto [parsed_to, ec] = std::from_chars(text.data() + start, stop, v);
    if (ec != std::errc() || parsed_to != stop || !std::isfinite(v)) {
      values.clear();
      break;
    }
    values.push_back(v);
    start = comma + 1;
  }
  if (values.size() != 3)
    throw ConfigError(option + ": expected x,y,theta (metres, metres, radians; three finite numbers), got '" + text + "'");
  return {values[0], values[1], values[2]};
}

}  // namespace dsswarm
