#include "grid/multires_map.hpp"

#include <array>
#include <bit>
#include <limits>
#include <memory>
#include <string>

#include "common/errors.hpp"
#include "grid/ray_traversal.hpp"
#include "grid/sampling.hpp"

namespace dsswarm {

void MapConfig::validate() const {
  if (!(resolution >= 0.005 && resolution <= 2.0)) throw ConfigError("map.resolution must be in [0.005, 2] m");
  if (levels < 1 || levels > 6) throw ConfigError("map.levels must be in [1, 6]");
  if (!(free_margin_cells >= 0.0 && free_margin_cells <= 10.0))
    throw ConfigError("map.free_margin_cells must be in [0, 10]");
  evidence.validate();
}

namespace {

// The state repeated passes reach from a vacuous cell, if they reach one that
// a pass leaves unchanged (the discount holds free mass below 1, so they do
// within a few hundred); otherwise a state no cell holds (occupied + free > 1).
PackedMass pass_fixed_point(const EvidenceModel& ev) {
  constexpr int kMaxPasses = 100000;
  PackedMass s{};
  for (int i = 0; i < kMaxPasses; ++i) {
    const PackedMass next = PackedMass::pack_valid(ev.update_passed(s.unguarded_mass()));
    if (next == s) return s;
    s = next;
  }
  return {65535, 65535};
}

// EvidenceModel::passed_free of every stored free mass: insertion's update
// of open space becomes one read. Shared by all maps of one model (the
// default one's is built once per process).
std::shared_ptr<const std::vector<std::uint16_t>> passed_free_table(const EvidenceModel& ev) {
  const auto build = [](const EvidenceModel& model) {
    auto table = std::make_shared<std::vector<std::uint16_t>>(std::size_t{65536});
    for (std::size_t f = 0; f < table->size(); ++f) (*table)[f] = model.passed_free(static_cast<std::uint16_t>(f));
    return std::shared_ptr<const std::vector<std::uint16_t>>(std::move(table));
  };
  static const auto kDefault = build(EvidenceModel{});
  const EvidenceModel d;
  return ev.pass_free == d.pass_free && ev.min_unknown == d.min_unknown ? kDefault : build(ev);
}

}  // namespace

MultiResMap::MultiResMap(const MapConfig& config) : config_(config) {
  config_.validate();
  passed_free_ = passed_free_table(config_.evidence);
  pass_fixed_point_ = pass_fixed_point(config_.evidence);
  double res = config_.resolution;
  for (int i = 0; i < config_.levels; ++i, res *= 2.0) grids_.emplace_back(res);
}

void MultiResMap::insert_scan(const Pose2& robot_pose, const Pose2& laser_in_base,
                              const std::vector<ScanPoint>& points) {
  MultiResMap* self[] = {this};
  insert_scan(self, robot_pose, laser_in_base, points);
}

namespace {

// Updates one level's cell in every map at once, keeping each map's current
// tile: a beam crosses dozens of cells of one tile before it needs the next,
// so most cells cost no tile lookup.
class LevelWriter {
 public:
  LevelWriter(std::span<MultiResMap* const> maps, std::size_t level) : cells_(maps.size(), nullptr) {
    for (MultiResMap* m : maps) grids_.push_back(&m->mutable_level(static_cast<int>(level)));
  }

  template <class Update>
  void apply(CellIndex c, Update&& update) {
    select_tile(c);
    const int i = DsGrid::local_index(c);
    for (PackedMass* cells : cells_) cells[i] = PackedMass::pack_valid(update(cells[i].unguarded_mass()));
  }

 private:
  void select_tile(CellIndex c) {
    const std::int32_t tx = c.x >> DsGrid::kTileBits, ty = c.y >> DsGrid::kTileBits;
    if (tx != tile_x_ || ty != tile_y_) {
      for (std::size_t k = 0; k < grids_.size(); ++k) cells_[k] = grids_[k]->mutable_tile_cells(c);
      tile_x_ = tx;
      tile_y_ = ty;
    }
  }

  std::vector<DsGrid*> grids_;
  std::vector<PackedMass*> cells_;  // the current tile's cells, per map
  // No tile yet: no cell's tile coordinate is this low.
  std::int32_t tile_x_ = std::numeric_limits<std::int32_t>::min(), tile_y_ = tile_x_;
};

// Hits written a run at a time: consecutive hits that land on the same 2×2
// block of cells (the same cell, for unspread hits) combine first, and the
// block is written once per run. Pure occupied masses s combine by Dempster's
// rule to 1 − Π(1 − s) (no conflict), and the rule is associative, so a cell
// ends where writing each hit in turn would leave it, up to rounding and the
// discount on near-certain cells. Along a wall near the lidar several hits
// fall in one cell.
class HitRuns {
 public:
  HitRuns(LevelWriter& writer, const EvidenceModel& ev) : writer_(writer), ev_(ev) {}
  // A hit's occupied mass on each cell of the block with lower-left `corner` (DsGrid::quad order).
  void add(CellIndex corner, const std::array<float, 4>& shares) {
    if (open_ && corner != corner_) flush();
    corner_ = corner;
    open_ = true;
    for (std::size_t k = 0; k < 4; ++k) kept_[k] *= 1.0f - shares[k];
  }
  void flush() {
    if (!open_) return;
    const CellIndex c = corner_;
    const CellIndex cells[4] = {c, {c.x + 1, c.y}, {c.x, c.y + 1}, {c.x + 1, c.y + 1}};
    for (std::size_t k = 0; k < 4; ++k) {
      if (kept_[k] >= 1.0f) continue;
      const DsMass run{1.0f - kept_[k], 0.0f};
      writer_.apply(cells[k], [&](const DsMass& m) { return ev_.update(m, run); });
    }
    kept_ = {1.0f, 1.0f, 1.0f, 1.0f};
    open_ = false;
  }

 private:
  LevelWriter& writer_;
  const EvidenceModel& ev_;
  CellIndex corner_{};
  std::array<float, 4> kept_{1.0f, 1.0f, 1.0f, 1.0f};  // Π(1 − s) per cell of the run
  bool open_ = false;
};

// A beam's pass, apply(c, update_passed), in N maps at once, minus the cells
// it leaves as they are. N is fixed at compile time so that the current
// tiles stay in registers: every free cell of every beam comes through here.
template <std::size_t N>
class PassWriter {
 public:
  PassWriter(std::span<MultiResMap* const> maps, int level, const std::uint16_t* passed_free, PackedMass fixed_point)
      : ev_(maps.front()->config().evidence),
        passed_free_(passed_free),
        fixed_point_(std::bit_cast<std::uint32_t>(fixed_point)) {
    for (std::size_t k = 0; k < N; ++k) grids_[k] = &maps[k]->mutable_level(level);
  }
  void enter_tile(CellIndex c) {
    for (std::size_t k = 0; k < N; ++k) cells_[k] = grids_[k]->mutable_tile_cells(c);
  }
  // Cell `i` (local_index) of the tile last entered.
  void pass(int i) {
    for (std::size_t k = 0; k < N; ++k) {
      PackedMass& cell = cells_[k][i];
      if (std::bit_cast<std::uint32_t>(cell) == fixed_point_) continue;
      if (cell.occupied == 0) cell.free = passed_free_[cell.free];
      else cell = PackedMass::pack_valid(ev_.update_passed(cell.unguarded_mass()));
    }
  }

 private:
  const EvidenceModel& ev_;
  const std::uint16_t* passed_free_;  // EvidenceModel::passed_free of every free mass
  std::uint32_t fixed_point_;         // the stored cell a pass leaves as it is
  std::array<DsGrid*, N> grids_{};
  std::array<PackedMass*, N> cells_{};
};

// Free evidence along every beam into one level of N maps.
template <std::size_t N>
void pass_beams(std::span<MultiResMap* const> maps, int level, const Eigen::Vector2d& origin,
                const std::vector<Eigen::Vector2d>& hits, double margin, const std::uint16_t* passed_free,
                PackedMass fixed_point) {
  PassWriter<N> writer(maps, level, passed_free, fixed_point);
  const double resolution = maps.front()->level(level).resolution();
  for (const Eigen::Vector2d& h : hits) {
    const Eigen::Vector2d beam = h - origin;
    const double length = beam.norm();
    if (length <= margin) continue;
    // traverse_ray leaves out the cell holding its end, so the hit's own
    // cell never gets free evidence, whatever the margin.
    const Eigen::Vector2d end = margin > 0.0 ? Eigen::Vector2d(origin + beam * ((length - margin) / length)) : h;
    traverse_ray_by_tile(
        origin, end, resolution, [&](CellIndex c) { writer.enter_tile(c); }, [&](int i) { writer.pass(i); });
  }
}

// Neighbouring returns closer than `surface_gap` lie on one surface: the
// cells between them get (weak) occupied evidence too. Otherwise a wall seen
// at a grazing angle is a dotted line whose dots sit exactly where this
// viewpoint's beams ended, and the next scan, taken a few centimetres
// further on, fits the map best by pretending not to have moved.
void join_surfaces(LevelWriter& writer, const DsGrid& grid, const MapConfig& config, const Eigen::Vector2d& origin,
                   const std::vector<Eigen::Vector2d>& hits) {
  const EvidenceModel& ev = config.evidence;
  const DsMass between_hits{ev.hit().occupied * config.surface_mass_factor, 0.0f};
  for (std::size_t i = 1; i < hits.size(); ++i) {
    const Eigen::Vector2d segment = hits[i] - hits[i - 1];
    const double length = segment.norm();
    if (length > config.surface_gap || length == 0.0) continue;
    // A segment running almost along the beams is a depth jump (a chair
    // leg in front of a wall), not a surface: joining it would draw a
    // phantom wall towards the robot.
    const Eigen::Vector2d beam = (0.5 * (hits[i] + hits[i - 1]) - origin).normalized();
    if (std::abs(beam.dot(segment) / length) > config.surface_max_cos) continue;
    const CellIndex end = grid.cell_of(hits[i]);
    traverse_ray(hits[i - 1], hits[i], grid.resolution(), [&](CellIndex c) {
      if (c == end) return;
      writer.apply(c, [&](const DsMass& m) { return ev.update(m, between_hits); });
    });
  }
}

// The hits' occupied evidence, on their cells or (`splat`) spread over the
// four nearest.
void write_hits(LevelWriter& writer, const DsGrid& grid, const EvidenceModel& ev,
                const std::vector<Eigen::Vector2d>& hits, bool splat) {
  const DsMass hit = ev.hit();
  HitRuns runs(writer, ev);
  for (const Eigen::Vector2d& h : hits) {
    if (!splat) {
      runs.add(grid.cell_of(h), {hit.occupied, 0.0f, 0.0f, 0.0f});
      continue;
    }
    // Bilinear weights: the scorer reads cells back with bilinear
    // interpolation, so a hit seen through both is a tent centred exactly on
    // its point: coarse cells no longer pull scans towards their centres (a
    // bias of up to half a cell, the same for every wall of one orientation).
    const BilinearPoint b = bilinear_point(h.x(), h.y(), 1.0 / grid.resolution());
    std::array<float, 4> shares = b.weights();
    for (float& w : shares) w *= hit.occupied;
    runs.add(b.corner, shares);
  }
  runs.flush();
}

}  // namespace

void MultiResMap::insert_scan(std::span<MultiResMap* const> maps, const Pose2& robot_pose, const Pose2& laser_in_base,
                              const std::vector<ScanPoint>& points) {
  if (maps.empty()) return;
  const MapConfig& config = maps.front()->config_;
  for (MultiResMap* m : maps)
    if (m->config_.resolution != config.resolution || m->levels() != maps.front()->levels())
      throw ConfigError("MultiResMap::insert_scan: the maps differ in resolution or levels");
  const Pose2 laser = robot_pose * laser_in_base;
  const Eigen::Vector2d origin = laser.translation();
  std::vector<Eigen::Vector2d> hits;
  hits.reserve(points.size());
  const PointTransform to_world(robot_pose);
  for (const ScanPoint& p : points) hits.push_back(to_world(p.x, p.y));

  const PackedMass fixed_point = maps.front()->pass_fixed_point_;
  const std::uint16_t* passed_free = maps.front()->passed_free_->data();
  for (std::size_t level = 0; level < maps.front()->grids_.size(); ++level) {
    const DsGrid& grid = maps.front()->grids_[level];
    LevelWriter writer(maps, level);
    // Free evidence first, hits last: a cell that one beam ends in and a
    // neighbouring grazing beam passes through keeps its hit for this scan.
    // Coarse levels take hits only: a 20 cm cell holding a wall is also
    // crossed by grazing beams, and free evidence would erode the very cells
    // that guide the coarse search (see MapConfig::free_space_on_coarse_levels).
    if (level == 0 || config.free_space_on_coarse_levels) {
      const double margin = config.free_margin_cells * grid.resolution();
      // Local SLAM writes one map or two; more are written one at a time.
      const int l = static_cast<int>(level);
      if (maps.size() == 2) pass_beams<2>(maps, l, origin, hits, margin, passed_free, fixed_point);
      else
        for (std::size_t k = 0; k < maps.size(); ++k)
          pass_beams<1>(maps.subspan(k, 1), l, origin, hits, margin, passed_free, fixed_point);
    }
    const bool splat = level > 0 || config.splat_fine_hits;
    if (!splat && config.surface_gap > 0.0) join_surfaces(writer, grid, config, origin, hits);
    write_hits(writer, grid, config.evidence, hits, splat);
  }
}

std::size_t MultiResMap::cells_allocated() const {
  std::size_t n = 0;
  for (const auto& g : grids_) n += g.cells_allocated();
  return n;
}

std::size_t MultiResMap::memory_bytes() const {
  std::size_t n = 0;
  for (const auto& g : grids_) n += g.memory_bytes();
  return n;
}

}  // namespace dsswarm
