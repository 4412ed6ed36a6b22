#pragma once
// Other robots' maps in this robot's pose graph. Each robot we hold a map of
// has a map frame — where its map lies in ours — which our graph optimizes
// like a submap's pose: an encounter with that robot ties the frame to the
// node we stood at, and loop closures of our nodes into its finished submaps
// (searched like our own) tie it all along the ground the two robots share.
// So a merge does not rest on the one scan where the robots met: its heading
// error is not levered over the whole map. Each robot optimizes its own
// graph; no robot is in charge, and none needs the others' graphs.
//
// A frame's pieces are the other robot's submaps, placed in its frame as that
// robot last optimized them; they move when it sends newer ones.
#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <memory>
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/frozen_map.hpp"
#include "slam/peer_closure.hpp"
#include "slam/pose_graph.hpp"

namespace dsswarm {

// One submap of another robot's map.
using ForeignPiece = MapPiece;

// A piece as the loop-closure search sees it.
struct ForeignPieceInfo {
  int frame = 0;
  ForeignPiece piece;
  Eigen::Vector2d centre{0.0, 0.0};  // of its evidence, in its cells' frame
  double radius = 0.0;               // m from the centre that holds all its evidence
  // In the robot's latest list: a robot resumed from its checkpoint sends its
  // saved pieces again as one, and the old ones are no longer searched.
  bool current = true;
};

// A closure measured in a piece that has moved since (that robot closed a
// loop and sent the piece again) moves with it: relative := now ⊕ then⁻¹ ⊕
// relative, and then := now. Nothing for piece < 0 (not in a piece).
void follow_piece(int piece, Pose2& then, Pose2& relative, const std::vector<ForeignPieceInfo>& pieces);
void follow_pieces(std::vector<Constraint>& constraints, const std::vector<ForeignPieceInfo>& pieces);

class ForeignMaps {
 public:
  explicit ForeignMaps(const MapConfig& map) : map_(map) {}

  // Registers or updates robot `frame`'s map: its finished pieces (a piece
  // already held keeps its evidence and takes the new pose; one held but
  // not in the list is no longer current) and, until our
  // graph has constraints on the frame, its pose in ours. Returns the
  // indices (into pieces()) of pieces not held before.
  std::vector<std::size_t> set(int frame, const Pose2& frame_pose, const std::vector<ForeignPiece>& pieces);

  // An encounter: our node `node` was at `node_pose` (global) when the
  // robot's frame was seen at `frame_pose` (global): the constraint placing
  // the node in that frame. From then on the frame's pose is the graph's.
  Constraint encounter(int frame, int node, const Pose2& node_pose, const Pose2& frame_pose);

  // Frames in graph order (frame ids are the caller's; graph index = position here).
  int graph_index(int frame) const;
  const std::vector<int>& frames() const { return frame_ids_; }
  const std::vector<Pose2>& frame_poses() const { return poses_; }
  const std::vector<bool>& tied() const { return tied_; }
  // Poses the graph optimized (graph.frames, in graph order).
  void apply(const std::vector<Pose2>& optimized);
  Pose2 frame_pose(int frame) const;

  const std::vector<ForeignPieceInfo>& pieces() const { return pieces_; }
  std::size_t memory_bytes() const;

 private:
  int index_of(int frame);  // adds the frame if new

  MapConfig map_;
  std::vector<int> frame_ids_;
  std::vector<Pose2> poses_;
  std::vector<ForeignPieceInfo> pieces_;
  std::map<std::pair<int, int>, std::size_t> piece_index_;  // (frame, piece id) -> index
  std::vector<bool> tied_;  // per frame: an encounter placed it in the graph
};

}  // namespace dsswarm
