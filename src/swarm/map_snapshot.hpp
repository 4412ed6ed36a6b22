#pragma once
// What one robot knows of the world, kept layer by layer with its origin
// (provenance): its own evidence, and for every other robot it has heard of —
// directly or second-hand — that robot's own evidence, in that robot's map
// frame, with the pose of that frame in the holder's frame.
//
// Keeping evidence per origin instead of one blended map is what lets merging
// be idempotent and order-independent: a newer layer from the same origin
// replaces the older one (a robot's own map only grows), so the same evidence
// is never counted twice however often, and through whom, it arrives.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/frozen_map.hpp"
#include "grid/multires_map.hpp"
#include "slam/peer_closure.hpp"

namespace dsswarm {

struct MapLayer {
  std::string origin;          // robot whose own scans made this evidence
  std::uint64_t version = 0;   // scans the origin had put in its map when the layer was taken (more = newer)
  Pose2 origin_in_holder;      // pose of the origin's map frame in the holder's map frame
  int hops = 0;                // 0: the holder's own map; 1: received from the origin; 2+: second-hand
  // Immutable once taken, so snapshots and agents share it without copying.
  std::shared_ptr<const MultiResMap> map;
  // A robot with loop closure on sends its finished submaps apart, each at
  // its optimized pose in the origin's frame; then `map` holds only the rest
  // (the growing submap), and the layer's evidence is map ⊕ pieces. A holder
  // thus places the pieces where the origin's later loop closures put them.
  std::vector<MapPiece> pieces;
};

// One layer a robot holds, without its map: whose evidence, and how new
// (what robots tell each other so that only what is missing is sent).
struct LayerVersion {
  std::string origin;
  std::uint64_t version = 0;
  std::int32_t hops = 0;
  bool operator==(const LayerVersion&) const = default;
};

inline std::vector<LayerVersion> layer_versions(const std::vector<MapLayer>& layers) {
  std::vector<LayerVersion> out;
  for (const MapLayer& l : layers) out.push_back({l.origin, l.version, l.hops});
  return out;
}

// Where a robot's map lies now, for a robot that holds a copy of it: its
// loop closures since the copy was taken moved its submaps (pieces) and the
// scans where it met the holder. A few bytes per submap, against the
// megabytes of the map itself; without it the holder's copy and its
// estimate of where the robot's frame lies keep the old shape.
struct PiecePose {
  std::int32_t id = 0;  // MapPiece::id
  Pose2 pose;           // where its cells lie in the robot's frame now
};
struct TieMove {
  std::uint64_t encounter = 0;  // the encounter's id
  Pose2 then;                   // the robot's scan there, as it offered it
  Pose2 now;                    // the same scan now
};
// The robot's own side of an encounter, as it tells a follower where it went.
struct TieScan {
  std::uint64_t encounter = 0;
  std::size_t scan_index = 0;  // its scan there (process() order)
  Pose2 offered;               // that scan's pose as it offered it
};
struct MapMoves {
  std::uint64_t revision = 0;  // the robot's graph revision: a higher one supersedes
  std::vector<PiecePose> pieces;
  std::vector<TieMove> ties;   // its encounters with the holder
  // Its loop closures into the holder's map (slam/peer_closure.hpp): the
  // holder weighs them in its own graph too, so the two robots' graphs rest
  // on the same constraints between their maps.
  std::vector<PeerClosure> closures;
};

// What a robot sends at an encounter (and what a .dsmap file holds): layers[0]
// is the sender's own map (origin == sender, identity pose, hops 0), then what
// it knows of others, placed in the sender's frame.
struct MapSnapshot {
  std::string sender;
  std::vector<MapLayer> layers;
};

}  // namespace dsswarm
