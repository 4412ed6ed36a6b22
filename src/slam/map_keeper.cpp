#include "slam/map_keeper.hpp"

#include <cmath>
#include <string>

#include "common/errors.hpp"

namespace dsswarm {

void InsertConfig::validate() const {
  if (min_travel < 0.0 || min_rotation < 0.0)
    throw ConfigError("slam.insert_min_travel and insert_min_rotation must be >= 0");
}

MapKeeper::MapKeeper(const MapConfig& map, const InsertConfig& insert, MultiResMap initial)
    : MapKeeper(map, insert) {
  if (initial.config().resolution != map.resolution || initial.levels() != map.levels)
    throw ConfigError("the initial map's resolution/levels (" + std::to_string(initial.config().resolution) + " m, " +
                      std::to_string(initial.levels()) + ") differ from map.resolution/map.levels (" +
                      std::to_string(map.resolution) + " m, " + std::to_string(map.levels) + ")");
  map_ = std::move(initial);
}

void MapKeeper::replace_working_map(MultiResMap working) {
  if (working.config().resolution != map_.config().resolution || working.levels() != map_.levels())
    throw ConfigError("replace_working_map: the map's resolution/levels differ from this robot's");
  if (!own_map_) own_map_ = std::move(map_);
  map_ = std::move(working);
}

bool MapKeeper::insert(const Pose2& pose, const LaserScan& scan, const std::vector<ScanPoint>& points) {
  if (last_insert_pose_) {
    const Pose2 d = between(*last_insert_pose_, pose);
    if (std::hypot(d.x, d.y) < insert_.min_travel && std::abs(d.theta) < insert_.min_rotation) return false;
  }
  map_.insert_scan(pose, scan.laser_offset, points);
  if (own_map_) own_map_->insert_scan(pose, scan.laser_offset, points);
  last_insert_pose_ = pose;
  ++inserted_;
  return true;
}

}  // namespace dsswarm
