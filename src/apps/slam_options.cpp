#include "apps/slam_options.hpp"

#include "config/slam_config_json.hpp"

namespace dsswarm {

void add_slam_options(CLI::App& command, SlamOptions& o) {
  command.add_option("--config", o.config_file, "SLAM configuration (JSON; `dsswarm config` prints the defaults)")
      ->check(CLI::ExistingFile);
  command.add_option("--seed", o.seed, "Seed of the matcher's random search (same seed, same result)");
  command.add_flag("--no-odometry", o.no_odometry, "Ignore odometry (constant-velocity motion prior)");
  command.add_flag("--filter", o.filter, "Drop redundant scans before matching (scan filter; config key filter.enabled)");
  command.add_option("--evaluations", o.evaluations, "Pose evaluations per scan (matcher budget)")
      ->check(CLI::Range(1, 100000));
  command.add_option("--resolution", o.resolution, "Map cell size, metres")->check(CLI::Range(0.005, 2.0));
}

SlamConfig SlamOptions::resolve() const {
  SlamConfig c;
  if (!config_file.empty()) load_slam_config(config_file, c);
  if (seed) c.seed = *seed;
  if (no_odometry) c.use_odometry = false;
  if (filter) c.use_filter = true;
  if (evaluations) c.matcher.evaluations = *evaluations;
  if (resolution) c.map.resolution = *resolution;
  c.validate();
  return c;
}

}  // namespace dsswarm
