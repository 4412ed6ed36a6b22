#include "slam/slam.hpp"

#include <algorithm>
#include <chrono>

#include "common/errors.hpp"
#include "matching/scan_scorer.hpp"

namespace dsswarm {

void SlamConfig::validate() const {
  filter.validate();
  map.validate();
  matcher.validate();
  motion.validate();
  verify.validate();
  recovery.validate();
  degeneracy.validate();
  stall.validate();
  jump.validate();
  align.validate();
  insert.validate();
  submaps.validate();
  loop_closure.validate();
  if (min_points < 1) throw ConfigError("slam.min_points must be >= 1");
  if (pause_after_still_scans < 0) throw ConfigError("slam.pause_after_still_scans must be >= 0");
}

SubmapConfig SlamConfig::active_submaps() const {
  if (loop_closure.enabled) return submaps;
  SubmapConfig one = submaps;
  one.max_scans = 0;
  one.max_travel = 0.0;
  return one;
}

SlamConfig with_loop_closure(SlamConfig config) {
  config.loop_closure.enabled = true;
  return config;
}

SlamConfig without_loop_closure(SlamConfig config) {
  config.loop_closure.enabled = false;
  return config;
}

namespace {
const SlamConfig& validated(const SlamConfig& config) {
  config.validate();
  return config;
}
}  // namespace

Slam::Slam(const SlamConfig& config, Executor* background)
    : config_(validated(config)),
      filter_(config.filter),
      motion_(config.motion, config.use_odometry),
      standing_still_(config.pause_after_still_scans, config.use_odometry),
      matcher_(config.matcher, config.seed),
      verifier_(config.verify),
      recovery_(config.matcher, config.recovery, config.seed + 1),
      stall_(config.stall),
      jump_(config.jump),
      submaps_(config.map, config.active_submaps(), config.insert),
      closer_(config.loop_closure, config.map, config.points, config.seed + 2, background),
      background_(background) {}

Slam::Slam(const SlamConfig& config, MultiResMap initial, const Pose2& start, MapUse use, Executor* background,
           const std::optional<Pose2>& start_odometry)
    : Slam(config, background) {
  localize_only_ = use == MapUse::localize;
  submaps_.start_with(std::move(initial), !localize_only_);
  if (!localize_only_) closer_.add_fixed_submap();
  motion_.start_at(start, start_odometry);  // the predictor ignores odometry when use_odometry is off
  has_initial_map_ = true;
}

bool Slam::filter_keeps(const LaserScan& scan) {
  const auto t0 = std::chrono::steady_clock::now();
  const bool keep = filter_.decide(scan).keep;
  filter_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return keep;
}

const MultiResMap& Slam::matching_map() const {
  if (working_ && config_.active_submaps().single_map() && !localize_only_) return *working_;
  return submaps_.local_map();
}

SlamStep Slam::process(const LaserScan& scan) {
  submaps_.resume();  // after finish()
  SlamStep step;  // poses in the local frame until finish_step
  step.index = processed_;
  const bool first = processed_ == 0;
  // A new map's frame is the odometry frame; a given map keeps its own.
  if (first && !has_initial_map_ && config_.use_odometry && scan.odometry) motion_.start_at(*scan.odometry);
  // A given map's first scan: the odometry since `start` when it is known.
  step.prior = first && !has_initial_map_ ? motion_.pose() : motion_.predict(scan);
  const bool measured_prior = !first && motion_.from_odometry(scan);
  ++processed_;
  const bool standing_still = standing_still_.update(scan) && !first;

  if (config_.use_filter && !filter_keeps(scan) && !first) {
    // Redundant: the pose follows the motion prediction (held when standing
    // still), and nothing enters the map.
    step.pose = standing_still ? motion_.pose() : step.prior;
    step.dropped = true;
    if (config_.revise_dropped) gaps_.note_dropped(step.index, step.pose, motion_.pose());
    return finish_step(std::move(step), scan, {}, false);
  }
  if (standing_still) {
    step.pose = motion_.pose();
    step.still = true;
    ++held_;
    gaps_.clear();
    return finish_step(std::move(step), scan, {}, false);
  }

  const std::vector<ScanPoint> points = scan_to_points(scan, config_.points);
  const bool enough_points = static_cast<int>(points.size()) >= config_.min_points;
  step.pose = step.prior;
  if (first && !has_initial_map_) {
    // A new map's axes along the first scan's walls (wall_alignment.hpp).
    if (const auto axis = wall_axis(surface_normals(points, config_.degeneracy), config_.align))
      step.pose = step.prior = turned_to_walls(step.prior, *axis);
  }
  if (first && has_initial_map_ && enough_points) {
    locate_in_initial_map(points, step);
  } else if (!first && enough_points) {
    match_and_verify(points, step, measured_prior);
  }
  // A kept scan ends the gap; only a matched one knows better than the prediction.
  if (step.matched && !gaps_.empty()) step.revised = gaps_.revise(step.pose, step.prior);
  gaps_.clear();
  const bool founding = first && !has_initial_map_;
  return finish_step(std::move(step), scan, points, enough_points && (founding || step.matched) && !localize_only_);
}

SlamStep Slam::finish_step(SlamStep step, const LaserScan& scan, const std::vector<ScanPoint>& points, bool insert) {
  const std::optional<int> submap = insert ? submaps_.insert(step.pose, scan, points) : std::nullopt;
  closer_.add_scan(step.index, step.pose, submap, points, submaps_);
  for (const PoseRevision& r : step.revised) closer_.revise_scan(r.index, r.pose);
  motion_.advance(scan, step.pose);
  step.pose = closer_.to_global(step.pose);
  step.prior = closer_.to_global(step.prior);
  for (PoseRevision& r : step.revised) r.pose = closer_.to_global(r.pose);
  if (submap && working_) working_->insert_scan(step.pose, scan.laser_offset, points);
  return step;
}

std::vector<std::pair<const char*, std::size_t>> Slam::scan_counters() const {
  return {{"scans_matched", scans_matched()},       {"scans_held", scans_held()},
          {"scans_stall_held", scans_stall_held()}, {"scans_jump_held", scans_jump_held()},
          {"matches_rejected", matches_rejected()}, {"recovery_searches", recoveries()}};
}

void Slam::finish() {
  if (!localize_only_) submaps_.freeze();
  closer_.finish(submaps_);
}

void Slam::replace_working_map(MultiResMap working) {
  if (working.config().resolution != config_.map.resolution || working.levels() != config_.map.levels)
    throw ConfigError("replace_working_map: the map's resolution/levels differ from this robot's");
  working_ = std::move(working);
}

const MultiResMap& Slam::map() const { return working_ ? *working_ : own_map(); }

const MultiResMap& Slam::own_map() const {
  if (localize_only_) return submaps_.local_map();  // the given map, unchanged
  const std::vector<const Submap*> all = submaps_.all();
  if (all.empty()) return submaps_.current().map;
  // One growing submap where local SLAM put it: that is the map, no copy.
  if (all.size() == 1 && !all.front()->finished && is_identity(closer_.submap_cells_pose(all.front()->id)))
    return all.front()->map;
  const std::pair<std::size_t, std::uint64_t> version{submaps_.scans_inserted(), closer_.version()};
  if (!global_ || global_version_ != version) {
    // Both threads when the background has nothing else to do (at the end of
    // a run): composing many overlapping submaps is the longest step there.
    Executor* helper = closer_.idle() ? background_ : nullptr;
    global_ = combine_submaps(config_.map, all, [this](int id) { return closer_.submap_cells_pose(id); }, helper);
    global_version_ = version;
  }
  return *global_;
}

bool Slam::holds_evidence() const {
  if (working_) return working_->finest().holds_evidence();
  if (localize_only_) return submaps_.local_map().finest().holds_evidence();
  const std::vector<const Submap*> all = submaps_.all();
  return std::any_of(all.begin(), all.end(), [](const Submap* s) {
    return s->finished ? s->frozen.holds_evidence() : s->map.finest().holds_evidence();
  });
}

std::vector<ForeignPiece> Slam::finished_pieces() const {
  std::vector<ForeignPiece> out;
  for (const std::shared_ptr<const Submap>& s : submaps_.finished())
    out.push_back({s->id, closer_.submap_cells_pose(s->id), std::shared_ptr<const FrozenMap>(s, &s->frozen)});
  return out;
}

MultiResMap Slam::unfinished_map() const {
  std::vector<const Submap*> growing;
  for (const Submap* s : submaps_.all())
    if (!s->finished) growing.push_back(s);
  return combine_submaps(config_.map, growing, [this](int id) { return closer_.submap_cells_pose(id); });
}

void Slam::locate_in_initial_map(const std::vector<ScanPoint>& points, SlamStep& step) {
  const MultiResMap& map = matching_map();
  MatchResult m = recovery_.locate(map, points, step.prior);
  MatchQuality q = match_quality(map.finest(), points, m.pose);
  // Odometry that restarted with the robot (back at zero) predicts nonsense:
  // when the match from it fails or lands mostly off the map, the start
  // itself is searched from too, and the match more of whose points land on
  // walls wins. Not both always: the better score would often pick an
  // aliased place (a corridor looks alike all along). Likewise the prior
  // turned to the walls: a map whose axes were turned to its first scan's
  // walls (wall_alignment.hpp) lies turned against the odometry frame.
  const bool doubtful = verifier_.rejects(q) || q.known_fraction < config_.verify.min_known;
  if (doubtful) {
    std::vector<Pose2> others{motion_.pose()};
    if (const auto axis = wall_axis(surface_normals(points, config_.degeneracy), config_.align))
      others.push_back(turned_to_walls(step.prior, *axis));
    for (const Pose2& other : others) {
      if (other == step.prior) continue;
      const MatchResult found = recovery_.locate(map, points, other);
      const MatchQuality fq = match_quality(map.finest(), points, found.pose);
      if (fq.known_fraction * fq.inlier_ratio > q.known_fraction * q.inlier_ratio) {
        m = found;
        q = fq;
      }
    }
  }
  step.pose = m.pose;
  step.score = m.score;
  step.inlier_ratio = q.inlier_ratio;
  step.matched = true;
  ++matched_;
}

void Slam::match_and_verify(const std::vector<ScanPoint>& points, SlamStep& step, bool measured_prior) {
  // Odometry can lag and then jump (intel and mit-csail do both). When it
  // disagrees sharply with a constant-velocity prediction, search from both
  // and keep the better match. Only then: the score cannot reliably tell a
  // small true motion from none (a young map is sparse, and the last scan's
  // own viewpoint always fits it best), so an always-on alternative would
  // pull a moving robot back to where it was.
  std::vector<Pose2> priors{step.prior};
  if (const std::optional<Pose2> constant_velocity = motion_.doubt(step.prior)) priors.push_back(*constant_velocity);
  // Odometry, fresh, and agreeing with constant velocity.
  const bool prior_trusted = measured_prior && priors.size() == 1;
  const MultiResMap& map = matching_map();
  MatchResult m = matcher_.match(map, points, priors);
  MatchQuality q = match_quality(map.finest(), points, m.pose);
  if (verifier_.rejects(q)) {
    // Recovery: a wider search from every prediction we have (odometry,
    // constant velocity, standing still); keep the most consistent answer.
    priors.push_back(motion_.pose());
    const MatchResult wide = recovery_.search(map, points, priors);
    const MatchQuality wq = match_quality(map.finest(), points, wide.pose);
    if (wq.inlier_ratio > q.inlier_ratio) {
      m = wide;
      q = wq;
    }
  }
  step.score = m.score;
  step.inlier_ratio = q.inlier_ratio;
  // Verify before trusting: a match that puts much of the scan into space
  // the map has seen free is a failure (a wrong local maximum). Keep the
  // prediction instead and keep the scan out of the map, so one bad match
  // cannot corrupt every later one.
  if (verifier_.rejects(q)) {
    ++rejected_;
    verifier_.note_rejected();
    return;
  }
  step.pose = m.pose;
  if (prior_trusted) {
    Pose2 raw = m.pose;
    if (jump_.holds_at_prior(step.prior, raw, m.score - m.prior_score)) {
      raw = step.prior;
      step.score = m.prior_score;
    }
    step.pose = raw;
    if (const std::optional<Eigen::Vector2d> weak = weak_direction(points, config_.degeneracy))
      step.pose = hold_along(step.prior, raw, *weak);
    // A given map (--load-map) is not young: only a map of our own first scans needs the guard.
    if (!has_initial_map_) step.pose = stall_.check(motion_.pose(), step.prior, raw, step.pose);
  } else {
    stall_.reset();
    jump_.reset();
  }
  step.matched = true;
  ++matched_;
  verifier_.note_accepted(q, matched_ <= 1);
}

}  // namespace dsswarm
