#pragma once
// Everything one robot has learnt from others, kept per origin (provenance).
//
// Rules, which make merging idempotent, order-independent and transitive:
//  - a layer is identified by its origin robot; of two layers from the same
//    origin the one with the higher version wins (a robot's own map only
//    grows, so it contains the older one); equal versions are tied by fewer
//    hops, then by the smaller pose (any fixed rule would do);
//  - a robot never takes in a layer of its own origin: its own map is newer;
//  - layers arriving through a robot S are placed through the chain of
//    transforms: origin → S's frame → own frame.
// So receiving the same snapshot twice changes nothing, receiving several in
// any order gives the same set of layers, and what A learnt from B reaches C
// when A meets C.
#include <map>
#include <string>
#include <vector>

#include "swarm/map_snapshot.hpp"

namespace dsswarm {

class MapKnowledge {
 public:
  explicit MapKnowledge(std::string self) : self_(std::move(self)) {}

  // Takes in the layers of `snapshot`, whose sender's frame has pose
  // `sender_in_self` in ours. Returns whether any layer was added or replaced.
  bool absorb(const MapSnapshot& snapshot, const Pose2& sender_in_self);

  // Puts back what a snapshot of this robot (a checkpoint) held, layers as
  // they were (no hop added); its own layer is not part of the knowledge.
  void restore(const MapSnapshot& saved);

  // The foreign layers, in origin order.
  std::vector<MapLayer> layers() const;
  const MapLayer* find(const std::string& origin) const;
  std::size_t size() const { return layers_.size(); }
  const std::string& self() const { return self_; }

  // What this robot sends: its own map as layer 0, then everything it knows.
  MapSnapshot snapshot(std::shared_ptr<const MultiResMap> own_map, std::uint64_t own_version) const;
  MapSnapshot snapshot(MapLayer own) const;

  // Moves `origin`'s map frame to `origin_in_holder` (as this robot's pose
  // graph placed it); nothing if no layer of it is held.
  void place(const std::string& origin, const Pose2& origin_in_holder);
  // Moves the pieces of `origin`'s layer that it holds to where `origin`
  // says they lie now (MapMoves). Returns whether any moved.
  bool move_pieces(const std::string& origin, const std::vector<PiecePose>& poses);

 private:
  std::string self_;
  std::map<std::string, MapLayer> layers_;
};

// Whether `candidate` should replace `current` (same origin): see the rules above.
bool supersedes(const MapLayer& candidate, const MapLayer& current);

}  // namespace dsswarm
