#pragma once
// Bilinear interpolation between cell centres, the one implementation shared
// by everything that reads a grid between its cells (the scorer reading
// occupancy, the map merge reading masses) or writes a point over the four
// cells around it (coarse-level hits). Reading through the same weights that
// writing spreads with makes a hit a tent centred exactly on its point.
#include <array>
#include <cmath>
#include <cstdint>

#include "grid/ds_grid.hpp"

namespace dsswarm {

// A world point's place among the four cell centres around it: the 2×2 block
// whose lower-left cell is `corner` (in DsGrid::quad order) and the point's
// fractional offsets from that cell's centre, in [0, 1).
struct BilinearPoint {
  CellIndex corner;
  float ax = 0.0f;
  float ay = 0.0f;

  // Each cell's share of the point, in DsGrid::quad order; they sum to 1.
  std::array<float, 4> weights() const { return {(1 - ax) * (1 - ay), ax * (1 - ay), (1 - ax) * ay, ax * ay}; }
  // The value at the point from the block's four values (quad order).
  float interpolate(float v00, float v10, float v01, float v11) const {
    return (1 - ay) * ((1 - ax) * v00 + ax * v10) + ay * ((1 - ax) * v01 + ax * v11);
  }
};

// floor() for values well inside the int32 range (cell indices), without the
// libm call or the long sequence baseline x86-64 compiles std::floor into
// (and, in single precision, in a form loops can vectorise).
template <class Real>
inline std::int32_t floor_to_cell(Real v) {
  const auto i = static_cast<std::int32_t>(v);  // truncates towards zero
  return i - static_cast<std::int32_t>(v < static_cast<Real>(i));
}

// The bilinear place of a point given in cell units measured from cell
// centres (world coordinate / resolution − 0.5).
inline BilinearPoint bilinear_cell_point(double gx, double gy) {
  const std::int32_t ix = floor_to_cell(gx), iy = floor_to_cell(gy);
  return {{ix, iy}, static_cast<float>(gx - ix), static_cast<float>(gy - iy)};
}

inline BilinearPoint bilinear_point(double wx, double wy, double inv_resolution) {
  return bilinear_cell_point(wx * inv_resolution - 0.5, wy * inv_resolution - 0.5);
}

// What a cell is worth to a scan point: the belief that it is occupied plus a
// share `unknown_value` of its unknown mass. With 0 only evidence of an
// obstacle counts, so a scan is not rewarded for drifting into unexplored
// space; with 0.5 this is the pignistic occupancy used for display.
inline float cell_value(const DsMass& m, float unknown_value) { return m.occupied + unknown_value * m.unknown(); }

// The value at a world point, bilinear between cell centres.
inline float interpolated_occupancy(const DsGrid& grid, double wx, double wy, float unknown_value) {
  const BilinearPoint b = bilinear_point(wx, wy, 1.0 / grid.resolution());
  DsMass q[4];
  grid.quad(b.corner, q);
  return b.interpolate(cell_value(q[0], unknown_value), cell_value(q[1], unknown_value),
                       cell_value(q[2], unknown_value), cell_value(q[3], unknown_value));
}

// The masses of `grid` at a world point, bilinear between cell centres: a
// convex blend of valid masses, clamped against rounding.
// The same from the four cells around the point as stored (DsGrid::packed_quad).
inline DsMass interpolated_masses(const BilinearPoint& b, const PackedMass packed[4]) {
  const std::array<float, 4> w = b.weights();
  DsMass m;
  for (int k = 0; k < 4; ++k) {
    const DsMass q = packed[k].mass();
    m.occupied += w[k] * q.occupied;
    m.free += w[k] * q.free;
  }
  m.occupied = std::clamp(m.occupied, 0.0f, 1.0f);
  m.free = std::clamp(m.free, 0.0f, 1.0f - m.occupied);
  return m;
}

inline DsMass interpolated_masses(const DsGrid& grid, double wx, double wy) {
  const BilinearPoint b = bilinear_point(wx, wy, 1.0 / grid.resolution());
  PackedMass q[4];
  grid.packed_quad(b.corner, q);
  return interpolated_masses(b, q);
}

}  // namespace dsswarm
