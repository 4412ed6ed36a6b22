#include "swarm/map_knowledge.hpp"

#include <tuple>

namespace dsswarm {

bool supersedes(const MapLayer& candidate, const MapLayer& current) {
  if (candidate.version != current.version) return candidate.version > current.version;
  if (candidate.hops != current.hops) return candidate.hops < current.hops;
  const Pose2& a = candidate.origin_in_holder;
  const Pose2& b = current.origin_in_holder;
  return std::tie(a.x, a.y, a.theta) < std::tie(b.x, b.y, b.theta);
}

bool MapKnowledge::absorb(const MapSnapshot& snapshot, const Pose2& sender_in_self) {
  bool changed = false;
  for (const MapLayer& layer : snapshot.layers) {
    if (layer.origin == self_ || !layer.map) continue;
    MapLayer placed = layer;
    placed.origin_in_holder = sender_in_self * layer.origin_in_holder;
    placed.hops = layer.hops + 1;
    auto it = layers_.find(layer.origin);
    if (it == layers_.end()) {
      layers_.emplace(layer.origin, std::move(placed));
      changed = true;
    } else if (supersedes(placed, it->second)) {
      it->second = std::move(placed);
      changed = true;
    }
  }
  return changed;
}

void MapKnowledge::restore(const MapSnapshot& saved) {
  for (const MapLayer& layer : saved.layers)
    if (layer.origin != self_ && layer.map) layers_[layer.origin] = layer;
}

std::vector<MapLayer> MapKnowledge::layers() const {
  std::vector<MapLayer> out;
  out.reserve(layers_.size());
  for (const auto& [origin, layer] : layers_) out.push_back(layer);
  return out;
}

const MapLayer* MapKnowledge::find(const std::string& origin) const {
  auto it = layers_.find(origin);
  return it == layers_.end() ? nullptr : &it->second;
}

MapSnapshot MapKnowledge::snapshot(std::shared_ptr<const MultiResMap> own_map, std::uint64_t own_version) const {
  return snapshot(MapLayer{self_, own_version, Pose2{}, 0, std::move(own_map), {}});
}

MapSnapshot MapKnowledge::snapshot(MapLayer own) const {
  MapSnapshot s;
  s.sender = self_;
  s.layers.push_back(std::move(own));
  for (const auto& [origin, layer] : layers_) s.layers.push_back(layer);
  return s;
}

void MapKnowledge::place(const std::string& origin, const Pose2& origin_in_holder) {
  if (auto it = layers_.find(origin); it != layers_.end()) it->second.origin_in_holder = origin_in_holder;
}

bool MapKnowledge::move_pieces(const std::string& origin, const std::vector<PiecePose>& poses) {
  const auto it = layers_.find(origin);
  if (it == layers_.end() || poses.empty()) return false;
  std::map<std::int32_t, Pose2> by_id;
  for (const PiecePose& p : poses) by_id[p.id] = p.pose;
  bool moved = false;
  for (MapPiece& piece : it->second.pieces) {
    const auto p = by_id.find(piece.id);
    if (p == by_id.end() || p->second == piece.pose) continue;
    piece.pose = p->second;
    moved = true;
  }
  return moved;
}

}  // namespace dsswarm
