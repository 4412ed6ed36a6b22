#pragma once
// Where the robot should be at the next scan, before matching: the odometry
// increment since the last odometry reading that moved (the anchor), applied
// to our pose at that reading; without usable odometry, constant velocity
// from the last two poses.
#include <optional>

#include "geometry/pose2.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm {

struct MotionConfig {
  // When the odometry prediction and the constant-velocity prediction differ
  // by more than this, the matcher searches from both (odometry glitches).
  double odometry_doubt_xy = 0.2;      // m
  double odometry_doubt_theta = 0.15;  // rad

  void validate() const;  // throws ConfigError naming the field
};

class MotionPredictor {
 public:
  // `use_odometry` false: always constant velocity.
  MotionPredictor(const MotionConfig& config, bool use_odometry) : config_(config), use_odometry_(use_odometry) {}

  Pose2 predict(const LaserScan& scan) const;
  // Does predict(scan) come from fresh odometry (not constant velocity)?
  bool from_odometry(const LaserScan& scan) const;
  // The constant-velocity prediction when it disagrees sharply with the
  // odometry's `prediction` (see MotionConfig::odometry_doubt_xy), else none.
  std::optional<Pose2> doubt(const Pose2& prediction) const;
  // The scan's final pose: moves the anchor (when its odometry is fresh) and
  // the constant-velocity state on.
  void advance(const LaserScan& scan, const Pose2& pose);
  // Puts the robot at `pose` before its first scan, with no motion history;
  // with `odometry` (the reading at `pose`, e.g. from a checkpoint) the first
  // scan is predicted from the odometry increment since then.
  void start_at(const Pose2& pose, const std::optional<Pose2>& odometry = std::nullopt) {
    pose_ = pose;
    anchor_pose_ = pose;
    anchor_odometry_ = odometry;
  }

  const Pose2& pose() const { return pose_; }  // the last scan's pose

 private:
  // A moving robot whose odometry repeats the anchor's reading exactly has a
  // stalled odometry stream, not a robot that stopped dead.
  bool odometry_stale(const LaserScan& scan) const;

  MotionConfig config_;
  bool use_odometry_;
  Pose2 pose_;
  std::optional<Pose2> previous_pose_;  // for the constant-velocity prior
  // Last odometry reading that moved, and our pose at that scan. Increments
  // are taken from this anchor, so odometry that freezes for a few scans and
  // then jumps (real logs do this) still predicts the whole motion.
  std::optional<Pose2> anchor_odometry_;
  Pose2 anchor_pose_;
  bool odometry_moving_ = false;  // did the last fresh odometry increment move?
};

}  // namespace dsswarm
