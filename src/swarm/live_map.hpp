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
// only the growing submap goes in afresh each time.
//
// Taken apart under the robot's lock (live_map_parts: shares the finished
// submaps and the layers, copies the growing submap) and composed on any
// thread (LiveMap), off the scan path.
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

class LiveMap {
 public:
  // finished submaps ⊕ foreign layers (by origin, as compose_working_map) ⊕
  // the growing submap, the finest level only. The first two are reused from
  // the last call when every submap, layer and pose is the same.
  MultiResMap compose(const LiveMapParts& parts);
  // How often the kept part had to be composed afresh.
  std::size_t base_compositions() const { return base_compositions_; }

 private:
  // What the kept part was composed from: per submap or piece its owner
  // ("" for this robot's own), id, version and pose.
  struct Entry {
    std::string origin;
    std::int64_t id = 0;
    std::uint64_t version = 0;
    Pose2 pose;
    bool operator==(const Entry& o) const {
      return origin == o.origin && id == o.id && version == o.version && same_pose(pose, o.pose);
    }
  };
  static std::vector<Entry> key_of(const LiveMapParts& parts);

  std::vector<Entry> base_key_;
  std::optional<MultiResMap> base_;
  std::size_t base_compositions_ = 0;
};

}  // namespace dsswarm
