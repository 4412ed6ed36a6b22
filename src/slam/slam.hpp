#pragma once
// Single-robot SLAM pipeline: feed scans (with odometry when the robot has
// it), get a pose per scan; the map is readable at any time.
//
//   scan ─► points ─► prior (last pose ⊕ odometry increment) ─► Monte-Carlo
//   matcher against the map ─► pose ─► insert scan into the map
//
// No I/O happens here: readers and writers live in src/io.
#include <cstdint>
#include <optional>

#include "filter/scan_filter.hpp"
#include "geometry/pose2.hpp"
#include "grid/multires_map.hpp"
#include "matching/monte_carlo_matcher.hpp"
#include "sensor/laser_scan.hpp"
#include "sensor/scan_points.hpp"

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
  // Insert a matched scan into the map only when the robot has moved this much
  // since the last insertion: a robot standing still would otherwise pile
  // evidence from one viewpoint, making its noise look certain.
  // When the odometry prediction and the constant-velocity prediction differ
  // by more than this, the matcher searches from both (odometry glitches).
  double odometry_doubt_xy = 0.2;       // m
  double odometry_doubt_theta = 0.15;   // rad
  // Match verification (see match_quality): a match is rejected when at least
  // `verify_min_known` of its points land on known cells and its inlier ratio
  // is below max(verify_min_inliers, verify_relative × the running average of
  // accepted matches); never more than `verify_max_consecutive` in a row.
  double verify_min_known = 0.3;
  double verify_min_inliers = 0.3;
  double verify_relative = 0.75;
  int verify_max_consecutive = 10;
  // A robot whose odometry has not changed for this many scans (after it
  // first moved) is standing still: its pose is held and its scans are
  // neither matched nor inserted until the odometry changes again (see
  // process). Odometry that stalls while the robot moves (real logs do)
  // freezes for fewer scans. Needs use_odometry.
  int pause_after_still_scans = 20;     // 0: never pause
  double insert_min_travel = 0.0;       // m
  double insert_min_rotation = 0.0;     // rad

  void validate() const;
};

// A better pose for an earlier scan, found after the fact.
struct PoseRevision {
  std::size_t index = 0;  // the scan's position in process() order, from 0
  Pose2 pose;
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

class Slam {
 public:
  explicit Slam(const SlamConfig& config = {});
  // Continues mapping in `initial` (a saved map, or evidence received from
  // other robots): the first scan is matched against it from `start` (a wide
  // search) instead of founding the map. `initial` counts as own evidence.
  Slam(const SlamConfig& config, MultiResMap initial, const Pose2& start);

  SlamStep process(const LaserScan& scan);

  // The map the robot localizes in: its own evidence combined with whatever
  // it received from others (see replace_working_map).
  const MultiResMap& map() const { return map_; }
  // Only the evidence of this robot's own scans: what it shares with others,
  // so that nothing received from a third robot is ever passed on as its own.
  const MultiResMap& own_map() const { return own_map_ ? *own_map_ : map_; }
  // Installs a richer map to localize in (own evidence ⊕ foreign evidence,
  // built by the swarm layer from own_map()). From then on every insertion
  // goes into both maps; Dempster's rule is associative and commutative, so
  // the working map stays exactly own ⊕ foreign.
  void replace_working_map(MultiResMap working);
  // How many scans this robot has put into its own map (a snapshot's version).
  std::size_t scans_inserted() const { return inserted_; }
  const Pose2& pose() const { return pose_; }
  std::size_t scans_processed() const { return processed_; }
  std::size_t scans_matched() const { return matched_; }
  std::size_t matches_rejected() const { return rejected_; }
  std::size_t recoveries() const { return recoveries_; }
  std::size_t scans_dropped() const { return filter_.dropped(); }
  std::size_t scans_held() const { return held_; }  // standing still (SlamStep::still)
  double filter_seconds() const { return filter_seconds_; }
  const SlamConfig& config() const { return config_; }

 private:
  Pose2 predict(const LaserScan& scan) const;
  // Matches `points` from step.prior (and alternatives), verifies the match and
  // fills step.pose / matched / score; a rejected match leaves the prior.
  void match_and_verify(const std::vector<ScanPoint>& points, SlamStep& step);
  // Bookkeeping after every scan: odometry anchor and constant-velocity state.
  void advance(const LaserScan& scan, const Pose2& pose);
  bool odometry_stale(const LaserScan& scan) const;
  // Counts scans with unchanged odometry; true once the robot stands still.
  bool note_standing_still(const LaserScan& scan);
  // Fills step.revised for the dropped scans since the last kept one.
  void revise_gap(SlamStep& step) const;
  // A wider, costlier search for scans whose normal match fails verification.
  static MatcherConfig recovery_config(const MatcherConfig& normal);

  SlamConfig config_;
  void insert(const Pose2& pose, const LaserScan& scan, const std::vector<ScanPoint>& points);

  MultiResMap map_;                      // working map: own ⊕ foreign evidence
  std::optional<MultiResMap> own_map_;   // set once the working map holds foreign evidence
  bool has_initial_map_ = false;         // first scan is matched, not founding
  std::size_t inserted_ = 0;
  MonteCarloMatcher matcher_;
  MonteCarloMatcher recovery_matcher_;
  ScanFilter filter_;
  double filter_seconds_ = 0.0;
  Pose2 pose_;
  std::optional<Pose2> previous_pose_;  // for the constant-velocity prior
  // Last odometry reading that moved, and our pose at that scan. Increments
  // are taken from this anchor, so odometry that freezes for a few scans and
  // then jumps (real logs do this) still predicts the whole motion.
  std::optional<Pose2> anchor_odometry_;
  Pose2 anchor_pose_;
  bool odometry_moving_ = false;  // did the last fresh odometry increment move?
  // Dropped scans since the last kept one (index, predicted pose), and the
  // pose of that kept scan, where their prediction started.
  std::vector<PoseRevision> gap_;
  Pose2 gap_start_;
  std::optional<Pose2> last_insert_pose_;
  std::optional<Pose2> last_odometry_;  // the previous scan's reading
  int still_scans_ = 0;                 // consecutive scans with the same odometry reading
  bool has_moved_ = false;              // has the odometry ever changed?
  std::size_t processed_ = 0;
  std::size_t matched_ = 0;
  std::size_t rejected_ = 0;
  std::size_t held_ = 0;
  std::size_t recoveries_ = 0;
  int consecutive_rejections_ = 0;
  double inlier_average_ = 0.0;  // running average inlier ratio of accepted matches
};

}  // namespace dsswarm
