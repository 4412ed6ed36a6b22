#pragma once
// Where is the other robot? Placing a foreign scan in one's own map when the
// relative heading is unknown and the position is known only to lie within
// the proximity sensor's range.
//
//   1. exhaustive search on the coarsest level: every heading (3° steps) ×
//      every position on a 0.15 m lattice within the range (coarse_search.hpp) — cheap there,
//      and the coarse level's wide basins make a lattice this sparse safe;
//   2. the best few distinct modes are refined coarse-to-fine by the
//      Monte-Carlo matcher (no motion prior: there is no prior);
//   3. the refined modes are ranked by how well the foreign robot's
//      *surroundings* fit — the obstacles of its own map within a few metres,
//      which it sends anyway with its map: one scan of a corridor fits many
//      places, the walls, doors and rooms around it far fewer. A mode whose
//      beams meet the map's walls from behind (same_side_ratio) cannot be
//      where the robot is, however its surroundings fit: it ranks after
//      every mode that can. The best mode
//      is refined once more with those points (hundreds of walls cells pin
//      the pose better than one scan) and is the answer; the best *distinct*
//      alternative is kept too, because a placement is only trustworthy when
//      it clearly beats every other one.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "grid/multires_map.hpp"
#include "matching/monte_carlo_matcher.hpp"
#include "matching/same_side.hpp"
#include "sensor/scan_points.hpp"

namespace dsswarm {

struct RelativePoseConfig {
  double search_radius = 3.0;        // m around one's own position (the proximity range)
  double coarse_step_xy = 0.15;      // m, lattice of the exhaustive search
  double coarse_step_theta = 0.0524; // rad (3°)
  int coarse_points = 90;            // scan points used by the exhaustive search
  int candidates = 32;               // coarse modes refined
  double surroundings_radius = 8.0;  // m around the foreign robot (step 3)
  int surroundings_points = 2000;    // at most this many obstacle cells
  // Once a placement is accepted, the transform the maps are merged with is
  // refined against the foreign robot's obstacles this far around it, thinned
  // to at most this many (refine_placement): a map that drifted fits one scan
  // and its near surroundings in a slightly turned pose; the wide fit is what
  // lines the two maps up as wholes. Measured on 20 simulated 3-robot runs
  // (transform error against the frames as the maps stood, README): 8 m as
  // for ranking left 8 of 231 merges outside 0.05 m / 0.5 degrees, 15 m 4 of
  // 220, 25 m 2 of 226, 40 m none of 222. 0 disables. Not used with loop
  // closure on: there the closures into the other robot's submaps line the
  // maps up (SwarmAgent::view).
  double merge_surroundings_radius = 40.0;  // m
  int merge_surroundings_points = 8000;
  // The last refinement of a placement with the surroundings
  // (refine_placement, step 3's and the merge's) starts this narrow.
  double polish_sigma_xy = 0.03;     // m
  double polish_sigma_theta = 0.01;  // rad
  // With loop closure on, the peer is placed in the robot's unfinished
  // submaps as well, and the better placement kept: where the robot returns to
  // a place before that loop has closed, its composed map holds both visits
  // out of line, while its recent submaps hold what it sees now
  // (SwarmAgent::view, locate_peer).
  bool place_in_recent_submaps = true;
  // Two placements are distinct modes when this far apart (either way).
  double mode_separation_xy = 0.5;      // m
  double mode_separation_theta = 0.26;  // rad (15°)
  // Modes whose same_side_ratio is below this rank after all others, and are
  // no runner-up to one that passes (0: rank by the surroundings alone).
  double possible_same_side = 0.8;
  // Every point on every level (no merge, the coarse levels' old stride): a
  // wrong placement here is a wrong closure or merge, not one scan's error.
  MatcherConfig refine{.evaluations = 600, .sigma_xy = 0.15, .sigma_theta = 0.04,
                       .fine_merge_cells = 0.0, .coarse_merge_cells = 0.0, .coarse_stride = 2,
                       .prior_weight = 0.0};

  void validate() const;  // throws ConfigError naming the field
};

struct PoseHypothesis {
  Pose2 pose;                  // foreign robot base pose in the own map frame
  double score = 0.0;          // finest-level weighted occupancy of the scan, [0, 1]
  // The ranking: mean (occupied − free) mass under the surroundings points,
  // in [−1, 1] (= score when there are no surroundings).
  double surroundings_score = 0.0;
  double inlier_ratio = 0.0;   // see match_quality
  double known_fraction = 0.0;
  // Of the scan points that land on obstacles, the weight share whose beam,
  // once clear of the obstacle (15 cm or more before the hit), runs through
  // space the map has seen free: the obstacle was seen from the same side.
  // A thin wall seen from opposite sides fits either way when shifted by its
  // thickness, and only this tells the two apart (see same_side_ratio).
  double same_side_ratio = 0.0;
};

struct RelativePoseResult {
  PoseHypothesis best;
  std::optional<PoseHypothesis> runner_up;  // best placement distinct from `best`
  int evaluations = 0;                      // pose evaluations spent
};

// `points`: the foreign scan in the foreign robot's base frame; `near`: one's
// own position (the foreign robot is within search_radius of it);
// `surroundings`: obstacle cells of the foreign map around the foreign robot,
// in its base frame (see surroundings_points), or empty to rank by the scan.
RelativePoseResult locate_scan(const MultiResMap& map, const std::vector<ScanPoint>& points,
                               const Eigen::Vector2d& near, const RelativePoseConfig& config, std::uint64_t seed,
                               const std::vector<ScanPoint>& surroundings = {});

// Polishes an accepted placement `start` of the foreign robot in `map` with
// its scan and `surroundings` together (obstacle cells of its map, its base
// frame), by the fine Monte-Carlo search locate_scan ends with.
MatchResult refine_placement(const MultiResMap& map, const std::vector<ScanPoint>& points,
                       const std::vector<ScanPoint>& surroundings, const Pose2& start, const RelativePoseConfig& config,
                       std::uint64_t seed);

// Obstacle cells (occupied mass ≥ 0.5) of `map`'s finest level within
// `radius` of `robot_pose`, as points in the robot's base frame, thinned
// evenly to at most `max_points`.
std::vector<ScanPoint> surroundings_points(const MultiResMap& map, const Pose2& robot_pose, double radius,
                                           int max_points);

// Whether two placements are distinct modes under `config`.
bool distinct_modes(const Pose2& a, const Pose2& b, const RelativePoseConfig& config);

}  // namespace dsswarm
