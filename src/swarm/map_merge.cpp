#include "swarm/map_merge.hpp"

#include <algorithm>

namespace dsswarm {
namespace {

void add_layer(MultiResMap& target, const MapLayer& layer, const Pose2& origin_in_target) {
  if (layer.map) combine_into(target, *layer.map, origin_in_target);
  for (const MapPiece& piece : layer.pieces)
    if (piece.map) combine_into(target, piece.map->thaw(target.config()), origin_in_target * piece.pose);
}

}  // namespace

MultiResMap compose_working_map(const MultiResMap& own, const std::vector<MapLayer>& foreign) {
  std::vector<const MapLayer*> ordered;
  for (const MapLayer& l : foreign) ordered.push_back(&l);
  std::sort(ordered.begin(), ordered.end(), [](const MapLayer* a, const MapLayer* b) { return a->origin < b->origin; });
  MultiResMap working = own;
  for (const MapLayer* l : ordered) add_layer(working, *l, l->origin_in_holder);
  return working;
}

MultiResMap layer_evidence(const MapLayer& layer) {
  if (layer.pieces.empty()) return layer.map ? *layer.map : MultiResMap();
  MultiResMap out(layer.map ? layer.map->config() : MapConfig{});
  add_layer(out, layer, Pose2());
  return out;
}

}  // namespace dsswarm
