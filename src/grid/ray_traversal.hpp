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

// The traversal's state: the current cell and the parametric distance (t in
// [0, 1] along the segment) to the next crossing of each axis.
struct RaySteps {
  CellIndex cell, last;
  int step_x, step_y;
  double delta_x, delta_y;  // t to cross one cell along each axis
  double t_x, t_y;          // t of the next crossing
  int steps;                // cells to visit at most

  RaySteps(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double resolution) {
    const double inv = 1.0 / resolution;
    const Eigen::Vector2d s = start * inv, e = end * inv;
    cell = {static_cast<std::int32_t>(std::floor(s.x())), static_cast<std::int32_t>(std::floor(s.y()))};
    last = {static_cast<std::int32_t>(std::floor(e.x())), static_cast<std::int32_t>(std::floor(e.y()))};
    const Eigen::Vector2d d = e - s;
    step_x = d.x() > 0 ? 1 : -1;
    step_y = d.y() > 0 ? 1 : -1;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    delta_x = d.x() != 0.0 ? std::abs(1.0 / d.x()) : kInf;
    delta_y = d.y() != 0.0 ? std::abs(1.0 / d.y()) : kInf;
    t_x = d.x() != 0.0 ? ((step_x > 0 ? (cell.x + 1 - s.x()) : (s.x() - cell.x)) * delta_x) : kInf;
    t_y = d.y() != 0.0 ? ((step_y > 0 ? (cell.y + 1 - s.y()) : (s.y() - cell.y)) * delta_y) : kInf;
    // The number of cells is bounded by the Manhattan distance: guards
    // against floating-point edge cases ever looping past the end.
    steps = std::abs(last.x - cell.x) + std::abs(last.y - cell.y);
  }
  // Steps into the next cell; returns whether it was the neighbour along x (else along y).
  bool advance() {
    if (t_x < t_y) {
      cell.x += step_x;
      t_x += delta_x;
      return true;
    }
    cell.y += step_y;
    t_y += delta_y;
    return false;
  }
};

}  // namespace ray_detail

template <typename Visit>
void traverse_ray(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double resolution, Visit&& visit) {
  ray_detail::RaySteps r(start, end, resolution);
  for (int i = 0; i < r.steps && !(r.cell == r.last); ++i) {
    visit(r.cell);
    r.advance();
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
  if (r.steps == 0 || r.cell == r.last) return;
  enter_tile(r.cell);
  int local = DsGrid::local_index(r.cell);
  std::int32_t lx = r.cell.x & kLast, ly = r.cell.y & kLast;  // the cell's place in its tile
  const int row_step = r.step_y * DsGrid::kTileSize;
  for (int i = 0; i < r.steps && !(r.cell == r.last); ++i) {
    visit(local);
    if (r.advance()) {
      lx += r.step_x;
      local += r.step_x;
    } else {
      ly += r.step_y;
      local += row_step;
    }
    if ((lx | ly) & ~kLast) {  // left the tile: lx or ly is -1 or kTileSize
      lx &= kLast;
      ly &= kLast;
      local = (ly << DsGrid::kTileBits) | lx;
      if (i + 1 < r.steps && !(r.cell == r.last)) enter_tile(r.cell);  // only tiles with cells to visit
    }
  }
}

}  // namespace dsswarm
