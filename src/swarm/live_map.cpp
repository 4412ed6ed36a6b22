#include "swarm/live_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "common/errors.hpp"
#include "swarm/map_merge.hpp"

namespace dsswarm {
namespace {

// The circle around the cells [lo, hi) of a grid at `resolution`.
void set_extent(CellIndex lo, CellIndex hi, double resolution, Eigen::Vector2d& centre, double& reach) {
  centre = Eigen::Vector2d(lo.x + hi.x, lo.y + hi.y) * (0.5 * resolution);
  reach = 0.5 * resolution * std::hypot(double(hi.x - lo.x), double(hi.y - lo.y));
}

}  // namespace

void LiveMapConfig::validate() const {
  if (!(redraw_cells >= 0.0 && std::isfinite(redraw_cells))) throw ConfigError("live_map.redraw_cells must be >= 0");
}

LiveMap::LiveMap(const LiveMapConfig& config) : config_(config) { config_.validate(); }

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
  const double res = parts.config.resolution;
  std::vector<Entry> key;
  CellIndex lo, hi;
  for (std::size_t i = 0; i < parts.finished.size(); ++i) {
    Entry& e = key.emplace_back(Entry{"", parts.finished[i]->id, 0, parts.finished_poses[i]});
    parts.finished[i]->frozen.bounds(lo, hi);
    set_extent(lo, hi, res, e.centre, e.reach);
  }
  for (const MapLayer& l : parts.foreign) {
    Entry& layer = key.emplace_back(Entry{l.origin, -1, l.version, l.origin_in_holder});
    if (l.map) {
      l.map->finest().bounds(lo, hi);
      set_extent(lo, hi, res, layer.centre, layer.reach);
    }
    for (const MapPiece& piece : l.pieces) {
      Entry& e = key.emplace_back(Entry{l.origin, piece.id, l.version, l.origin_in_holder * piece.pose});
      if (piece.map) {
        piece.map->bounds(lo, hi);
        set_extent(lo, hi, res, e.centre, e.reach);
      }
    }
  }
  return key;
}

bool LiveMap::still_holds(const std::vector<Entry>& kept, const std::vector<Entry>& now, double resolution) const {
  if (kept.size() != now.size()) return false;
  const double tolerance = config_.redraw_cells * resolution;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const Entry& a = kept[i];
    const Entry& b = now[i];
    if (a.origin != b.origin || a.id != b.id || a.version != b.version) return false;
    if (a.pose == b.pose) continue;
    // Every cell lies within `reach` of the centre: it moved at most as far
    // as the centre did plus the turn's sweep at that distance.
    const double moved = (b.pose * b.centre - a.pose * a.centre).norm() +
                         std::abs(normalize_angle(b.pose.theta - a.pose.theta)) * b.reach;
    if (!(moved <= tolerance)) return false;
  }
  return true;
}

bool LiveMap::add_finished(const LiveMapParts& parts, const std::vector<Entry>& key) {
  // A key lists this robot's own submaps first, oldest first.
  const auto own = [](const std::vector<Entry>& k) {
    return static_cast<std::size_t>(std::find_if(k.begin(), k.end(), [](const Entry& e) { return !e.origin.empty(); }) -
                                    k.begin());
  };
  const std::size_t kept_own = own(base_key_), now_own = own(key);
  if (now_own <= kept_own) return false;
  std::vector<Entry> rest = key;
  rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(kept_own), rest.begin() + static_cast<std::ptrdiff_t>(now_own));
  if (!still_holds(base_key_, rest, parts.config.resolution)) return false;
  for (std::size_t i = kept_own; i < now_own; ++i) add_submap(*base_, *parts.finished[i], parts.finished_poses[i]);
  base_key_.insert(base_key_.begin() + static_cast<std::ptrdiff_t>(kept_own),
                   key.begin() + static_cast<std::ptrdiff_t>(kept_own), key.begin() + static_cast<std::ptrdiff_t>(now_own));
  ++base_additions_;
  return true;
}

MultiResMap LiveMap::compose(const LiveMapParts& parts) {
  MapConfig finest = parts.config;
  finest.levels = 1;  // what a picture shows; the coarse levels serve only matching
  std::vector<Entry> key = key_of(parts);
  const bool kept = base_ && base_->config().resolution == finest.resolution;
  if (!kept || (!still_holds(base_key_, key, finest.resolution) && !add_finished(parts, key))) {
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
