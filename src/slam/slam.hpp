#pragma once
// Single-robot SLAM pipeline: feed scans (with odometry when the robot has
// it), get a pose per scan; the map is readable at any time.
//
//   local SLAM, per scan, in its own local frame:
//     scan ─► filter ─► standing still? ─► points ─► prior (motion predictor)
//          ─► Monte-Carlo matcher against the local map (previous ⊕ current
//             submap) ─► match verifier (recovery search when it fails)
//          ─► degeneracy (hold the prediction along what the scan leaves
//             free) ─► pose ─► insert into the current submap
//   global SLAM, in background rounds (loop_closer.hpp):
//     new nodes ─► loop-closure search in finished submaps nearby ─► verify
//          ─► pose graph (Ceres) ─► global poses; the global map is the
//             Dempster combination of the submaps at their optimized poses
//
// The pipeline owns one small module per job (motion_predictor,
// standing_still, match_verifier, degeneracy, recovery, gap_reviser,
// submaps, loop_closer). No I/O happens here: readers and writers live in src/io,
// threads in src/runtime.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "filter/scan_filter.hpp"
#include "geometry/pose2.hpp"
#include "grid/multires_map.hpp"
#include "matching/monte_carlo_matcher.hpp"
#include "sensor/laser_scan.hpp"
#include "sensor/scan_points.hpp"
#include "slam/degeneracy.hpp"
#include "slam/executor.hpp"
#include "slam/gap_reviser.hpp"
#include "slam/loop_closer.hpp"
#include "slam/match_verifier.hpp"
#include "slam/motion_predictor.hpp"
#include "slam/recovery.hpp"
#include "slam/jump_guard.hpp"
#include "slam/stall_guard.hpp"
#include "slam/wall_alignment.hpp"
#include "slam/standing_still.hpp"
#include "slam/submaps.hpp"

namespace dsswarm {

struct SlamConfig {
  // Scan filter in front of the matcher (off by default; `run --filter`).
  bool use_filter = false;
  ScanFilterConfig filter;
  // A dropped scan's pose is at first the motion prediction from the last
  // matched pose (odometry, or constant velocity). true: once the next scan
  // is matched, the dropped poses of the gap are revised (SlamStep::revised),
  // blending the forward prediction with the one back from that match, so the
  // correction the match found is spread over the gap instead of landing at
  // its end. The online pose and the map are the same either way.
  bool revise_dropped = true;
  MapConfig map;
  MatcherConfig matcher;
  PointWeightConfig points;
  bool use_odometry = true;    // false: constant-velocity prior from the last two poses
  std::uint64_t seed = 1;      // the matcher's random source: same seed, same result
  int min_points = 20;         // scans with fewer valid points are not matched (pose = prior)
  MotionConfig motion;
  VerifyConfig verify;
  // The wider search for a match that fails verification (recovery.hpp).
  RecoveryConfig recovery;
  // Where a scan leaves a direction unconstrained (a corridor with its end
  // out of range), the pose along it follows the prediction (degeneracy.hpp).
  DegeneracyConfig degeneracy;
  // Where the matches stall while odometry drives on, the position along the
  // motion follows the odometry (stall_guard.hpp).
  StallConfig stall;
  // A match that leaps from a trusted prediction for little gain is held at
  // the prediction (jump_guard.hpp).
  JumpConfig jump;
  // A new map's axes run along its first scan's walls (wall_alignment.hpp).
  WallAlignConfig align;
  // A robot whose odometry has not changed for this many scans (after it
  // first moved) is standing still (see standing_still.hpp). Needs use_odometry.
  int pause_after_still_scans = 20;  // 0: never pause
  InsertConfig insert;
  // Submaps are what loop closure works on, so they are used only with it
  // (loop_closure.enabled, on by default): without it one map, which local
  // SLAM matches better against on revisits (figures in docs/loop_closure.md).
  SubmapConfig submaps{.max_scans = 150, .max_travel = 15.0};
  LoopClosureConfig loop_closure;

  // `submaps` with loop closure on; one map (no submaps) without it.
  SubmapConfig active_submaps() const;
  void validate() const;
};

struct SlamStep {
  std::size_t index = 0;  // this scan's position in process() order, from 0
  Pose2 pose;            // estimated robot base pose in the map frame
  Pose2 prior;           // prediction before matching
  bool matched = false;  // false: too few points, match rejected, dropped (pose = prior) or still
  bool dropped = false;  // the scan filter judged it redundant: not matched, not inserted
  bool still = false;    // standing still (pause_after_still_scans): pose held, not matched, not inserted
  double score = 0.0;    // matcher score on the finest level
  double inlier_ratio = 0.0;  // verification measure of the match (see match_quality)
  // Matched after dropped scans (SlamConfig::revise_dropped): their revised
  // poses, oldest first. Callers keeping a trajectory overwrite those entries.
  std::vector<PoseRevision> revised;
};

// `config` with loop closure on (submaps, loop-closure rounds, pose graph),
// or off (one map).
SlamConfig with_loop_closure(SlamConfig config = {});
SlamConfig without_loop_closure(SlamConfig config = {});

// What a given map is for.
enum class MapUse {
  extend,    // keep mapping in it (new evidence in new submaps)
  localize,  // localize in it; it never changes
};

class Slam {
 public:
  // `background` runs loop closing (not owned; nullptr: on the calling
  // thread), and half of composing the global map when loop closing is idle.
  explicit Slam(const SlamConfig& config = {}, Executor* background = nullptr);
  // Starts in `initial` (a saved map, or evidence received from other
  // robots): the first scan is matched against it from `start` (a wide
  // search) instead of founding the map. Extending it, `initial` counts as
  // own evidence and stays fixed as the first submap. `start_odometry`: the
  // odometry reading at `start` (a resumed robot); the first scan's search
  // then starts from where the odometry says the robot went since, as well.
  Slam(const SlamConfig& config, MultiResMap initial, const Pose2& start, MapUse use = MapUse::extend,
       Executor* background = nullptr, const std::optional<Pose2>& start_odometry = std::nullopt);

  SlamStep process(const LaserScan& scan);
  // Waits for background work and runs a last loop-closing round, so that
  // trajectory() and map() reflect every scan. Processing may go on after.
  void finish();

  // The map the robot localizes in, in the global frame: its own evidence
  // (the submaps at their optimized poses) or, once the swarm installed one,
  // own ⊕ foreign (see replace_working_map).
  const MultiResMap& map() const;
  // Only the evidence of this robot's own scans: what it shares with others,
  // so that nothing received from a third robot is ever passed on as its own.
  const MultiResMap& own_map() const;
  // Whether map() would hold any evidence, found without composing it.
  bool holds_evidence() const;
  // Installs a richer map (own evidence ⊕ foreign evidence, built by the
  // swarm layer from own_map()) as map(); from then on every insertion goes
  // into it too (Dempster's rule is associative and commutative, so it stays
  // own ⊕ foreign). With one map (submaps.max_scans = max_travel = 0) the
  // robot also localizes in it, as before submaps; with submaps it localizes
  // in its own recent submaps.
  void replace_working_map(MultiResMap working);
  // How many scans this robot has put into its own map (a snapshot's version).
  std::size_t scans_inserted() const { return submaps_.scans_inserted(); }
  // The robot's pose now, in the global frame.
  Pose2 pose() const { return closer_.to_global(motion_.pose()); }
  // Every scan's pose in process() order: optimized (global frame), and as
  // local SLAM estimated it (its local frame, before any loop closure).
  std::vector<Pose2> trajectory() const { return closer_.trajectory(); }
  std::vector<Pose2> local_trajectory() const { return closer_.local_trajectory(); }
  const Submaps& submaps() const { return submaps_; }
  // Localizing in a given map that never changes (MapUse::localize).
  bool localizing_only() const { return localize_only_; }
  // This robot's finished submaps as another robot holds them: each one's
  // evidence (shared, not copied) where its cells lie in our global frame.
  std::vector<ForeignPiece> finished_pieces() const;
  // The evidence of the submaps not finished yet, at their global poses:
  // with finished_pieces(), all of own_map().
  MultiResMap unfinished_map() const;

  // Other robots' maps in this robot's pose graph (with loop closure on;
  // slam/foreign_maps.hpp). `frame` is the caller's id for the other robot.
  void set_foreign_map(int frame, const Pose2& frame_pose, const std::vector<ForeignPiece>& pieces) {
    closer_.set_foreign_map(frame, frame_pose, pieces);
  }
  // An encounter: at our scan `index` (process() order; its global pose then
  // `scan_pose`) the other robot's frame was seen at `frame_pose`.
  // `encounter` names it, for when the other robot says its scan moved
  // (LoopCloser::move_encounter).
  void add_encounter(int frame, std::size_t index, const Pose2& scan_pose, const Pose2& frame_pose,
                     std::uint64_t encounter = 0) {
    closer_.add_encounter(frame, index, scan_pose, frame_pose, encounter);
  }
  bool move_encounter(int frame, std::uint64_t encounter, const Pose2& then, const Pose2& now) {
    return closer_.move_encounter(frame, encounter, then, now);
  }
  // That robot's own closures into our submaps (LoopCloser::set_peer_closures).
  void set_peer_closures(int frame, std::vector<PeerClosure> closures) {
    closer_.set_peer_closures(frame, std::move(closures));
  }
  // Scan `index`'s best global pose now (process() order), and a number that
  // grows whenever loop closing moves the trajectory and submaps.
  Pose2 scan_pose(std::size_t index) const { return closer_.scan_pose(index); }
  std::uint64_t graph_revision() const { return closer_.version(); }
  // Where the other robot's frame lies in ours now (as optimized); nullopt if unknown.
  std::optional<Pose2> foreign_frame(int frame) const { return closer_.frame_pose(frame); }
  const LoopCloser& loop_closer() const { return closer_; }
  std::size_t scans_processed() const { return processed_; }
  std::size_t scans_matched() const { return matched_; }
  std::size_t matches_rejected() const { return rejected_; }
  std::size_t recoveries() const { return recovery_.searches(); }
  std::size_t scans_dropped() const { return filter_.dropped(); }
  std::size_t scans_held() const { return held_; }  // standing still (SlamStep::still)
  // Matches whose position along the motion the stall guard put back to the odometry's.
  std::size_t scans_stall_held() const { return stall_.holds(); }
  // Matches the jump guard held at the prediction.
  std::size_t scans_jump_held() const { return jump_.holds(); }
  double filter_seconds() const { return filter_seconds_; }
  // The per-scan counters above, named as the outputs' stats.json report them:
  // one list, so a new counter reaches `run`'s, the swarm's and the agent's stats.
  std::vector<std::pair<const char*, std::size_t>> scan_counters() const;
  const SlamConfig& config() const { return config_; }

 private:
  // Whether the scan filter keeps the scan (timed: its cost is part of a scan's price).
  bool filter_keeps(const LaserScan& scan);
  // Matches `points` from step.prior (and alternatives), verifies the match
  // (with a recovery search when it fails) and fills step.pose / matched /
  // score; a rejected match leaves the prior. Poses in the local frame.
  // `measured_prior`: the prior is fresh odometry, which may be held along
  // what the scan leaves free (degeneracy.hpp); an extrapolation may not.
  void match_and_verify(const std::vector<ScanPoint>& points, SlamStep& step, bool measured_prior);
  // The first scan in a given map: where in it are we? Only the start is known, roughly.
  void locate_in_initial_map(const std::vector<ScanPoint>& points, SlamStep& step);
  const MultiResMap& matching_map() const;
  // Records the scan (local poses in `step`), inserts it, and turns the step's poses global.
  SlamStep finish_step(SlamStep step, const LaserScan& scan, const std::vector<ScanPoint>& points, bool insert);

  SlamConfig config_;
  ScanFilter filter_;
  MotionPredictor motion_;
  StandingStill standing_still_;
  MonteCarloMatcher matcher_;
  MatchVerifier verifier_;
  Recovery recovery_;
  StallGuard stall_;
  JumpGuard jump_;
  GapReviser gaps_;
  Submaps submaps_;
  LoopCloser closer_;
  Executor* background_;                // not owned; may be null
  std::optional<MultiResMap> working_;  // own ⊕ foreign, once the swarm installed it
  bool has_initial_map_ = false;        // first scan is matched, not founding
  bool localize_only_ = false;
  double filter_seconds_ = 0.0;
  std::size_t processed_ = 0;
  std::size_t matched_ = 0;
  std::size_t rejected_ = 0;
  std::size_t held_ = 0;
  // own_map() composed on demand, and what it was composed from.
  mutable std::optional<MultiResMap> global_;
  mutable std::pair<std::size_t, std::uint64_t> global_version_{0, 0};
};

}  // namespace dsswarm
