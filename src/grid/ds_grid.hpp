#pragma once
// An unbounded 2D grid of Dempster–Shafer cells at one resolution.
//
// Cells live in square tiles of kTileSize² allocated on first write, so the
// map grows in any direction from the start and unexplored space costs one
// null pointer per tile. Tiles are found through a dense table of pointers
// that is re-centred and doubled when a write falls outside it: a lookup is
// two array reads, which matters because the matcher does millions per second.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "grid/ds_mass.hpp"
#include "grid/grid_raster.hpp"

namespace dsswarm {

struct CellIndex {
  std::int32_t x = 0;
  std::int32_t y = 0;
  bool operator==(const CellIndex&) const = default;
};

class DsGrid {
 public:
  static constexpr int kTileBits = 6;
  static constexpr int kTileSize = 1 << kTileBits;  // 64 cells: 3.2 m at 5 cm
  static constexpr int kTileCells = kTileSize * kTileSize;

  explicit DsGrid(double resolution = 0.05);
  // Deep copies (a robot hands a frozen copy of its map to others); moves are cheap.
  DsGrid(const DsGrid& other);
  DsGrid& operator=(const DsGrid& other);
  DsGrid(DsGrid&&) noexcept = default;
  DsGrid& operator=(DsGrid&&) noexcept = default;

  double resolution() const { return resolution_; }

  // World point -> index of the cell containing it. Cell (0,0) spans [0, res)².
  CellIndex cell_of(const Eigen::Vector2d& p) const {
    return {static_cast<std::int32_t>(std::floor(p.x() * inv_resolution_)),
            static_cast<std::int32_t>(std::floor(p.y() * inv_resolution_))};
  }
  Eigen::Vector2d cell_center(CellIndex c) const {
    return {(c.x + 0.5) * resolution_, (c.y + 0.5) * resolution_};
  }

  // Read access; cells never written are vacuous (all unknown).
  DsMass at(CellIndex c) const { return packed_at(c).mass(); }
  // Occupancy in [0, 1] (unknown counts 0.5): the value the matcher reads.
  float occupancy(CellIndex c) const { return at(c).occupancy(); }

  // The 2×2 block of cells with lower-left corner `c`, in the order (c),
  // (c+x), (c+y), (c+x+y). One tile lookup when the block lies in one tile
  // (63 times out of 64): the matcher's bilinear interpolation lives on this.
  void quad(CellIndex c, DsMass out[4]) const {
    PackedMass packed[4];
    packed_quad(c, packed);
    for (int k = 0; k < 4; ++k) out[k] = packed[k].mass();
  }
  // quad() in the stored units, for readers that need no DsMass.
  void packed_quad(CellIndex c, PackedMass out[4]) const {
    const int lx = c.x & (kTileSize - 1), ly = c.y & (kTileSize - 1);
    if (lx < kTileSize - 1 && ly < kTileSize - 1) {
      const Tile* t = find_tile(c);
      if (!t) {
        out[0] = out[1] = out[2] = out[3] = PackedMass{};
        return;
      }
      quad_in_tile(t->cells.data(), c, out);
      return;
    }
    out[0] = packed_at(c);
    out[1] = packed_at({c.x + 1, c.y});
    out[2] = packed_at({c.x, c.y + 1});
    out[3] = packed_at({c.x + 1, c.y + 1});
  }
  // packed_quad's block read from the cells of the tile holding it (for
  // readers that keep a tile; the block must not reach past the tile's edge).
  static void quad_in_tile(const PackedMass* tile, CellIndex c, PackedMass out[4]) {
    const PackedMass* base = tile + local_index(c);
    out[0] = base[0];
    out[1] = base[1];
    out[2] = base[kTileSize];
    out[3] = base[kTileSize + 1];
  }
  PackedMass packed_at(CellIndex c) const {
    const Tile* t = find_tile(c);
    return t ? t->cells[local_index(c)] : PackedMass{};
  }

  // The cells of the tile holding `c` (index them with local_index), or null
  // where nothing was written: for readers that keep a tile across points.
  const PackedMass* tile_cells(CellIndex c) const {
    const Tile* t = find_tile(c);
    return t ? t->cells.data() : nullptr;
  }
  static int local_index(CellIndex c) {
    return ((c.y & (kTileSize - 1)) << kTileBits) | (c.x & (kTileSize - 1));
  }

  // Write access: cell c becomes update(its masses); allocates the tile if needed.
  template <typename F>
  void update(CellIndex c, F&& update) {
    PackedMass& cell = mutable_cell(c);
    cell = PackedMass::pack(update(cell.mass()));
  }
  void set(CellIndex c, const DsMass& m) { mutable_cell(c) = PackedMass::pack(m); }
  void set_packed(CellIndex c, PackedMass m) { mutable_cell(c) = m; }

  // The cells of the tile holding `c`, allocated if needed: for writers that
  // keep a tile across cells (a beam crosses dozens of one tile's cells).
  // The pointer stays valid as long as the grid.
  PackedMass* mutable_tile_cells(CellIndex c) {
    if (Tile* t = find_tile(c)) return t->cells.data();
    return get_or_create_tile(c).cells.data();
  }

  // Whether any cell holds evidence (an allocated tile may hold none).
  bool holds_evidence() const;
  std::size_t tiles_allocated() const { return tiles_.size(); }
  std::size_t cells_allocated() const { return tiles_.size() * kTileCells; }
  // Heap bytes held by the grid (tiles plus the pointer table), for memory reports.
  std::size_t memory_bytes() const;

  // Takes over `other`'s tiles (same resolution, none where this grid has
  // one: two halves of one map built apart); `other` is left empty. Throws
  // std::logic_error when a tile is in both.
  void absorb(DsGrid&& other);

  // Bounding box of allocated tiles, in cells [min, max) — empty grid gives min == max.
  void bounds(CellIndex& min, CellIndex& max) const;

  // Dense copy of the region that holds any evidence (plus `margin` cells).
  GridRaster to_raster(int margin = 2) const;

  // The cell at position `i` of the cells array for_each_tile hands out, for
  // the tile whose lower-left cell is `origin`.
  static CellIndex tile_cell(CellIndex origin, int i) {
    return {origin.x + (i & (kTileSize - 1)), origin.y + (i >> kTileBits)};
  }

  // Visits every allocated tile: f(tile_origin_cell, const PackedMass* cells[kTileCells]).
  template <typename F>
  void for_each_tile(F&& f) const {
    for (const auto& t : tiles_) f(CellIndex{t->origin.x, t->origin.y}, t->cells.data());
  }

 private:
  struct Tile {
    CellIndex origin;  // index of its lower-left cell
    std::array<PackedMass, kTileCells> cells{};
  };

  PackedMass& mutable_cell(CellIndex c) {
    // Inline when the tile exists (insertion writes mostly into existing tiles).
    if (Tile* t = find_tile(c)) return t->cells[local_index(c)];
    return get_or_create_tile(c).cells[local_index(c)];
  }

  // The tile holding `c`, or null (the table holds mutable tiles; const
  // accessors only read through it).
  Tile* find_tile(CellIndex c) const {
    const std::int32_t tx = (c.x >> kTileBits) - table_origin_.x;
    const std::int32_t ty = (c.y >> kTileBits) - table_origin_.y;
    if (tx < 0 || ty < 0 || tx >= table_width_ || ty >= table_height_) return nullptr;
    return table_[static_cast<std::size_t>(ty) * table_width_ + tx];
  }
  Tile& get_or_create_tile(CellIndex c);
  // The table's slot for tile (tx, ty), the table grown to hold it if need be.
  Tile*& slot_of(std::int32_t tx, std::int32_t ty);
  void grow_table_to_include(std::int32_t tx, std::int32_t ty);

  double resolution_;
  double inv_resolution_;
  std::vector<std::unique_ptr<Tile>> tiles_;  // owning storage
  std::vector<Tile*> table_;                  // dense lookup, row-major over tile coords
  CellIndex table_origin_{0, 0};              // tile coords of table_[0]
  std::int32_t table_width_ = 0;
  std::int32_t table_height_ = 0;
};

}  // namespace dsswarm
