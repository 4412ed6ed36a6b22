#include "slam/submaps.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <string>

#include "common/errors.hpp"
#include "grid/map_combine.hpp"

namespace dsswarm {

void InsertConfig::validate() const {
  if (min_travel < 0.0 || min_rotation < 0.0)
    throw ConfigError("slam.insert_min_travel and insert_min_rotation must be >= 0");
}

void SubmapConfig::validate() const {
  if (max_scans < 0) throw ConfigError("submaps.max_scans must be >= 0");
  if (!(max_travel >= 0.0)) throw ConfigError("submaps.max_travel must be >= 0");
  if (!(keep_previous >= 0.0 && keep_previous <= 1.0)) throw ConfigError("submaps.keep_previous must be in [0, 1]");
}

Submaps::Submaps(const MapConfig& map, const SubmapConfig& submaps, const InsertConfig& insert)
    : map_config_(map), config_(submaps), insert_(insert), current_(std::make_unique<Submap>()) {
  current_->map = MultiResMap(map_config_);
}

void Submaps::start_with(MultiResMap initial, bool extend) {
  if (initial.config().resolution != map_config_.resolution || initial.levels() != map_config_.levels)
    throw ConfigError("the initial map's resolution/levels (" + std::to_string(initial.config().resolution) + " m, " +
                      std::to_string(initial.levels()) + ") differ from map.resolution/map.levels (" +
                      std::to_string(map_config_.resolution) + " m, " + std::to_string(map_config_.levels) + ")");
  if (extend) {  // kept as submap 0, the first part of the global map
    auto given = std::make_shared<Submap>();
    given->finished = true;
    given->frozen = FrozenMap(initial);
    finished_ = {given};
  }
  local_ = std::move(initial);  // matched against as it is
  current_ = std::make_unique<Submap>();
  current_->id = 1;
  current_->map = MultiResMap(map_config_);
}

std::optional<int> Submaps::insert(const Pose2& local_pose, const LaserScan& scan,
                                   const std::vector<ScanPoint>& points) {
  double step = 0.0;
  if (last_insert_pose_) {
    const Pose2 d = between(*last_insert_pose_, local_pose);
    if (std::hypot(d.x, d.y) < insert_.min_travel && std::abs(d.theta) < insert_.min_rotation) return std::nullopt;
    step = std::hypot(d.x, d.y);
  }
  Submap& s = *current_;
  if (s.scans == 0) s.anchor = local_pose;
  else s.travel += step;
  if (local_) {
    MultiResMap* both[] = {&s.map, &*local_};
    MultiResMap::insert_scan(both, local_pose, scan.laser_offset, points);
  } else {
    s.map.insert_scan(local_pose, scan.laser_offset, points);
  }
  ++s.scans;
  last_insert_pose_ = local_pose;
  ++inserted_;
  const int id = s.id;
  const auto reached = [&](double fraction) {
    return (config_.max_scans > 0 && s.scans >= fraction * config_.max_scans) ||
           (config_.max_travel > 0.0 && s.travel >= fraction * config_.max_travel);
  };
  // Part-way through a submap its own evidence carries local SLAM: the
  // previous one is let go (half the insertion work and memory from here on).
  if (local_ && reached(config_.keep_previous)) local_.reset();
  if (reached(1.0)) finish_current();
  return id;
}

void Submaps::finish_current() {
  current_->finished = true;
  current_->frozen = FrozenMap(current_->map);
  // The new submap is matched against this one until it has evidence of its own.
  local_ = std::move(current_->map);
  current_->map = MultiResMap(map_config_);
  std::shared_ptr<const Submap> done(current_.release());
  finished_.push_back(done);
  current_ = std::make_unique<Submap>();
  current_->id = done->id + 1;
  current_->map = MultiResMap(map_config_);
}

void Submaps::freeze() {
  if (config_.single_map()) return;  // the one live map is the map
  if (current_->scans > 0) finish_current();
  if (finished_.empty()) return;  // nothing but the (empty) current map
  local_.reset();
  frozen_ = true;
}

void Submaps::resume() {
  if (!frozen_) return;
  local_ = finished_.back()->frozen.thaw(map_config_);
  frozen_ = false;
}

const MultiResMap& Submaps::local_map() const {
  return local_ ? *local_ : current_->map;
}

std::vector<const Submap*> Submaps::all() const {
  std::vector<const Submap*> out;
  for (const auto& s : finished_) out.push_back(s.get());
  if (current_->scans > 0) out.push_back(current_.get());
  return out;
}

std::size_t Submaps::memory_bytes() const {
  std::size_t n = current_->map.memory_bytes() + (local_ ? local_->memory_bytes() : 0);
  for (const auto& s : finished_) n += s->frozen.memory_bytes();
  return n;
}

namespace {

// Where a submap's cells lie along the global y axis (metres), and how wide
// they spread along x: enough to split the composition's work in two and to
// skip a submap in a band it cannot reach.
struct Extent {
  double lo = 0.0, hi = 0.0, width = 0.0;
  bool empty = true;
};

Extent extent_of(const Submap& s, const Pose2& pose, double resolution) {
  CellIndex lo, hi;
  if (s.finished)
    s.frozen.bounds(lo, hi);
  else
    s.map.finest().bounds(lo, hi);
  if (lo == hi) return {};
  Extent e{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0.0, false};
  double x_lo = e.lo, x_hi = e.hi;
  for (int corner = 0; corner < 4; ++corner) {
    const Eigen::Vector2d q =
        pose * Eigen::Vector2d((corner & 1 ? hi.x : lo.x) * resolution, (corner & 2 ? hi.y : lo.y) * resolution);
    e.lo = std::min(e.lo, q.y());
    e.hi = std::max(e.hi, q.y());
    x_lo = std::min(x_lo, q.x());
    x_hi = std::max(x_hi, q.x());
  }
  e.width = x_hi - x_lo;
  return e;
}

// The y that splits the submaps' placed area in halves: each band then has
// about half the cells to resample.
double balanced_split(const std::vector<Extent>& extents) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, total = 0.0;
  for (const Extent& e : extents) {
    if (e.empty) continue;
    lo = std::min(lo, e.lo);
    hi = std::max(hi, e.hi);
    total += e.width * (e.hi - e.lo);
  }
  if (!(lo < hi)) return 0.0;
  const auto below = [&](double y) {
    double area = 0.0;
    for (const Extent& e : extents)
      if (!e.empty) area += e.width * std::clamp(y - e.lo, 0.0, e.hi - e.lo);
    return area;
  };
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (below(mid) < 0.5 * total ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Combines the submaps into `map`, in order, writing the target tiles of
// `band` only; a submap that cannot reach the band is not even thawed.
void combine_band(MultiResMap& map, const MapConfig& config, const std::vector<const Submap*>& submaps,
                  const std::vector<Pose2>& poses, const std::vector<Extent>& extents, const TileBand& band) {
  // A level's tile rows start up to a tile below the cells they hold, and a
  // coarse level's evidence reaches a few of its cells past the finest's.
  const double coarsest = config.resolution * static_cast<double>(1 << (config.levels - 1));
  const double margin = (DsGrid::kTileSize + 4) * coarsest;
  for (std::size_t i = 0; i < submaps.size(); ++i) {
    const Extent& e = extents[i];
    if (!e.empty && (e.hi + margin < band.from || e.lo - margin >= band.to)) continue;
    add_submap(map, *submaps[i], poses[i], band);
  }
}

}  // namespace

void add_submap(MultiResMap& map, const Submap& submap, const Pose2& cells_pose, const TileBand& band) {
  const MultiResMap thawed = submap.finished ? submap.frozen.thaw(map.config()) : MultiResMap();
  const MultiResMap& cells = submap.finished ? thawed : submap.map;
  if (is_identity(cells_pose))
    combine_aligned(map, cells, band);
  else
    combine_into(map, cells, cells_pose, band);
}

MultiResMap combine_submaps(const MapConfig& config, const std::vector<const Submap*>& submaps,
                            const std::function<Pose2(int)>& cells_pose, Executor* helper) {
  std::vector<Pose2> poses;
  std::vector<Extent> extents;
  for (const Submap* s : submaps) {
    poses.push_back(cells_pose(s->id));
    extents.push_back(extent_of(*s, poses.back(), config.resolution));
  }
  MultiResMap map(config);
  if (!helper || submaps.size() < 2) {
    combine_band(map, config, submaps, poses, extents, {});
    return map;
  }
  const double split = balanced_split(extents);
  MultiResMap upper(config);
  std::exception_ptr failed;
  const std::uint64_t ticket = helper->submit([&] {
    try {
      combine_band(upper, config, submaps, poses, extents, {split, std::numeric_limits<double>::infinity()});
    } catch (...) {
      failed = std::current_exception();
    }
  });
  try {
    combine_band(map, config, submaps, poses, extents, {-std::numeric_limits<double>::infinity(), split});
  } catch (...) {
    helper->wait_for(ticket);  // the job uses this frame's data
    throw;
  }
  helper->wait_for(ticket);
  if (failed) std::rethrow_exception(failed);
  for (int level = 0; level < map.levels(); ++level)
    map.mutable_level(level).absorb(std::move(upper.mutable_level(level)));
  return map;
}

}  // namespace dsswarm
