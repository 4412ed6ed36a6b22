#include "sim/robot.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

// Controller: turn in place above the first heading error and keep turning
// until below the second; a waypoint counts as reached within kArrived.
constexpr double kStartTurnInPlace = 0.35;  // rad
constexpr double kStopTurnInPlace = 0.02;   // rad
constexpr double kArrived = 0.03;           // m

// Exact motion along the arc of constant speed v and turn rate w for dt.
Pose2 integrate_arc(const Pose2& pose, double v, double w, double dt) {
  const double dtheta = w * dt;
  if (std::abs(dtheta) < 1e-9) return pose * Pose2(v * dt, 0.0, dtheta);
  const double radius = v / w;
  return pose * Pose2(radius * std::sin(dtheta), radius * (1.0 - std::cos(dtheta)), dtheta);
}

}  // namespace

void validate(const RobotConfig& c) {
  require_config("robot config", std::isfinite(c.max_speed) && c.max_speed > 0 && c.max_speed <= 20, "max_speed must be in (0, 20] m/s");
  require_config("robot config", std::isfinite(c.max_turn_rate) && c.max_turn_rate > 0 && c.max_turn_rate <= 20,
          "max_turn_rate must be in (0, 20] rad/s");
  require_config("robot config", std::isfinite(c.odom_trans_noise) && c.odom_trans_noise >= 0 && c.odom_trans_noise <= 1,
          "odom_trans_noise must be in [0, 1]");
  require_config("robot config", std::isfinite(c.odom_rot_noise) && c.odom_rot_noise >= 0 && c.odom_rot_noise <= 1,
          "odom_rot_noise must be in [0, 1]");
  require_config("robot config", std::isfinite(c.odom_drift) && std::abs(c.odom_drift) <= 1, "odom_drift must be in [-1, 1] rad/m");
  require_config("robot config", std::isfinite(c.laser_offset.x) && std::isfinite(c.laser_offset.y) && std::isfinite(c.laser_offset.theta),
          "laser_offset must be finite");
}

DrivenPath drive_waypoints(const std::vector<Eigen::Vector2d>& waypoints, const Pose2& start,
                           const RobotConfig& config, double dt) {
  validate(config);
  require_config("robot config", std::isfinite(dt) && dt > 0, "control step must be a positive number of seconds");
  // Step budget (against endless circling): three times the straight-line
  // driving time plus a full turn per waypoint.
  double length = 0.0;
  Eigen::Vector2d previous = start.translation();
  for (const Eigen::Vector2d& w : waypoints) {
    length += (w - previous).norm();
    previous = w;
  }
  const double budget_s = 3.0 * length / config.max_speed +
                          2.0 * std::numbers::pi * static_cast<double>(waypoints.size() + 1) / config.max_turn_rate +
                          10.0;
  const auto max_steps = static_cast<std::size_t>(std::ceil(budget_s / dt));

  DrivenPath path;
  Pose2 pose = start;
  path.poses.push_back(pose);
  std::size_t next = 0;
  bool turning_in_place = false;
  for (;;) {
    while (next < waypoints.size() && (waypoints[next] - pose.translation()).norm() < kArrived) ++next;
    if (next == waypoints.size()) break;
    if (path.poses.size() > max_steps) {
      path.reached_goal = false;
      break;
    }
    const Eigen::Vector2d to_target = waypoints[next] - pose.translation();
    const double distance = to_target.norm();
    const double error = normalize_angle(std::atan2(to_target.y(), to_target.x()) - pose.theta);
    if (std::abs(error) > kStartTurnInPlace) turning_in_place = true;
    if (std::abs(error) < kStopTurnInPlace) turning_in_place = false;

    double v = 0.0, w = 0.0;
    if (turning_in_place) {
      w = std::clamp(error / dt, -config.max_turn_rate, config.max_turn_rate);
    } else {
      // Halve the heading error per step; never drive past the waypoint.
      w = std::clamp(error / (2.0 * dt), -config.max_turn_rate, config.max_turn_rate);
      v = std::min(config.max_speed, distance / dt) * std::cos(error);
    }
    pose = integrate_arc(pose, v, w, dt);
    path.poses.push_back(pose);
  }
  return path;
}

std::vector<Pose2> simulate_odometry(const std::vector<Pose2>& truth, const RobotConfig& config, Rng& rng) {
  validate(config);
  std::vector<Pose2> odometry;
  odometry.reserve(truth.size());
  if (truth.empty()) return odometry;
  Pose2 odom;  // identity: the odometry frame starts where the robot starts
  odometry.push_back(odom);
  for (std::size_t k = 1; k < truth.size(); ++k) {
    const Pose2 step = between(truth[k - 1], truth[k]);
    const double distance = std::hypot(step.x, step.y);
    // Both draws always happen, so the stream does not depend on the motion.
    const double scale = 1.0 + rng.normal(0.0, config.odom_trans_noise);
    const double rot_noise = rng.normal(0.0, config.odom_rot_noise) * std::abs(step.theta);
    const double rot_error = rot_noise + config.odom_drift * distance;
    odom = odom * Pose2(step.x * scale, step.y * scale, step.theta + rot_error);
    odometry.push_back(odom);
  }
  return odometry;
}

SimulatedRun simulate_run(const World& world, const std::vector<Eigen::Vector2d>& waypoints, const Pose2& start,
                          const RobotConfig& robot, const LidarConfig& lidar, std::uint64_t seed, double start_time) {
  validate(robot);
  validate(lidar);
  require_config("robot config", std::isfinite(start_time), "start_time must be finite");
  const DrivenPath path = drive_waypoints(waypoints, start, robot, 1.0 / lidar.rate_hz);
  Rng odometry_rng(stream_seed(seed, 1));
  Rng lidar_rng(stream_seed(seed, 2));
  const std::vector<Pose2> odometry = simulate_odometry(path.poses, robot, odometry_rng);

  SimulatedRun run;
  run.log.source = "simulation (seed " + std::to_string(seed) + ")";
  if (!path.reached_goal)
    run.log.warnings.push_back("simulated robot ran out of time before its last waypoint; run cut short after " +
                               std::to_string(path.poses.size()) + " steps");
  run.log.scans.reserve(path.poses.size());
  run.ground_truth.reserve(path.poses.size());
  for (std::size_t k = 0; k < path.poses.size(); ++k) {
    LaserScan scan = simulate_scan(world, path.poses[k] * robot.laser_offset, lidar, lidar_rng);
    scan.timestamp = start_time + static_cast<double>(k) / lidar.rate_hz;
    scan.odometry = odometry[k];
    scan.laser_offset = robot.laser_offset;
    run.ground_truth.emplace_back(scan.timestamp, path.poses[k]);
    run.log.scans.push_back(std::move(scan));
  }
  return run;
}

Pose2 tour_start_pose(const std::vector<Eigen::Vector2d>& waypoints) {
  if (waypoints.empty()) return {};
  const Eigen::Vector2d& p = waypoints.front();
  if (waypoints.size() < 2) return {p.x(), p.y(), 0.0};
  const Eigen::Vector2d d = waypoints[1] - p;
  return {p.x(), p.y(), std::atan2(d.y(), d.x())};
}

}  // namespace dsswarm
