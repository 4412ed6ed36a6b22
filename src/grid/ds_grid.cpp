#include "grid/ds_grid.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace dsswarm {

DsGrid::DsGrid(double resolution) : resolution_(resolution), inv_resolution_(1.0 / resolution) {}

DsGrid::DsGrid(const DsGrid& other)
    : resolution_(other.resolution_),
      inv_resolution_(other.inv_resolution_),
      table_(other.table_.size(), nullptr),
      table_origin_(other.table_origin_),
      table_width_(other.table_width_),
      table_height_(other.table_height_) {
  tiles_.reserve(other.tiles_.size());
  for (const auto& t : other.tiles_) {
    tiles_.push_back(std::make_unique<Tile>(*t));
    const std::int32_t x = (t->origin.x >> kTileBits) - table_origin_.x, y = (t->origin.y >> kTileBits) - table_origin_.y;
    table_[static_cast<std::size_t>(y) * table_width_ + x] = tiles_.back().get();
  }
}

DsGrid& DsGrid::operator=(const DsGrid& other) {
  if (this != &other) *this = DsGrid(other);
  return *this;
}

DsGrid::Tile*& DsGrid::slot_of(std::int32_t tx, std::int32_t ty) {
  std::int32_t lx = tx - table_origin_.x, ly = ty - table_origin_.y;
  if (lx < 0 || ly < 0 || lx >= table_width_ || ly >= table_height_) {
    grow_table_to_include(tx, ty);
    lx = tx - table_origin_.x;
    ly = ty - table_origin_.y;
  }
  return table_[static_cast<std::size_t>(ly) * table_width_ + lx];
}

DsGrid::Tile& DsGrid::get_or_create_tile(CellIndex c) {
  const std::int32_t tx = c.x >> kTileBits, ty = c.y >> kTileBits;
  Tile*& slot = slot_of(tx, ty);
  if (!slot) {
    auto tile = std::make_unique<Tile>();
    tile->origin = {tx << kTileBits, ty << kTileBits};
    slot = tile.get();
    tiles_.push_back(std::move(tile));
  }
  return *slot;
}

void DsGrid::grow_table_to_include(std::int32_t tx, std::int32_t ty) {
  // New extent: the old one plus the requested tile, with slack on every side
  // so that a robot driving steadily in one direction triggers O(log n) regrowths.
  std::int32_t min_x = tx, min_y = ty, max_x = tx + 1, max_y = ty + 1;
  if (table_width_ > 0) {
    min_x = std::min(min_x, table_origin_.x);
    min_y = std::min(min_y, table_origin_.y);
    max_x = std::max(max_x, table_origin_.x + table_width_);
    max_y = std::max(max_y, table_origin_.y + table_height_);
  }
  const std::int32_t slack_x = std::max<std::int32_t>(4, (max_x - min_x) / 2);
  const std::int32_t slack_y = std::max<std::int32_t>(4, (max_y - min_y) / 2);
  if (tx < table_origin_.x || table_width_ == 0) min_x -= slack_x;
  if (ty < table_origin_.y || table_height_ == 0) min_y -= slack_y;
  if (tx >= table_origin_.x + table_width_ || table_width_ == 0) max_x += slack_x;
  if (ty >= table_origin_.y + table_height_ || table_height_ == 0) max_y += slack_y;

  std::vector<Tile*> table(static_cast<std::size_t>(max_x - min_x) * (max_y - min_y), nullptr);
  for (const auto& t : tiles_) {
    const std::int32_t x = (t->origin.x >> kTileBits) - min_x, y = (t->origin.y >> kTileBits) - min_y;
    table[static_cast<std::size_t>(y) * (max_x - min_x) + x] = t.get();
  }
  table_ = std::move(table);
  table_origin_ = {min_x, min_y};
  table_width_ = max_x - min_x;
  table_height_ = max_y - min_y;
}

std::size_t DsGrid::memory_bytes() const {
  return tiles_.size() * sizeof(Tile) + tiles_.capacity() * sizeof(std::unique_ptr<Tile>) +
         table_.capacity() * sizeof(Tile*);
}

void DsGrid::absorb(DsGrid&& other) {
  if (other.resolution_ != resolution_) throw std::logic_error("DsGrid::absorb: resolutions differ");
  for (auto& tile : other.tiles_) {
    Tile*& slot = slot_of(tile->origin.x >> kTileBits, tile->origin.y >> kTileBits);
    if (slot) throw std::logic_error("DsGrid::absorb: a tile is in both grids");
    slot = tile.get();
    tiles_.push_back(std::move(tile));
  }
  other = DsGrid(resolution_);
}

void DsGrid::bounds(CellIndex& min, CellIndex& max) const {
  if (tiles_.empty()) {
    min = max = {0, 0};
    return;
  }
  min = {std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max()};
  max = {std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::min()};
  for (const auto& t : tiles_) {
    min.x = std::min(min.x, t->origin.x);
    min.y = std::min(min.y, t->origin.y);
    max.x = std::max(max.x, t->origin.x + kTileSize);
    max.y = std::max(max.y, t->origin.y + kTileSize);
  }
}

GridRaster DsGrid::to_raster(int margin) const {
  GridRaster r;
  r.resolution = resolution_;
  if (tiles_.empty()) return r;
  // Tighten the tile bounds to cells that hold any evidence.
  CellIndex lo{std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max()};
  CellIndex hi{std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::min()};
  for (const auto& t : tiles_) {
    for (int i = 0; i < kTileCells; ++i) {
      if (t->cells[i].vacuous()) continue;
      const CellIndex c = tile_cell(t->origin, i);
      const std::int32_t x = c.x, y = c.y;
      lo = {std::min(lo.x, x), std::min(lo.y, y)};
      hi = {std::max(hi.x, x), std::max(hi.y, y)};
    }
  }
  if (lo.x > hi.x) return r;  // allocated but no evidence
  lo = {lo.x - margin, lo.y - margin};
  hi = {hi.x + margin, hi.y + margin};
  r.width = hi.x - lo.x + 1;
  r.height = hi.y - lo.y + 1;
  r.origin = {lo.x * resolution_, lo.y * resolution_};
  r.cells.assign(static_cast<std::size_t>(r.width) * r.height, DsMass::vacuous());
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x) r.cells[static_cast<std::size_t>(y) * r.width + x] = at({lo.x + x, lo.y + y});
  return r;
}

bool DsGrid::holds_evidence() const {
  return std::any_of(tiles_.begin(), tiles_.end(), [](const std::unique_ptr<Tile>& t) {
    return std::any_of(t->cells.begin(), t->cells.end(), [](PackedMass m) { return !m.vacuous(); });
  });
}

}  // namespace dsswarm
