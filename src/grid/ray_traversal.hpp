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

template <typename Visit>
void traverse_ray(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double resolution, Visit&& visit) {
  const double inv = 1.0 / resolution;
  const Eigen::Vector2d s = start * inv, e = end * inv;
  CellIndex c{static_cast<std::int32_t>(std::floor(s.x())), static_cast<std::int32_t>(std::floor(s.y()))};
  const CellIndex last{static_cast<std::int32_t>(std::floor(e.x())), static_cast<std::int32_t>(std::floor(e.y()))};
  const Eigen::Vector2d d = e - s;
  const int step_x = d.x() > 0 ? 1 : -1, step_y = d.y() > 0 ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Parametric distance (t in [0,1]) to cross one cell along each axis, and to the first crossing.
  const double delta_x = d.x() != 0.0 ? std::abs(1.0 / d.x()) : kInf;
  const double delta_y = d.y() != 0.0 ? std::abs(1.0 / d.y()) : kInf;
  double t_x = d.x() != 0.0 ? ((step_x > 0 ? (c.x + 1 - s.x()) : (s.x() - c.x)) * delta_x) : kInf;
  double t_y = d.y() != 0.0 ? ((step_y > 0 ? (c.y + 1 - s.y()) : (s.y() - c.y)) * delta_y) : kInf;
  // The number of cells is bounded by the Manhattan distance: guards against
  // floating-point edge cases ever looping past the end.
  const int max_steps = std::abs(last.x - c.x) + std::abs(last.y - c.y);
  for (int i = 0; i < max_steps && !(c == last); ++i) {
    visit(c);
    if (t_x < t_y) {
      c.x += step_x;
      t_x += delta_x;
    } else {
      c.y += step_y;
      t_y += delta_y;
    }
  }
}

}  // namespace dsswarm
