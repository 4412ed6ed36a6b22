#pragma once
// The pose graph of one robot (sparse pose adjustment, Konolige et al. 2010,
// as in Cartographer): trajectory nodes and submaps are SE(2) poses in the
// global frame, tied by relative-pose constraints of a node in a submap
//
//   * local: local SLAM's estimate, for the submap the node's scan went into
//     and, where submaps meet, the one before it (that ties them together),
//   * loop:  a loop closure into another submap, under a robust loss,
//   * foreign: the node placed in another robot's map frame (a frame of
//     `frames`: where that robot's map lies in ours) — by an encounter with
//     it, or a loop closure into one of its submaps — under the same loss,
//   * peer: that robot's own closure into one of our submaps (`peer`): its
//     node, held where that robot last put it in its frame, in our submap,
//
// and optimized by Ceres (one thread). No constraint joins two nodes, so
// Ceres eliminates the nodes first (Schur complement) and factorizes only
// the submaps' and frames' part: fast, and small in memory however long the trajectory.
// The graph is plain data: the loop-closure module snapshots it, optimizes
// the copy and hands the poses back (loop_closer.hpp).
#include <cstdint>
#include <vector>

#include "geometry/pose2.hpp"

namespace dsswarm {

struct PoseGraphConfig {
  // Standard deviations of the constraints' errors: residuals are divided by
  // them. Local SLAM is trusted over short distances; a loop closure's scan
  // was placed in a submap built long before.
  double local_sigma_xy = 0.02;      // m
  double local_sigma_theta = 0.005;  // rad
  double loop_sigma_xy = 0.05;       // m
  double loop_sigma_theta = 0.01;    // rad
  // Another robot's map frame seen from one of our nodes: its submaps were
  // optimized by that robot, and an encounter rests on one scan.
  double foreign_sigma_xy = 0.05;    // m
  double foreign_sigma_theta = 0.01; // rad
  // Another robot's closures into our map (`peer`) weigh less: each robot
  // solves against the other's last shape while the other does the same,
  // and at full weight the two can overshoot towards each other's old
  // shapes. Their residuals (weighted as foreign ones) are scaled by this,
  // their cost by its square (0.707: half).
  double peer_weight = 0.707;
  // Huber loss on loop closures (and foreign ones), in units of their sigmas: beyond it an edge
  // pulls with constant force, so one wrong closure cannot drag the graph far
  // while a right one after a long drift still pulls the loop shut.
  double loop_huber = 3.0;
  int max_iterations = 50;
  // Whether constraints into other robots' maps may move this robot's own
  // nodes and submaps (one optimization of everything), or only place the
  // other robots' frames (this robot's graph first, on its own constraints,
  // then the frames against its nodes held fixed): its map then stays its
  // own however the others' maps are bent.
  bool foreign_moves_own = true;

  void validate() const;  // throws ConfigError naming the field
};

struct Constraint {
  enum class Kind : std::uint8_t { local, loop, foreign };
  Kind kind = Kind::local;
  int submap = 0;   // foreign: the index of a frame in PoseGraph::frames
  int node = 0;
  Pose2 relative;   // measured pose of the node in the submap's frame (its anchor), or in the foreign frame
  // A closure into another robot's submap: that piece (its index in
  // ForeignMaps::pieces) and its pose in its frame when `relative` was
  // measured; `relative` moves with the piece when that robot's later
  // closures move it (follow_pieces, foreign_maps.hpp). -1: not in a piece.
  int piece = -1;
  Pose2 piece_pose{};
};

// Another robot's loop closure into one of our submaps: its node, at `node`
// in its own map frame (frames[frame]), measured at `relative` in our
// submap's frame. Weighed like a foreign constraint, under the same loss.
struct PeerConstraint {
  int submap = 0;
  int frame = 0;
  Pose2 node;
  Pose2 relative;
};

struct PoseGraph {
  std::vector<Pose2> nodes;    // global poses of the trajectory nodes
  std::vector<Pose2> submaps;  // global poses of the submaps' anchors
  std::vector<Pose2> frames;   // global poses of other robots' map frames
  std::vector<Constraint> constraints;
  std::vector<PeerConstraint> peer;
  int fixed_submap = 0;        // held constant: it anchors the global frame
};

// The pose a constraint places its node relative to: its submap's, or its frame's.
const Pose2& reference_pose(const PoseGraph& graph, const Constraint& c);

struct OptimizationSummary {
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  bool usable = false;  // false: the poses were left as they were
};

// Optimizes the poses of `graph` in place.
OptimizationSummary optimize(PoseGraph& graph, const PoseGraphConfig& config);

// The constraint's error at the graph's current poses: where the node is,
// seen from the submap, relative to where the constraint measured it.
Pose2 constraint_error(const PoseGraph& graph, const Constraint& c);

}  // namespace dsswarm
