#pragma once
// When a merge takes effect in the map a robot localizes in. A merged map is
// composed (own ⊕ the layers held) from the own map as it stood at the
// encounter's scan, and installed before the first scan `delay` seconds of
// log time after that one, with the scans inserted since replayed into it.
// In one process the encounter completes at once; a robot process composes
// off the scan path and its peer's placement and snapshot take a while to
// come. With the same scan as the moment of the swap, both paths localize
// the same scans in the same maps and their runs stay the same (a merge that
// is not ready in time takes effect when it is, counted as late).
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "grid/multires_map.hpp"
#include "swarm/map_snapshot.hpp"

namespace dsswarm {

class MergeSchedule {
 public:
  // What a merged map is composed from: pure data, composable on any thread.
  struct Job {
    std::shared_ptr<const MultiResMap> own;
    std::size_t own_version = 0;  // scans in `own`
    std::vector<MapLayer> foreign;
  };
  static MultiResMap compose(const Job& job);
  // A merged map due now, the scans since its own map replayed into it.
  struct Due {
    MultiResMap working;
    std::vector<LayerVersion> layers;      // the foreign layers it holds
    std::vector<std::uint64_t> encounters; // whose merges it brings in
    bool late = false;                     // a scan went by while it was due but not ready
  };

  explicit MergeSchedule(double delay = 0.0) : delay_(delay) {}
  double delay() const { return delay_; }

  // Every scan inserted into the own map (version: scans in it after this one).
  // Kept as long as a job may still start from before it; keeps_scans()
  // false: none is (merges at once, none pending), so the caller may skip it.
  bool keeps_scans() const { return delay_ > 0.0 || !entries_.empty(); }
  void inserted(std::size_t version, double stamp, const Pose2& pose, const Pose2& laser_offset,
                std::vector<ScanPoint> points);
  // Whether a job may start from the own map at `version` (current: the own
  // map's version now): every scan since is kept for replaying.
  bool replays_from(std::size_t version, std::size_t current) const;

  // A merge found at the encounter's scan, taken at `view_stamp`.
  void add(Job job, double view_stamp, std::uint64_t encounter);
  bool empty() const { return entries_.empty(); }

  // The composer's side: the oldest job nobody composes yet, and its result.
  struct Claimed {
    std::uint64_t ticket = 0;
    std::uint64_t encounter = 0;
    Job job;
  };
  std::optional<Claimed> claim();
  bool has_unclaimed() const;
  void composed(std::uint64_t ticket, MultiResMap working);

  // The newest merge due before a scan at `stamp` (its older ones it holds
  // already). `compose_here`: compose one not composed yet now (one process);
  // otherwise only one the composer has finished is taken.
  std::optional<Due> take_due(double stamp, bool compose_here);

 private:
  struct Inserted {
    std::size_t version = 0;
    double stamp = 0.0;
    Pose2 pose;
    Pose2 laser_offset;
    std::vector<ScanPoint> points;
  };
  struct Entry {
    std::uint64_t ticket = 0;
    Job job;
    double due = 0.0;
    std::uint64_t encounter = 0;
    std::optional<MultiResMap> working;
    bool claimed = false;
    bool missed = false;
  };
  void prune();

  double delay_;
  std::deque<Inserted> inserted_;
  double newest_stamp_ = 0.0;
  std::deque<Entry> entries_;
  std::uint64_t next_ticket_ = 1;
};

}  // namespace dsswarm
