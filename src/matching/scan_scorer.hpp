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
// Cell value at a world point, bilinear between cell centres.
inline float interpolated_occupancy(const DsGrid& grid, double wx, double wy, float unknown_value) {
  const double inv = 1.0 / grid.resolution();
  const double gx = wx * inv - 0.5, gy = wy * inv - 0.5;
  const double fx = std::floor(gx), fy = std::floor(gy);
  const auto x0 = static_cast<std::int32_t>(fx), y0 = static_cast<std::int32_t>(fy);
  const float ax = static_cast<float>(gx - fx), ay = static_cast<float>(gy - fy);
  DsMass q[4];
  grid.quad({x0, y0}, q);
  auto value = [unknown_value](const DsMass& m) { return m.occupied + unknown_value * m.unknown(); };
  const float o00 = value(q[0]), o10 = value(q[1]), o01 = value(q[2]), o11 = value(q[3]);
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

namespace dsswarm {

// A cell that holds an obstacle: occupied mass at least 0.15 and more than
// its free mass.
inline bool is_obstacle(const DsMass& m) { return m.occupied >= 0.15f && m.occupied > m.free; }

// Whether `holds` is true of cell `c` or one of its 8 neighbours: the
// neighbourhood absorbs a cell's worth of misplacement.
template <class Predicate>
bool in_neighbourhood(const DsGrid& grid, CellIndex c, Predicate holds) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (holds(grid.at({c.x + dx, c.y + dy}))) return true;
  return false;
}

inline bool near_obstacle(const DsGrid& grid, CellIndex c) { return in_neighbourhood(grid, c, is_obstacle); }

// How well a placed scan agrees with the map, independent of how much of the
// map is new: of the points that land where the map has evidence (their cell
// or a neighbour is not vacuous), the share that land on or next to a cell
// believed more occupied than free. A correct match keeps most points on
// walls; a wrong one puts them in space the map has seen to be free. Points
// in unexplored space count for neither, so entering a new room is no failure.
struct MatchQuality {
  double known_fraction = 0.0;  // weight share of points that land on known cells
  double inlier_ratio = 1.0;    // of those, the weight share on or next to an obstacle
};

inline MatchQuality match_quality(const DsGrid& grid, const std::vector<ScanPoint>& points, const Pose2& pose) {
  constexpr float kKnown = 0.1f;  // evidence mass that makes a cell "seen"
  double total = 0.0, known = 0.0, inliers = 0.0;
  for (const ScanPoint& p : points) {
    const CellIndex c = grid.cell_of(pose * Eigen::Vector2d(p.x, p.y));
    const bool obstacle = near_obstacle(grid, c);
    const bool seen =
        obstacle || in_neighbourhood(grid, c, [](const DsMass& m) { return m.occupied + m.free >= kKnown; });
    total += p.weight;
    if (seen) known += p.weight;
    if (obstacle) inliers += p.weight;
  }
  MatchQuality q;
  if (total > 0.0) q.known_fraction = known / total;
  if (known > 0.0) q.inlier_ratio = inliers / known;
  return q;
}

}  // namespace dsswarm
