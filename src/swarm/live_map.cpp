#include "swarm/live_map.hpp"

#include "swarm/map_merge.hpp"

namespace dsswarm {

LiveMapParts live_map_parts(const Slam& slam, const std::vector<MapLayer>& foreign) {
  LiveMapParts p;
  p.config = slam.config().map;
  const LoopCloser& closer = slam.loop_closer();
  for (const std::shared_ptr<const Submap>& s : slam.submaps().finished()) {
    p.finished.push_back(s);
    p.finished_poses.push_back(closer.submap_cells_pose(s->id));
  }
  const Submap& current = slam.submaps().current();
  if (current.scans > 0) {
    p.growing = current;
    p.growing_pose = closer.submap_cells_pose(current.id);
  }
  p.foreign = foreign;
  return p;
}

std::vector<LiveMap::Entry> LiveMap::key_of(const LiveMapParts& parts) {
  std::vector<Entry> key;
  for (std::size_t i = 0; i < parts.finished.size(); ++i)
    key.push_back({"", parts.finished[i]->id, 0, parts.finished_poses[i]});
  for (const MapLayer& l : parts.foreign) {
    key.push_back({l.origin, -1, l.version, l.origin_in_holder});
    for (const MapPiece& piece : l.pieces) key.push_back({l.origin, piece.id, l.version, piece.pose});
  }
  return key;
}

MultiResMap LiveMap::compose(const LiveMapParts& parts) {
  MapConfig finest = parts.config;
  finest.levels = 1;  // what a picture shows; the coarse levels serve only matching
  std::vector<Entry> key = key_of(parts);
  if (!base_ || key != base_key_ || base_->config().resolution != finest.resolution) {
    MultiResMap own(finest);
    for (std::size_t i = 0; i < parts.finished.size(); ++i) add_submap(own, *parts.finished[i], parts.finished_poses[i]);
    base_ = compose_working_map(own, parts.foreign);
    base_key_ = std::move(key);
    ++base_compositions_;
  }
  MultiResMap map = *base_;
  if (parts.growing) add_submap(map, *parts.growing, parts.growing_pose);
  return map;
}

}  // namespace dsswarm
