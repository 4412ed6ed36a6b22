#include "slam/slam.hpp"

#include <chrono>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "matching/scan_scorer.hpp"

namespace dsswarm {

void SlamConfig::validate() const {
  filter.validate();
  map.validate();
  matcher.validate();
  if (min_points < 1) throw ConfigError("slam.min_points must be >= 1");
  if (insert_min_travel < 0.0 || insert_min_rotation < 0.0)
    throw ConfigError("slam.insert_min_travel and insert_min_rotation must be >= 0");
  if (!(odometry_doubt_xy > 0.0) || !(odometry_doubt_theta > 0.0))
    throw ConfigError("slam.odometry_doubt_xy and odometry_doubt_theta must be > 0");
  auto unit = [](double v) { return v >= 0.0 && v <= 1.0; };
  if (!unit(verify_min_known) || !unit(verify_min_inliers) || !unit(verify_relative))
    throw ConfigError("slam.verify_min_known, verify_min_inliers and verify_relative must be in [0, 1]");
  if (verify_max_consecutive < 0) throw ConfigError("slam.verify_max_consecutive must be >= 0");
  if (pause_after_still_scans < 0) throw ConfigError("slam.pause_after_still_scans must be >= 0");
}

Slam::Slam(const SlamConfig& config)
    : config_(config),
      map_(config.map),
      matcher_(config.matcher, config.seed),
      recovery_matcher_(recovery_config(config.matcher), config.seed + 1),
      filter_(config.filter) {
  config_.validate();
}

Slam::Slam(const SlamConfig& config, MultiResMap initial, const Pose2& start) : Slam(config) {
  if (initial.config().resolution != config_.map.resolution || initial.levels() != config_.map.levels)
    throw ConfigError("the initial map's resolution/levels (" + std::to_string(initial.config().resolution) + " m, " +
                      std::to_string(initial.levels()) + ") differ from map.resolution/map.levels (" +
                      std::to_string(config_.map.resolution) + " m, " + std::to_string(config_.map.levels) + ")");
  map_ = std::move(initial);
  pose_ = start;
  has_initial_map_ = true;
}

void Slam::replace_working_map(MultiResMap working) {
  if (working.config().resolution != map_.config().resolution || working.levels() != map_.levels())
    throw ConfigError("replace_working_map: the map's resolution/levels differ from this robot's");
  if (!own_map_) own_map_ = std::move(map_);
  map_ = std::move(working);
}

void Slam::insert(const Pose2& pose, const LaserScan& scan, const std::vector<ScanPoint>& points) {
  map_.insert_scan(pose, scan.laser_offset, points);
  if (own_map_) own_map_->insert_scan(pose, scan.laser_offset, points);
  last_insert_pose_ = pose;
  ++inserted_;
}

bool Slam::odometry_stale(const LaserScan& scan) const {
  // A moving robot whose odometry repeats the previous reading exactly has a
  // stalled odometry stream, not a robot that stopped dead.
  return scan.odometry && anchor_odometry_ && odometry_moving_ && scan.odometry->x == anchor_odometry_->x &&
         scan.odometry->y == anchor_odometry_->y && scan.odometry->theta == anchor_odometry_->theta;
}

MatcherConfig Slam::recovery_config(const MatcherConfig& normal) {
  MatcherConfig c = normal;
  c.evaluations = normal.evaluations * 4;
  c.sigma_xy = normal.sigma_xy * 3;
  c.sigma_theta = normal.sigma_theta * 4;
  c.patience = normal.patience * 2;
  return c;
}

Pose2 Slam::predict(const LaserScan& scan) const {
  const bool odometry_usable = config_.use_odometry && scan.odometry && anchor_odometry_ && !odometry_stale(scan);
  if (odometry_usable) {
    // The odometry increment is expressed in the robot frame of the anchor
    // odometry pose, so it applies to our corrected pose whatever the drift
    // between the odometry frame and the map frame.
    return anchor_pose_ * between(*anchor_odometry_, *scan.odometry);
  }
  // No (usable) odometry: constant velocity from the last two poses.
  if (previous_pose_) return pose_ * between(*previous_pose_, pose_);
  return pose_;
}

SlamStep Slam::process(const LaserScan& scan) {
  SlamStep step;
  step.index = processed_;
  const bool first = processed_ == 0;
  // A new map's frame is the odometry frame; a given map keeps its own.
  if (first && !has_initial_map_ && config_.use_odometry && scan.odometry) pose_ = *scan.odometry;
  step.prior = first ? pose_ : predict(scan);
  ++processed_;

  const bool standing_still = note_standing_still(scan) && !first;

  if (config_.use_filter) {
    // Timed here because the filter's cost is part of the price of a scan.
    const auto t0 = std::chrono::steady_clock::now();
    const bool keep = filter_.decide(scan).keep;
    filter_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!keep && !first) {
      // Redundant: the pose follows the motion prediction (odometry from the
      // last matched pose; held when standing still), and nothing enters the map.
      step.pose = standing_still ? pose_ : step.prior;
      step.dropped = true;
      if (config_.revise_dropped) {  // at most filter.max_consecutive_drops long
        if (gap_.empty()) gap_start_ = pose_;
        gap_.push_back({step.index, step.pose});
      }
      advance(scan, step.pose);
      return step;
    }
  }

  if (standing_still) {
    // Parked: hold the pose. Matching the same view over and over only lets
    // the pose random-walk (a constant-velocity prior keeps any creep going;
    // simulated robots waiting at a rendezvous crept 0.25 m and 1.3° in 80 s),
    // and adding evidence would pile up one viewpoint's noise until the map,
    // and then the pose, creep too.
    step.pose = pose_;
    step.still = true;
    ++held_;
    gap_.clear();
    advance(scan, step.pose);
    return step;
  }

  const std::vector<ScanPoint> points = scan_to_points(scan, config_.points);
  const bool enough_points = static_cast<int>(points.size()) >= config_.min_points;
  step.pose = step.prior;
  const bool founding = first && !has_initial_map_;
  if (first && has_initial_map_ && enough_points) {
    // Where in the given map are we? Only `start` is known, roughly: search wide.
    const MatchResult m = recovery_matcher_.match(map_, points, step.prior);
    step.pose = m.pose;
    step.score = m.score;
    step.inlier_ratio = match_quality(map_.finest(), points, m.pose).inlier_ratio;
    step.matched = true;
    ++matched_;
  } else if (!first && enough_points) {
    match_and_verify(points, step);
  }

  if (enough_points && (founding || step.matched)) {
    bool insert = !last_insert_pose_;
    if (last_insert_pose_) {
      const Pose2 d = between(*last_insert_pose_, step.pose);
      insert = std::hypot(d.x, d.y) >= config_.insert_min_travel ||
               std::abs(d.theta) >= config_.insert_min_rotation;
    }
    if (insert) this->insert(step.pose, scan, points);
  }

  // A kept scan ends the gap; only a matched one knows better than the prediction.
  if (step.matched && !gap_.empty()) revise_gap(step);
  gap_.clear();

  advance(scan, step.pose);
  return step;
}

bool Slam::note_standing_still(const LaserScan& scan) {
  if (!config_.use_odometry || !scan.odometry) return false;
  // Unchanged within a micrometre / microradian: odometry integrated in
  // floating point can move by rounding alone (simulated parked robots did).
  constexpr double kSame = 1e-6;
  const bool same = last_odometry_ && std::abs(scan.odometry->x - last_odometry_->x) < kSame &&
                    std::abs(scan.odometry->y - last_odometry_->y) < kSame &&
                    std::abs(normalize_angle(scan.odometry->theta - last_odometry_->theta)) < kSame;
  still_scans_ = same ? still_scans_ + 1 : 0;
  has_moved_ = has_moved_ || (last_odometry_ && !same);
  last_odometry_ = scan.odometry;
  // Not before the robot first moves: a young map needs its first views.
  return has_moved_ && config_.pause_after_still_scans > 0 && still_scans_ >= config_.pause_after_still_scans;
}

void Slam::revise_gap(SlamStep& step) const {
  // Two estimates of each dropped pose, both pinned to the kept poses on
  // either side of the gap: the motion prediction blended from both ends
  // (forward from the pose before the gap, as predicted so far, and back from
  // this match through the same motion, match ⊕ prior⁻¹ ⊕ forward), and plain
  // interpolation between the two kept poses (the robot moves smoothly). The
  // revised pose is their midpoint. Measured on the filter-off trajectories
  // of the three logs (dropping the scans of 1-4 scan gaps after the fact):
  // odometry increments err 1-3.5 degrees per scan, so interpolation wins on
  // short gaps and the prediction on long ones; the midpoint was best or
  // within a millimetre of it everywhere. Fractions go by scan count, not
  // odometry travel: odometry that stalls and then jumps (mit-csail, intel)
  // would bunch the poses.
  const double n = static_cast<double>(gap_.size() + 1);
  step.revised.reserve(gap_.size());
  for (std::size_t i = 0; i < gap_.size(); ++i) {
    const double t = static_cast<double>(i + 1) / n;
    const Pose2& forward = gap_[i].pose;
    const Pose2 backward = step.pose * between(step.prior, forward);
    const Pose2 predicted = interpolate(forward, backward, t);
    const Pose2 interpolated = interpolate(gap_start_, step.pose, t);
    step.revised.push_back({gap_[i].index, interpolate(predicted, interpolated, 0.5)});
  }
}

void Slam::match_and_verify(const std::vector<ScanPoint>& points, SlamStep& step) {
  // Odometry can lag and then jump (intel and mit-csail do both). When it
  // disagrees sharply with a constant-velocity prediction, search from both
  // and keep the better match. Only then: the score cannot reliably tell a
  // small true motion from none (a young map is sparse, and the last scan's
  // own viewpoint always fits it best), so an always-on alternative would
  // pull a moving robot back to where it was.
  std::vector<Pose2> priors{step.prior};
  if (previous_pose_ && config_.use_odometry) {
    const Pose2 constant_velocity = pose_ * between(*previous_pose_, pose_);
    const Pose2 d = between(step.prior, constant_velocity);
    if (std::hypot(d.x, d.y) > config_.odometry_doubt_xy || std::abs(d.theta) > config_.odometry_doubt_theta)
      priors.push_back(constant_velocity);
  }
  MatchResult m = matcher_.match(map_, points, priors);
  MatchQuality q = match_quality(map_.finest(), points, m.pose);
  // A failure shows as a sudden drop of the inlier ratio below what recent
  // matches achieved (an absolute bar would reject whole regions whose map
  // is merely fuzzy, e.g. walls first seen from far away). After a few
  // rejections in a row the map, not the match, is likely what changed:
  // accept again rather than drift on odometry forever.
  const double bar = std::max(config_.verify_min_inliers, config_.verify_relative * inlier_average_);
  auto rejected = [&](const MatchQuality& mq) {
    return consecutive_rejections_ < config_.verify_max_consecutive &&
           mq.known_fraction >= config_.verify_min_known && mq.inlier_ratio < bar;
  };
  if (rejected(q)) {
    // Recovery: a wider search from every prediction we have (odometry,
    // constant velocity, standing still); keep the most consistent answer.
    priors.push_back(pose_);
    const MatchResult wide = recovery_matcher_.match(map_, points, priors);
    const MatchQuality wq = match_quality(map_.finest(), points, wide.pose);
    if (wq.inlier_ratio > q.inlier_ratio) {
      m = wide;
      q = wq;
    }
    ++recoveries_;
  }
  step.score = m.score;
  step.inlier_ratio = q.inlier_ratio;
  // Verify before trusting: a match that puts much of the scan into space
  // the map has seen free is a failure (a wrong local maximum). Keep the
  // prediction instead and keep the scan out of the map, so one bad match
  // cannot corrupt every later one.
  if (rejected(q)) {
    ++rejected_;
    ++consecutive_rejections_;
    return;
  }
  step.pose = m.pose;
  step.matched = true;
  ++matched_;
  consecutive_rejections_ = 0;
  if (q.known_fraction >= config_.verify_min_known)
    inlier_average_ = matched_ <= 1 ? q.inlier_ratio : 0.9 * inlier_average_ + 0.1 * q.inlier_ratio;
}

void Slam::advance(const LaserScan& scan, const Pose2& pose) {
  if (scan.odometry && !odometry_stale(scan)) {
    if (anchor_odometry_) {
      const Pose2 d = between(*anchor_odometry_, *scan.odometry);
      odometry_moving_ = d.x != 0.0 || d.y != 0.0 || d.theta != 0.0;
    }
    anchor_odometry_ = scan.odometry;
    anchor_pose_ = pose;
  }
  previous_pose_ = pose_;
  pose_ = pose;
}

}  // namespace dsswarm
