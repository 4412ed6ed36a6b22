#pragma once
// One background round of loop closing (see loop_closer.hpp): a pure function
// from a snapshot of the graph to new closures and optimized poses.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "sensor/scan_points.hpp"
#include "slam/compact_scan.hpp"
#include "slam/foreign_maps.hpp"
#include "slam/loop_search.hpp"
#include "slam/pose_graph.hpp"
#include "slam/submaps.hpp"

namespace dsswarm {

struct LoopClosureConfig {
  bool enabled = true;  // off: one map, no submaps (docs/loop_closure.md)
  // A scan inserted into a submap becomes a trajectory node when the robot
  // moved this much since the last node (and always the first of a submap).
  // The first `overlap_nodes` nodes of a submap are also tied into the
  // submap before it: that holds consecutive submaps together.
  double node_spacing = 0.2;           // m
  double node_rotation = 0.1;          // rad
  int overlap_nodes = 3;
  // Nodes this far apart along the trajectory are searched for loop closures.
  double search_spacing = 1.0;         // m
  double max_distance = 5.0;           // m: submaps with a node this close to the searched node's estimate
  int max_submaps = 3;                 // searched per node, nearest first
  // A finished submap that already has a closure (accepted, or found earlier
  // this round) from a node within this travel of the searched node is not
  // searched again from it: one more closure there adds little to the graph
  // and costs the background a search (0: search every time).
  double reclose_travel = 2.0;         // m
  // The search window grows with the distance travelled since the submap or
  // the last accepted closure, whichever is later.
  double window_xy = 0.3;              // m
  double window_xy_per_m = 0.05;
  double max_window_xy = 5.0;          // m
  double window_theta = 0.05;          // rad
  double window_theta_per_m = 0.005;   // rad per m
  double max_window_theta = 0.5;       // rad
  // Other robots' submaps (foreign_maps.hpp) are searched like our own, at
  // most `foreign_max_pieces` per node, nearest first, within a window that
  // grows with the distance from the nearest node already tied to that
  // robot's frame. Pieces new to us are also searched from our earlier nodes
  // near them, at most `foreign_backlog` such searches a round.
  int foreign_max_pieces = 3;
  int foreign_backlog = 100;
  LoopSearchConfig search;
  // Pairwise consistency: a verified candidate is accepted once another
  // closure (of this round, an earlier pending one or an accepted one) whose
  // node is within consistency_travel along the trajectory, and whose submap
  // is the same or as close, agrees with it within agree_xy / agree_theta.
  // Unconfirmed candidates wait `pending_rounds` rounds for a partner.
  double consistency_travel = 10.0;    // m
  double agree_xy = 0.1;               // m
  double agree_theta = 0.035;          // rad (2°)
  int pending_rounds = 3;
  // After optimization, a new closure whose error is still beyond these is
  // dropped (the graph does not bear it out) and the graph re-optimized.
  double max_residual_xy = 0.2;        // m
  double max_residual_theta = 0.05;    // rad
  // Nodes per round. Each round optimizes the whole graph: fewer, larger
  // rounds cost the background less (the solver's share halves from 20 to 40).
  int round_nodes = 40;
  // Rounds handed over and not yet applied: a round's result is applied when
  // this many more have been handed over (1: at the next hand-over), so the
  // background has that long to finish before local SLAM has to wait for it.
  int rounds_in_flight = 4;
  PoseGraphConfig graph;

  void validate() const;  // throws ConfigError naming the field
};

struct LoopClosureStats {
  std::size_t rounds = 0;
  std::size_t optimizations = 0;
  std::size_t searches = 0;              // (node, submap) pairs tried
  std::size_t skipped_closed = 0;        // pairs not tried: the submap was closed nearby (reclose_travel)
  std::size_t candidates = 0;            // passed every check of the search
  std::size_t accepted = 0;
  std::size_t rejected_no_match = 0;
  std::size_t rejected_unknown = 0;
  std::size_t rejected_inliers = 0;
  std::size_t rejected_same_side = 0;
  std::size_t rejected_ambiguous = 0;
  std::size_t rejected_prior_fits = 0;    // fits where the node is believed to be, yet matched elsewhere
  std::size_t rejected_inconsistent = 0;  // never found an agreeing partner
  std::size_t rejected_residual = 0;      // not borne out by the optimized graph
  std::size_t foreign_candidates = 0;     // of `candidates`: into other robots' submaps
  std::size_t foreign_accepted = 0;       // of `accepted`
  double background_seconds = 0.0;        // wall time of the rounds themselves
};

// A verified candidate waiting for an agreeing partner.
struct PendingCandidate {
  LoopCandidate candidate;
  int age = 0;  // rounds waited
};

// What loop closing has concluded so far. Each round starts from its
// predecessor's (the rounds run one after the other) and local SLAM takes it
// over when it applies a round.
struct LoopState {
  std::vector<Constraint> closures;         // accepted loop closures (own and foreign)
  std::vector<PendingCandidate> pending;    // verified, waiting for a partner
  // Optimized global poses of the first nodes.size() nodes, submaps and frames.
  std::vector<Pose2> nodes, submaps, frames;
  Pose2 global_from_local;  // moves local SLAM's newer poses into the global frame
  double last_closure_travel = -1e9;  // m along the trajectory of the latest own closure
  bool optimized = false;  // the round that made it optimized the graph
};

struct RoundInput {
  MapConfig map;    // the submaps' (to thaw them)
  // The graph at hand-over: local constraints and encounters, and local
  // SLAM's node poses; the round completes its estimates and adds the
  // closures from the state it starts from (graph.frames: the caller's
  // estimates, used for frames not tied by an encounter).
  PoseGraph graph;
  std::vector<Pose2> node_local;
  std::vector<bool> frame_tied;
  std::vector<int> node_submap;
  std::vector<double> node_travel;
  struct Search {
    int node;
    std::shared_ptr<const CompactScan> points;
  };
  std::vector<Search> searches;  // new nodes to search
  struct SubmapInfo {
    std::shared_ptr<const Submap> finished;  // null: still growing, not searched
    std::vector<int> nodes;
    Pose2 anchor;
    double travel_end = 0.0;  // m along the trajectory where it ends (so far)
    bool fixed = false;       // a given map
  };
  std::vector<SubmapInfo> submaps;
  // Filled from the state the round starts from.
  std::vector<PendingCandidate> pending;
  double last_closure_travel = -1e9;
  // Other robots' submaps (graph.frames holds their frames), and searches of
  // earlier nodes into pieces new to us: (node, index into `foreign`).
  std::vector<ForeignPieceInfo> foreign;
  struct Backlog {
    int node;
    std::shared_ptr<const CompactScan> points;
    std::size_t piece;
  };
  std::vector<Backlog> backlog;
  bool new_constraints = false;  // optimize even without new closures (an encounter arrived)
};

struct RoundOutput {
  std::vector<LoopCandidate> accepted;
  std::vector<PendingCandidate> pending;
  bool optimized = false;
  PoseGraph graph;  // the optimized poses (when optimized)
  LoopClosureStats stats;
  LoopState state;  // what the next round starts from
};

// Memory a closer's rounds reuse from one to the next. They run one at a
// time (an executor runs jobs in order), so they share it.
struct RoundScratch {
  BranchAndBoundMatcher matcher;
};

struct Round {
  RoundInput in;
  std::shared_ptr<RoundScratch> scratch;  // null: the round's own
  // Where it starts: the round before it (which runs first), or `base`.
  std::shared_ptr<const Round> previous;
  LoopState base;
  RoundOutput out;
};

// Searches, verifies, checks consistency and optimizes; fills round.out.
void run_round(Round& round, const LoopClosureConfig& config, const PointWeightConfig& weights, std::uint64_t seed);

void add_stats(LoopClosureStats& total, const LoopClosureStats& more);

}  // namespace dsswarm
