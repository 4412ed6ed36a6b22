#pragma once
// A simulated planar lidar: exact ranges from the world's geometry plus
// Gaussian noise, occasional dropped returns, and the "no return" convention
// of real logs (such beams read exactly range_max).
#include <numbers>

#include "common/rng.hpp"
#include "geometry/pose2.hpp"
#include "sensor/laser_scan.hpp"
#include "sim/world.hpp"

namespace dsswarm {

struct LidarConfig {
  int beams = 361;
  double fov = std::numbers::pi;  // rad, centred on the laser's x axis
  double range_max = 30.0;
  double range_min = 0.05;
  double noise_std = 0.01;        // metres, per beam
  double rate_hz = 10;            // scans per second (also the robot's control rate)
  double max_range_dropout = 0.0; // probability a beam returns nothing
};

// Throws ConfigError naming the field.
void validate(const LidarConfig& config);

// Beam i points at angle_min + i * angle_increment with angle_min = -fov/2.
// A full circle (fov = 2 pi) spreads the beams over [-pi, pi) without a
// duplicate beam; otherwise the first and last beams lie on the fov edges.
// Only the ranges (and the beam geometry) are set; timestamp, odometry and
// laser_offset are the caller's.
LaserScan simulate_scan(const World& world, const Pose2& laser_pose_in_world, const LidarConfig& config, Rng& rng);

}  // namespace dsswarm
