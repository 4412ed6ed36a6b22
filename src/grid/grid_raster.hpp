#pragma once
// A dense, bounded copy of (part of) the unbounded grid, for output and display.
#include <Eigen/Core>
#include <vector>

#include "grid/ds_mass.hpp"

namespace dsswarm {

struct GridRaster {
  int width = 0;             // cells along x
  int height = 0;            // cells along y
  double resolution = 0.05;  // metres per cell
  Eigen::Vector2d origin{0.0, 0.0};  // world position of the lower-left corner of cell (0, 0)
  std::vector<DsMass> cells;         // row-major; row 0 is the lowest y (ROS convention)

  const DsMass& at(int cx, int cy) const { return cells[static_cast<std::size_t>(cy) * width + cx]; }
  // World coordinates -> fractional cell coordinates.
  Eigen::Vector2d to_cell(const Eigen::Vector2d& world) const { return (world - origin) / resolution; }
};

}  // namespace dsswarm
