#pragma once
// A simulated differential-drive robot: it follows a waypoint path through a
// World, scans at every control step, and reports noisy odometry together
// with its exact (ground-truth) pose.
#include <cstdint>
#include <utility>
#include <vector>

#include "common/rng.hpp"
#include "geometry/pose2.hpp"
#include "sensor/laser_scan.hpp"
#include "sim/lidar.hpp"
#include "sim/world.hpp"

namespace dsswarm {

struct RobotConfig {
  double max_speed = 0.6;          // m/s
  double max_turn_rate = 1.0;      // rad/s
  double odom_trans_noise = 0.02;  // std of the translation error, as a fraction of the step's distance
  double odom_rot_noise = 0.02;    // std of the heading error per radian turned
  double odom_drift = 0.005;       // systematic heading error, rad per metre driven
  Pose2 laser_offset{0.1, 0, 0};   // laser pose in the base frame
};

// Throws ConfigError naming the field.
void validate(const RobotConfig& config);

struct SimulatedRun {
  SensorLog log;  // one scan per control step, with odometry
  std::vector<std::pair<double, Pose2>> ground_truth;  // true base pose per scan, same timestamps
};

struct DrivenPath {
  std::vector<Pose2> poses;  // true base pose at each control step, starting with `start`
  bool reached_goal = true;  // false if the step budget ran out first
};
// Drives through every waypoint in order with control steps of `dt` seconds.
// The controller turns in place while the heading error is large and
// otherwise drives and steers; it never overshoots a waypoint.
DrivenPath drive_waypoints(const std::vector<Eigen::Vector2d>& waypoints, const Pose2& start,
                           const RobotConfig& config, double dt);

// Odometry for a true path: each step's motion with noise proportional to it
// plus a systematic heading drift, integrated from the identity pose (the
// odometry frame is where the robot was switched on, not the world frame).
std::vector<Pose2> simulate_odometry(const std::vector<Pose2>& truth, const RobotConfig& config, Rng& rng);

// The whole run: drive, scan at every step (timestamps start_time + k/rate_hz),
// odometry. Noise comes from `seed` only, so equal seeds give identical runs.
SimulatedRun simulate_run(const World& world, const std::vector<Eigen::Vector2d>& waypoints, const Pose2& start,
                          const RobotConfig& robot, const LidarConfig& lidar, std::uint64_t seed,
                          double start_time = 0.0);

// Start pose for a tour: at its first waypoint, facing the second.
Pose2 tour_start_pose(const std::vector<Eigen::Vector2d>& waypoints);

}  // namespace dsswarm
