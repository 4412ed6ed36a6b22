#include "sim/lidar.hpp"

#include <cmath>
#include <string>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

bool is_full_circle(double fov) { return fov >= 2.0 * std::numbers::pi - 1e-9; }

}  // namespace

void validate(const LidarConfig& c) {
  require_config("lidar config", c.beams >= 2 && c.beams <= 100000, "beams must be in [2, 100000]");
  require_config("lidar config", std::isfinite(c.fov) && c.fov > 0 && c.fov <= 2.0 * std::numbers::pi + 1e-9, "fov must be in (0, 2 pi] rad");
  require_config("lidar config", std::isfinite(c.range_min) && c.range_min >= 0, "range_min must be >= 0");
  require_config("lidar config", std::isfinite(c.range_max) && c.range_max > c.range_min, "range_max must be finite and > range_min");
  require_config("lidar config", std::isfinite(c.noise_std) && c.noise_std >= 0, "noise_std must be >= 0");
  require_config("lidar config", std::isfinite(c.rate_hz) && c.rate_hz > 0 && c.rate_hz <= 1000, "rate_hz must be in (0, 1000]");
  require_config("lidar config", c.max_range_dropout >= 0 && c.max_range_dropout <= 1, "max_range_dropout must be in [0, 1]");
}

LaserScan simulate_scan(const World& world, const Pose2& laser_pose, const LidarConfig& config, Rng& rng) {
  validate(config);
  LaserScan scan;
  scan.angle_min = -config.fov / 2.0;
  scan.angle_increment = config.fov / (is_full_circle(config.fov) ? config.beams : config.beams - 1);
  scan.range_min = config.range_min;
  scan.range_max = config.range_max;
  scan.ranges.resize(static_cast<std::size_t>(config.beams));
  const Eigen::Vector2d origin = laser_pose.translation();
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double truth = world.raycast(origin, laser_pose.theta + scan.beam_angle(i), config.range_max);
    // Draw both numbers for every beam, so the noise of one beam does not
    // depend on whether its neighbours hit something.
    const double noise = config.noise_std > 0 ? rng.normal(0.0, config.noise_std) : 0.0;
    const bool dropped = config.max_range_dropout > 0 && rng.uniform() < config.max_range_dropout;
    double range = std::isfinite(truth) ? truth + noise : config.range_max;
    if (dropped || range >= config.range_max) range = config.range_max;
    scan.ranges[i] = static_cast<float>(range);
  }
  return scan;
}

}  // namespace dsswarm
