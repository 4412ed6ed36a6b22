#include "grid/map_combine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "grid/sampling.hpp"

namespace dsswarm {
namespace {

constexpr float kNothing = 1e-4f;  // below this a source cell knows nothing

// A target with fewer levels takes the source's finest ones (a picture needs only the finest).
void check_compatible(const MultiResMap& target, const MultiResMap& source) {
  if (source.levels() < target.levels() || source.config().resolution != target.config().resolution)
    throw ConfigError("cannot merge maps of different resolution or levels (" +
                      std::to_string(source.config().resolution) + " m × " + std::to_string(source.levels()) +
                      " vs " + std::to_string(target.config().resolution) + " m × " +
                      std::to_string(target.levels()) + ")");
}

// Which 8×8-cell blocks of a grid hold any evidence (8: fewest instructions
// composing mit-csail, against 4 and 16). A rotated submap's
// box in the target is mostly space it never saw, and even its tiles are
// mostly empty blocks (a frozen map keeps only the blocks with evidence):
// whole blocks of target cells that can only read empty ones are skipped.
class BlockMask {
 public:
  static constexpr int kBits = 3;

  explicit BlockMask(const DsGrid& grid) {
    CellIndex lo, hi;
    grid.bounds(lo, hi);
    if (lo == hi) return;
    origin_ = {lo.x >> kBits, lo.y >> kBits};
    width_ = ((hi.x - 1) >> kBits) - origin_.x + 1;
    height_ = ((hi.y - 1) >> kBits) - origin_.y + 1;
    held_.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0);
    constexpr int block = 1 << kBits, per_tile = DsGrid::kTileSize / block;
    static_assert(DsGrid::kTileSize % block == 0);
    grid.for_each_tile([&](CellIndex origin, const PackedMass* cells) {
      for (int by = 0; by < per_tile; ++by)
        for (int bx = 0; bx < per_tile; ++bx) {
          // The bits of a block's masses ORed together, a row at a time (vectorizes).
          std::uint32_t bits = 0;
          for (int y = 0; y < block && bits == 0; ++y) {
            const PackedMass* row = cells + (by * block + y) * DsGrid::kTileSize + bx * block;
            for (int x = 0; x < block; ++x) bits |= static_cast<std::uint32_t>(row[x].occupied | row[x].free);
          }
          if (bits != 0) held_[index((origin.x >> kBits) + bx - origin_.x, (origin.y >> kBits) + by - origin_.y)] = 1;
        }
    });
  }

  // Whether a block holding one of the cells [lo, hi] (inclusive) holds evidence.
  bool any(CellIndex lo, CellIndex hi) const {
    const std::int32_t x0 = std::max((lo.x >> kBits) - origin_.x, 0), x1 = std::min((hi.x >> kBits) - origin_.x, width_ - 1);
    const std::int32_t y0 = std::max((lo.y >> kBits) - origin_.y, 0), y1 = std::min((hi.y >> kBits) - origin_.y, height_ - 1);
    for (std::int32_t y = y0; y <= y1; ++y)
      for (std::int32_t x = x0; x <= x1; ++x)
        if (held_[index(x, y)]) return true;
    return false;
  }

 private:
  std::size_t index(std::int32_t x, std::int32_t y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }
  CellIndex origin_;
  std::int32_t width_ = 0, height_ = 0;
  std::vector<std::uint8_t> held_;
};

// DsGrid::packed_quad for reads that wander slowly over a grid (a row of
// target cells resampled from a source): the tile last read is kept, so most
// reads take no table lookup.
class QuadReader {
 public:
  explicit QuadReader(const DsGrid& grid) : grid_(grid) {}

  void read(CellIndex c, PackedMass out[4]) {
    constexpr int last = DsGrid::kTileSize - 1;
    if ((c.x & last) == last || (c.y & last) == last) {  // the block spans tiles
      grid_.packed_quad(c, out);
      return;
    }
    const CellIndex tile{c.x >> DsGrid::kTileBits, c.y >> DsGrid::kTileBits};
    if (!(tile == tile_)) {
      tile_ = tile;
      cells_ = grid_.tile_cells(c);
    }
    if (!cells_) {
      out[0] = out[1] = out[2] = out[3] = PackedMass{};
      return;
    }
    DsGrid::quad_in_tile(cells_, c, out);
  }

 private:
  const DsGrid& grid_;
  CellIndex tile_{std::numeric_limits<std::int32_t>::min(), 0};  // no tile's index (cells >> kTileBits)
  const PackedMass* cells_ = nullptr;
};

bool all_vacuous(const PackedMass q[4]) {
  return q[0].vacuous() && q[1].vacuous() && q[2].vacuous() && q[3].vacuous();
}

// The bounding box of the rectangle [lo, hi] (metres) moved by `move`.
struct Box {
  Eigen::Vector2d lo, hi;
};
Box moved_box(const PointTransform& move, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  Box box{Eigen::Vector2d::Constant(std::numeric_limits<double>::max()),
          Eigen::Vector2d::Constant(std::numeric_limits<double>::lowest())};
  for (int corner = 0; corner < 4; ++corner) {
    const Eigen::Vector2d q = move(corner & 1 ? hi.x() : lo.x(), corner & 2 ? hi.y() : lo.y());
    box.lo = box.lo.cwiseMin(q);
    box.hi = box.hi.cwiseMax(q);
  }
  return box;
}

// The source cells bilinear reads can touch for the target cells [lo, hi]
// (their centres placed in the source; a cell of margin against rounding).
bool source_has_evidence(const BlockMask& source, const PointTransform& to_source, double tr, double inv,
                         CellIndex lo, CellIndex hi) {
  const Box b = moved_box(to_source, {(lo.x + 0.5) * tr, (lo.y + 0.5) * tr}, {(hi.x + 0.5) * tr, (hi.y + 0.5) * tr});
  return source.any({floor_to_cell(b.lo.x() * inv - 0.5) - 1, floor_to_cell(b.lo.y() * inv - 0.5) - 1},
                    {floor_to_cell(b.hi.x() * inv - 0.5) + 2, floor_to_cell(b.hi.y() * inv - 0.5) + 2});
}

// Target cells [lo, hi] of one target tile (allocated on the first cell the
// source knows something about).
void combine_cells(DsGrid& target, QuadReader& source, double source_resolution, const PointTransform& to_source,
                   CellIndex lo, CellIndex hi, const EvidenceModel& evidence) {
  const double tr = target.resolution(), inv = 1.0 / source_resolution;
  PackedMass* cells = nullptr;
  for (std::int32_t y = lo.y; y <= hi.y; ++y) {
    const double wy = (y + 0.5) * tr;
    for (std::int32_t x = lo.x; x <= hi.x; ++x) {
      const Eigen::Vector2d sp = to_source((x + 0.5) * tr, wy);
      const BilinearPoint b = bilinear_point(sp.x(), sp.y(), inv);
      PackedMass q[4];
      source.read(b.corner, q);
      if (all_vacuous(q)) continue;  // most cells of a rotated submap's box land where it saw nothing
      const DsMass m = interpolated_masses(b, q);
      if (m.occupied + m.free < kNothing) continue;
      if (!cells) cells = target.mutable_tile_cells(lo);
      PackedMass& cell = cells[DsGrid::local_index({x, y})];
      cell = PackedMass::pack(evidence.update(cell.mass(), m));
    }
  }
}

void combine_level(DsGrid& target, const DsGrid& source, const Pose2& source_in_target, const EvidenceModel& evidence,
                   const TileBand& band) {
  CellIndex smin, smax;
  source.bounds(smin, smax);
  if (smin == smax) return;
  // The source's extent, placed in the target frame, bounds the cells to visit.
  const double sr = source.resolution();
  const Box placed =
      moved_box(PointTransform(source_in_target), {smin.x * sr, smin.y * sr}, {smax.x * sr, smax.y * sr});
  const CellIndex tmin = target.cell_of(placed.lo), tmax = target.cell_of(placed.hi);
  const PointTransform to_source(source_in_target.inverse());
  const BlockMask held(source);
  QuadReader reader(source);
  const double tr = target.resolution(), inv = 1.0 / sr;
  // Tile by tile, in blocks of the mask's size, skipping those whose place in the
  // source holds nothing.
  constexpr int bits = DsGrid::kTileBits, size = DsGrid::kTileSize, block = 1 << BlockMask::kBits;
  const double tile_height = size * tr;
  for (std::int32_t ty = tmin.y >> bits; ty <= tmax.y >> bits; ++ty) {
    if (!band.holds(ty, tile_height)) continue;
    for (std::int32_t tx = tmin.x >> bits; tx <= tmax.x >> bits; ++tx) {
      const CellIndex lo{std::max(tmin.x, tx * size), std::max(tmin.y, ty * size)};
      const CellIndex hi{std::min(tmax.x, tx * size + size - 1), std::min(tmax.y, ty * size + size - 1)};
      if (!source_has_evidence(held, to_source, tr, inv, lo, hi)) continue;
      for (std::int32_t by = lo.y >> BlockMask::kBits; by <= hi.y >> BlockMask::kBits; ++by)
        for (std::int32_t bx = lo.x >> BlockMask::kBits; bx <= hi.x >> BlockMask::kBits; ++bx) {
          const CellIndex blo{std::max(lo.x, bx * block), std::max(lo.y, by * block)};
          const CellIndex bhi{std::min(hi.x, bx * block + block - 1), std::min(hi.y, by * block + block - 1)};
          if (source_has_evidence(held, to_source, tr, inv, blo, bhi))
            combine_cells(target, reader, sr, to_source, blo, bhi, evidence);
        }
    }
  }
}

}  // namespace

void combine_into(MultiResMap& target, const MultiResMap& source, const Pose2& source_in_target,
                  const TileBand& band) {
  check_compatible(target, source);
  for (int level = 0; level < target.levels(); ++level)
    combine_level(target.mutable_level(level), source.level(level), source_in_target, target.config().evidence, band);
}

void combine_aligned(MultiResMap& target, const MultiResMap& source, const TileBand& band) {
  check_compatible(target, source);
  const EvidenceModel& evidence = target.config().evidence;
  for (int level = 0; level < target.levels(); ++level) {
    DsGrid& t = target.mutable_level(level);
    const double tile_height = DsGrid::kTileSize * t.resolution();
    source.level(level).for_each_tile([&](CellIndex origin, const PackedMass* cells) {
      if (!band.holds(origin.y >> DsGrid::kTileBits, tile_height)) return;
      for (int i = 0; i < DsGrid::kTileCells; ++i) {
        const DsMass m = cells[i].mass();
        if (m.occupied + m.free < kNothing) continue;
        t.update(DsGrid::tile_cell(origin, i), [&](const DsMass& cell) { return evidence.update(cell, m); });
      }
    });
  }
}

}  // namespace dsswarm
