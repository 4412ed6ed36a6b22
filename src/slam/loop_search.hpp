#pragma once
// One loop-closure search, synchronously: where does a trajectory node's scan
// lie in a finished submap, and is the answer to be trusted? A false loop
// closure bends a map that was right, so a candidate must pass everything the
// swarm asks of a foreign scan before it is merged (swarm/encounter):
//
//   1. branch and bound over the search window (matching/branch_and_bound_matcher)
//      finds the best pose; nothing scoring above `min_score`: no match;
//   2. the Monte-Carlo matcher refines it on the submap (no motion prior);
//   3. enough of the scan lands on mapped cells (`min_known`), and of those
//      enough on or next to obstacles (`min_inliers`, match_quality);
//   4. the obstacles are approached through space the submap saw free
//      (`min_same_side`, same_side_ratio): not a thin wall seen from behind;
//   5. no distinct pose in the window scores nearly as well (`max_runner_up`):
//      corridors and symmetric rooms fit several ways;
//   6. the scan does not also fit where the node is believed to be (refined
//      there, at least `min_prior_known` of it on mapped cells and
//      `min_inliers` of those on obstacles) while the match lies elsewhere:
//      a scan that only grazes the submap scores higher slid onto it (more
//      of it on mapped cells), but where it already fits nothing asks for a jump.
//
// Whether it agrees with the other closures is the caller's question
// (closures_agree, below).
#include <cstdint>
#include <vector>

#include "geometry/pose2.hpp"
#include "matching/branch_and_bound_matcher.hpp"
#include "matching/monte_carlo_matcher.hpp"
#include "slam/pose_graph.hpp"
#include "slam/submaps.hpp"

namespace dsswarm {

struct LoopSearchConfig {
  // The search looks at the scan's points within max_range (the farthest
  // sets the heading step, and the submap is thawed only that far around);
  // branch and bound at most `points` of them.
  int points = 150;
  double max_range = 15.0;  // m
  // Branch-and-bound levels at most (blocks of 2^(depth-1) cells at the top):
  // each costs a byte per cell of the searched area.
  int max_depth = 5;
  double min_score = 0.2;   // branch-and-bound score (mean occupied − free under the points)
  // Every point on every level (no merge, the coarse levels' old stride): a
  // wrong placement here is a wrong closure or merge, not one scan's error.
  MatcherConfig refine{.evaluations = 400, .sigma_xy = 0.05, .sigma_theta = 0.02,
                       .fine_merge_cells = 0.0, .coarse_merge_cells = 0.0, .coarse_stride = 2,
                       .prior_weight = 0.0};
  double min_known = 0.5;
  double min_inliers = 0.75;
  double min_same_side = 0.8;
  // The best pose at least runner_up_xy or runner_up_theta away from the
  // best must score below max_runner_up × the best's score.
  double max_runner_up = 0.9;
  double runner_up_xy = 0.5;      // m
  double runner_up_theta = 0.26;  // rad (15°)
  double min_prior_known = 0.1;

  void validate() const;  // throws ConfigError naming the field
};

enum class LoopRejection : std::uint8_t { none, no_match, unknown, inliers, same_side, ambiguous, prior_fits };
const char* to_string(LoopRejection r);

struct LoopCandidate {
  int node = 0;
  int submap = 0;           // foreign: the other robot's frame (its index in the graph's frames)
  bool foreign = false;     // into another robot's submap (foreign_maps.hpp)
  Pose2 relative;           // the node's pose in the submap's frame (its anchor), or in the foreign frame
  int piece = -1;           // foreign: the piece searched, and its pose in its frame then (Constraint)
  Pose2 piece_pose{};
  double score = 0.0;       // branch-and-bound score of the best pose
  double known = 0.0;       // match_quality of the refined pose
  double inliers = 0.0;
  double same_side = 0.0;
  double runner_up = 0.0;   // runner-up score / best score (0: none above the bar)
  double prior_known = 0.0; // match_quality where the node is believed to be (refined there)
  double prior_inliers = 0.0;
};

struct LoopSearch {
  LoopRejection rejection = LoopRejection::no_match;
  LoopCandidate candidate;  // filled as far as the search got
};

// Searches `points` (the node's scan, base frame) in `submap` within `window`
// around `prior`, the node's estimated pose in the submap's cells (local
// frame). `matcher` holds the submap's finest level's bounds.
LoopSearch search_loop_closure(const BranchAndBoundMatcher& matcher, const Submap& submap,
                               const std::vector<ScanPoint>& points, const Pose2& prior, const SearchWindow& window,
                               const LoopSearchConfig& config, std::uint64_t seed);

// Pairwise consistency of two loop closures (constraints of kind loop): the
// motion between their two nodes as the graph's estimate has it, against the
// motion the closures imply through their two submaps (whose relative pose
// the graph also has). Meaningful when the nodes are close along the
// trajectory and so are the submaps; agree within `xy` m and `theta` rad.
bool closures_agree(const PoseGraph& graph, const Constraint& a, const Constraint& b, double xy, double theta);

}  // namespace dsswarm
