#pragma once
// Pose score of the chapter's eq. (1): Σ over scan points of the occupancy of
// the cell the point falls in, times the point's weight — normalised by Σ w so
// scores of different scans compare (0 = every point in free space, 1 = every
// point on a surely occupied cell). Occupancy is interpolated bilinearly
// between the four nearest cell centres, which makes the score continuous in
// the pose and gives the matcher a slope to climb within a cell.
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/ds_grid.hpp"
#include "sensor/scan_points.hpp"

namespace dsswarm {

// What a cell is worth to a scan point: the belief that it is occupied plus a
// share `unknown_value` of its unknown mass. With 0 only evidence of an
// obstacle counts, so a scan is not rewarded for drifting into unexplored
// space; with 0.5 this is the pignistic occupancy used for display.
inline float cell_value(const DsGrid& grid, CellIndex c, float unknown_value) {
  const DsMass m = grid.at(c);
  return m.occupied + unknown_value * m.unknown();
}

// Cell value at a world point, bilinear between cell centres.
inline float interpolated_occupancy(const DsGrid& grid, double wx, double wy, float unknown_value) {
  const double inv = 1.0 / grid.resolution();
  const double gx = wx * inv - 0.5, gy = wy * inv - 0.5;
  const double fx = std::floor(gx), fy = std::floor(gy);
  const auto x0 = static_cast<std::int32_t>(fx), y0 = static_cast<std::int32_t>(fy);
  const float ax = static_cast<float>(gx - fx), ay = static_cast<float>(gy - fy);
  const float o00 = cell_value(grid, {x0, y0}, unknown_value), o10 = cell_value(grid, {x0 + 1, y0}, unknown_value);
  const float o01 = cell_value(grid, {x0, y0 + 1}, unknown_value),
              o11 = cell_value(grid, {x0 + 1, y0 + 1}, unknown_value);
  return (1 - ay) * ((1 - ax) * o00 + ax * o10) + ay * ((1 - ax) * o01 + ax * o11);
}

// Weighted mean occupancy under `points` placed at `pose`; uses every
// `stride`-th point (coarse levels need fewer points).
inline double score_pose(const DsGrid& grid, const std::vector<ScanPoint>& points, const Pose2& pose,
                         std::size_t stride = 1, float unknown_value = 0.0f) {
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  double sum = 0.0, weights = 0.0;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    const ScanPoint& p = points[i];
    const double wx = pose.x + c * p.x - s * p.y, wy = pose.y + s * p.x + c * p.y;
    sum += p.weight * interpolated_occupancy(grid, wx, wy, unknown_value);
    weights += p.weight;
  }
  return weights > 0.0 ? sum / weights : 0.0;
}

}  // namespace dsswarm
