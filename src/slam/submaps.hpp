#pragma once
// Local SLAM's maps: the trajectory cut into submaps of consecutive scans.
// Each scan's evidence goes into exactly one submap, so combining submaps
// never counts a scan twice. A scan is matched against the local map: the
// previous submap ⊕ the current one until the current one is half full (so
// a new submap is never matched into empty; SubmapConfig::keep_previous),
// then the current one alone.
// Every `max_scans` scans or `max_travel` metres the current submap is
// finished (frozen, shared with the loop-closure search) and a new one begins.
//
// Every submap's cells are in the trajectory's local frame (the frame local
// SLAM runs in), so the local map is an exact cell-by-cell combination. A
// submap's anchor is the local pose of its first scan; the pose graph places
// it globally, and its cells then sit at global_anchor ⊕ anchor⁻¹.
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/frozen_map.hpp"
#include "grid/map_combine.hpp"
#include "grid/multires_map.hpp"
#include "sensor/laser_scan.hpp"
#include "sensor/scan_points.hpp"
#include "slam/executor.hpp"

namespace dsswarm {

struct InsertConfig {
  // Insert a matched scan into the map only when the robot has moved this much
  // since the last insertion: a robot standing still would otherwise pile
  // evidence from one viewpoint, making its noise look certain.
  double min_travel = 0.0;    // m
  double min_rotation = 0.0;  // rad

  void validate() const;  // throws ConfigError naming the field
};

struct SubmapConfig {
  // A submap is finished after this many scans or this much travel, whichever
  // comes first (0: no limit; both 0: one map that never finishes, as before
  // submaps: no loop closure then).
  int max_scans = 0;
  double max_travel = 0.0;  // m
  // The local map holds the previous submap too until the current one is
  // this full (a share of max_scans or max_travel): a young submap alone is
  // too sparse to match against, and every scan goes into both meanwhile.
  double keep_previous = 0.5;

  bool single_map() const { return max_scans == 0 && max_travel == 0.0; }
  void validate() const;  // throws ConfigError naming the field
};

struct Submap {
  int id = 0;
  Pose2 anchor;       // local pose of its first scan (identity for a given initial map)
  int scans = 0;      // scans inserted
  double travel = 0;  // m between its first and last scan
  bool finished = false;
  // The evidence of its scans only, cells in the local frame: a live map
  // while it grows, compact once finished.
  MultiResMap map;
  FrozenMap frozen;

  // Its evidence as a map (a finished one thawed: a copy).
  MultiResMap evidence(const MapConfig& config) const { return finished ? frozen.thaw(config) : map; }
};

class Submaps {
 public:
  Submaps(const MapConfig& map, const SubmapConfig& submaps, const InsertConfig& insert);
  // Starts from `initial` (a saved map): the first local map, and frozen as
  // submap 0 (anchor identity) when it is to be extended; `extend` false:
  // nothing will be inserted (localization only). Throws ConfigError when
  // its resolution or levels differ from the configuration's.
  void start_with(MultiResMap initial, bool extend);

  // Inserts the scan at `local_pose` unless the robot has not moved enough
  // since the last insertion (InsertConfig); returns the id of the submap it
  // went into, or nothing. Finishes the current submap when it is full.
  std::optional<int> insert(const Pose2& local_pose, const LaserScan& scan, const std::vector<ScanPoint>& points);

  // Finishes the growing submap and lets go of the live local map, so that
  // all that is left is compact (at the end of a run, before the global map
  // is composed). resume() brings the local map back to go on.
  void freeze();
  void resume();

  // What local SLAM matches against.
  const MultiResMap& local_map() const;
  // Finished submaps, oldest first; they never change again.
  const std::vector<std::shared_ptr<const Submap>>& finished() const { return finished_; }
  // The growing submap (no scan yet when a submap was just finished).
  const Submap& current() const { return *current_; }
  // Every submap so far (finished ones, then the current one if it holds a scan).
  std::vector<const Submap*> all() const;
  std::size_t scans_inserted() const { return inserted_; }
  std::size_t memory_bytes() const;

 private:
  void finish_current();

  MapConfig map_config_;
  SubmapConfig config_;
  InsertConfig insert_;
  std::vector<std::shared_ptr<const Submap>> finished_;
  std::unique_ptr<Submap> current_;
  std::optional<MultiResMap> local_;  // previous ⊕ current, while the current one is young
  bool frozen_ = false;
  std::optional<Pose2> last_insert_pose_;
  std::size_t inserted_ = 0;
};

// Combines one submap's evidence into `map` (Dempster's rule), its cells at
// `cells_pose`; within `band` only.
void add_submap(MultiResMap& map, const Submap& submap, const Pose2& cells_pose, const TileBand& band = {});

// Combines `submaps` into one map (Dempster's rule, in the order given),
// each one's cells placed at cells_pose(id): the global map. With `helper`,
// the map is built in two bands of tiles, one of them as a job on `helper`
// (then idle: the caller waits for it), the same map to the bit.
MultiResMap combine_submaps(const MapConfig& config, const std::vector<const Submap*>& submaps,
                            const std::function<Pose2(int)>& cells_pose, Executor* helper = nullptr);

}  // namespace dsswarm
