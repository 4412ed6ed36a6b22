#pragma once
// Grid traversal of a beam (Amanatides & Woo, 1987): visits, in order, every
// cell the segment from `start` to `end` passes through, excluding the cell
// that contains `end` (that one receives the hit, not free evidence).
#include <Eigen/Core>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "grid/ds_grid.hpp"

namespace dsswarm {

namespace ray_detail {

// The traversal's state: the first cell and the parametric distance (t in
// [0, 1] along the segment) to the next crossing of each axis.
struct RaySteps {
  CellIndex first;
  int step_x, step_y;
  double delta_x, delta_y;  // t to cross one cell along each axis
  double t_x, t_y;          // t of the next crossing
  // Cells to visit: each step moves one cell along x or y, so the last cell,
  // this many steps away (Manhattan), is reached after exactly this many
  // steps and no sooner; floating-point edge cases cannot walk further.
  int steps;

  RaySteps(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double resolution) {
    const double inv = 1.0 / resolution;
    const Eigen::Vector2d s = start * inv, e = end * inv;
    first = {static_cast<std::int32_t>(std::floor(s.x())), static_cast<std::int32_t>(std::floor(s.y()))};
    const CellIndex last{static_cast<std::int32_t>(std::floor(e.x())), static_cast<std::int32_t>(std::floor(e.y()))};
    const Eigen::Vector2d d = e - s;
    step_x = d.x() > 0 ? 1 : -1;
    step_y = d.y() > 0 ? 1 : -1;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    delta_x = d.x() != 0.0 ? std::abs(1.0 / d.x()) : kInf;
    delta_y = d.y() != 0.0 ? std::abs(1.0 / d.y()) : kInf;
    t_x = d.x() != 0.0 ? ((step_x > 0 ? (first.x + 1 - s.x()) : (s.x() - first.x)) * delta_x) : kInf;
    t_y = d.y() != 0.0 ? ((step_y > 0 ? (first.y + 1 - s.y()) : (s.y() - first.y)) * delta_y) : kInf;
    steps = std::abs(last.x - first.x) + std::abs(last.y - first.y);
  }
  // Moves the crossings on by one cell; returns whether the next cell is the
  // neighbour along x (else along y).
  bool advance() {
    if (t_x < t_y) {
      t_x += delta_x;
      return true;
    }
    t_y += delta_y;
    return false;
  }
};

}  // namespace ray_detail

template <typename Visit>
void traverse_ray(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double resolution, Visit&& visit) {
  ray_detail::RaySteps r(start, end, resolution);
  CellIndex cell = r.first;
  for (int i = 0; i < r.steps; ++i) {
    visit(cell);
    if (r.advance()) cell.x += r.step_x;
    else cell.y += r.step_y;
  }
}

// The same cells in the same order, each given as its index in its tile
// (DsGrid::local_index): `enter_tile(cell)` is called before the first cell
// of each tile the beam crosses, then `visit(local_index)` for that tile's
// cells. Writers look a tile up once per tile, not once per cell, and keep no
// cell coordinates: the traversal steps the index itself.
template <typename EnterTile, typename Visit>
void traverse_ray_by_tile(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double resolution,
                          EnterTile&& enter_tile, Visit&& visit) {
  constexpr std::int32_t kLast = DsGrid::kTileSize - 1;
  ray_detail::RaySteps r(start, end, resolution);
  if (r.steps == 0) return;
  enter_tile(r.first);
  std::int32_t tile_x = r.first.x & ~kLast, tile_y = r.first.y & ~kLast;  // the tile's lower-left cell
  std::int32_t lx = r.first.x & kLast, ly = r.first.y & kLast;            // the cell's place in it
  int local = DsGrid::local_index(r.first);
  const int row_step = r.step_y * DsGrid::kTileSize;
  for (int i = 0; i < r.steps; ++i) {
    visit(local);
    if (r.advance()) {
      lx += r.step_x;
      local += r.step_x;
    } else {
      ly += r.step_y;
      local += row_step;
    }
    if ((lx | ly) & ~kLast) {  // left the tile: lx or ly is -1 or kTileSize
      tile_x += lx & ~kLast;  // -kTileSize, 0 or +kTileSize
      tile_y += ly & ~kLast;
      lx &= kLast;
      ly &= kLast;
      local = (ly << DsGrid::kTileBits) | lx;
      if (i + 1 < r.steps) enter_tile({tile_x + lx, tile_y + ly});  // only tiles with cells to visit
    }
  }
}

}  // namespace dsswarm
