#pragma once
// The map a robot shows while it runs (`/map`) with loop closure on: its own
// submaps at the poses its pose graph gives them now ⊕ what it holds of the
// other robots, at their frames now. So the picture follows every loop
// closure and every `Moved` word, not only the next merge.
//
// Composing all submaps afresh costs as much as all of them together, about
// once a second. Most of it rarely changes: the finished submaps and the
// other robots' layers move only when a round moves them, a submap finishes
// or a layer arrives. That part is kept and reused while it stays the same;
// only the growing submap goes in afresh each time, and a submap finished
// since is added to the kept part. A pose-graph round moves every submap a
// little; a move that shifts no cell by more than a fraction of a cell
// (LiveMapConfig) keeps the part as it was composed.
//
// Taken apart under the robot's lock (live_map_parts: shares the finished
// submaps and the layers, copies the growing submap) and composed on any
// thread (LiveMap), off the scan path.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "slam/slam.hpp"
#include "swarm/map_snapshot.hpp"

namespace dsswarm {

struct LiveMapParts {
  MapConfig config;
  std::vector<std::shared_ptr<const Submap>> finished;  // oldest first
  std::vector<Pose2> finished_poses;                    // where each one's cells lie now
  std::optional<Submap> growing;                        // a copy: the scan thread goes on filling it
  Pose2 growing_pose;
  std::vector<MapLayer> foreign;  // the other robots' layers, at their frames now
};

// `slam`'s submaps as its graph places them now, and `foreign` (MapKnowledge's layers).
LiveMapParts live_map_parts(const Slam& slam, const std::vector<MapLayer>& foreign);

struct LiveMapConfig {
  // The kept part is composed again when a submap or layer has moved so far
  // that some of its cells would lie more than this many cells from where
  // the kept part has them (0: on every move). Under a cell, a picture does
  // not show it; the error never adds up, as it is measured from the poses
  // the kept part was composed at.
  double redraw_cells = 0.5;

  void validate() const;  // throws ConfigError naming the field
};

class LiveMap {
 public:
  explicit LiveMap(const LiveMapConfig& config = {});
  // finished submaps ⊕ foreign layers (by origin, as compose_working_map) ⊕
  // the growing submap, the finest level only. The first two are reused from
  // the last call while they are the same submaps and layers, none of them
  // moved beyond LiveMapConfig::redraw_cells.
  MultiResMap compose(const LiveMapParts& parts);
  // How often the kept part had to be composed afresh, and how often it
  // only took submaps this robot had finished since.
  std::size_t base_compositions() const { return base_compositions_; }
  std::size_t base_additions() const { return base_additions_; }

 private:
  // What the kept part was composed from: per submap, layer map or piece its
  // owner ("" for this robot's own), id (-1: a layer's map), version, where
  // its cells lie in this robot's frame, and the extent of its cells (a
  // circle in its own cells' frame) that bounds how far any of them moved.
  struct Entry {
    std::string origin;
    std::int64_t id = 0;
    std::uint64_t version = 0;
    Pose2 pose;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    double reach = 0.0;  // m
  };
  static std::vector<Entry> key_of(const LiveMapParts& parts);
  // Whether a part composed at `kept` still stands for `now`.
  bool still_holds(const std::vector<Entry>& kept, const std::vector<Entry>& now, double resolution) const;
  // Adds to the kept part the submaps finished since, when nothing else in
  // it changed; false when it must be composed afresh.
  bool add_finished(const LiveMapParts& parts, const std::vector<Entry>& key);

  LiveMapConfig config_;
  std::vector<Entry> base_key_;
  std::optional<MultiResMap> base_;
  std::size_t base_compositions_ = 0;
  std::size_t base_additions_ = 0;
};

}  // namespace dsswarm
