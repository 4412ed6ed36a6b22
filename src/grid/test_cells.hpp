#pragma once
// Comparing maps cell by cell, for tests.
#include <algorithm>
#include <cmath>

#include "grid/ds_grid.hpp"
#include "grid/grid_raster.hpp"

namespace dsswarm::test {

// The largest difference of a mass over the cells `a` holds (cells b lacks count as b's empty cells).
inline double largest_difference(const DsGrid& a, const DsGrid& b) {
  double worst = 0.0;
  a.for_each_tile([&](CellIndex origin, const PackedMass* cells) {
    for (int i = 0; i < DsGrid::kTileCells; ++i) {
      const DsMass m = b.at(DsGrid::tile_cell(origin, i));
      worst = std::max({worst, std::abs(double{m.occupied} - cells[i].mass().occupied),
                        std::abs(double{m.free} - cells[i].mass().free)});
    }
  });
  return worst;
}

// The same over the cells either holds.
inline double cells_apart(const DsGrid& a, const DsGrid& b) {
  return std::max(largest_difference(a, b), largest_difference(b, a));
}

// Two pictures with the same extent and every cell's masses equal.
inline bool same_cells(const GridRaster& a, const GridRaster& b) {
  if (a.width != b.width || a.height != b.height || a.origin != b.origin) return false;
  for (std::size_t i = 0; i < a.cells.size(); ++i)
    if (a.cells[i].occupied != b.cells[i].occupied || a.cells[i].free != b.cells[i].free) return false;
  return true;
}

}  // namespace dsswarm::test
