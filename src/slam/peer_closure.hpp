#pragma once
// A loop closure of one robot into another's submap, as the first tells the
// second (swarm/map_snapshot.hpp, MapMoves): the second robot's submap, where
// the first robot's node lay in that submap's cells, and the node's pose in
// the first robot's own frame now. The second adds it to its own graph
// (LoopCloser::set_peer_closures), so both robots weigh the same constraints
// between their maps, as one optimization of both graphs would.
#include <cstdint>

#include "geometry/pose2.hpp"

namespace dsswarm {

struct PeerClosure {
  std::int32_t submap = 0;  // MapPiece::id: the receiver's submap
  Pose2 in_cells;           // the node in that submap's cells
  Pose2 node;               // the node in the sender's frame
  bool operator==(const PeerClosure&) const = default;
};

}  // namespace dsswarm
