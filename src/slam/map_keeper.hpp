#pragma once
// The maps a robot keeps: the map it localizes in (its own evidence, or own ⊕
// foreign once the swarm installed a richer one) and, once those differ, its
// own evidence apart, which is what it shares with others.
#include <cstddef>
#include <optional>
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/multires_map.hpp"
#include "sensor/laser_scan.hpp"
#include "sensor/scan_points.hpp"

namespace dsswarm {

struct InsertConfig {
  // Insert a matched scan into the map only when the robot has moved this much
  // since the last insertion: a robot standing still would otherwise pile
  // evidence from one viewpoint, making its noise look certain.
  double min_travel = 0.0;    // m
  double min_rotation = 0.0;  // rad

  void validate() const;  // throws ConfigError naming the field
};

class MapKeeper {
 public:
  MapKeeper(const MapConfig& map, const InsertConfig& insert) : map_(map), insert_(insert) {}
  // Continues in `initial` (a saved map, or evidence received from others).
  // Throws ConfigError when its resolution or levels differ from `map`'s.
  MapKeeper(const MapConfig& map, const InsertConfig& insert, MultiResMap initial);

  // Inserts the scan unless the robot has not moved enough since the last
  // insertion (InsertConfig); returns whether it did.
  bool insert(const Pose2& pose, const LaserScan& scan, const std::vector<ScanPoint>& points);

  const MultiResMap& map() const { return map_; }
  const MultiResMap& own_map() const { return own_map_ ? *own_map_ : map_; }
  void replace_working_map(MultiResMap working);
  std::size_t scans_inserted() const { return inserted_; }

 private:
  MultiResMap map_;                     // working map: own ⊕ foreign evidence
  std::optional<MultiResMap> own_map_;  // set once the working map holds foreign evidence
  InsertConfig insert_;
  std::optional<Pose2> last_insert_pose_;
  std::size_t inserted_ = 0;
};

}  // namespace dsswarm
