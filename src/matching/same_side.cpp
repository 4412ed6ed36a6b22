#include "matching/same_side.hpp"

#include <algorithm>
#include <optional>

#include "matching/scan_scorer.hpp"

namespace dsswarm {

double same_side_ratio(const DsGrid& grid, const std::vector<ScanPoint>& points, const Pose2& pose) {
  constexpr float kSeenFree = 0.08f;     // two beams' worth of free evidence
  constexpr double kApproach = 0.15;     // m before the hit: beyond the surface's own blur
  // A grazing beam is still inside its wall's cells 15 cm before its hit, in
  // cells the map has never seen free even when the placement is right. The
  // approach point steps further back along the beam until it leaves the
  // obstacle; a hit still inside one this far back does not vote.
  constexpr double kMaxStepBack = 0.6;   // m along the beam
  const double step = grid.resolution();
  const Eigen::Vector2d origin = pose.translation();
  const PointTransform to_world(pose);
  double inliers = 0.0, same_side = 0.0;
  for (const ScanPoint& p : points) {
    const Eigen::Vector2d hit = to_world(p.x, p.y);
    if (!near_obstacle(grid, grid.cell_of(hit))) continue;
    const Eigen::Vector2d to_hit = hit - origin;
    const double range = to_hit.norm();
    std::optional<CellIndex> before;
    for (double back = kApproach; back <= std::min(kMaxStepBack, range); back += step) {
      const CellIndex c = grid.cell_of(hit - to_hit * (back / range));
      if (!is_obstacle(grid.at(c))) {
        before = c;
        break;
      }
    }
    if (!before) continue;
    inliers += p.weight;
    // Far from every viewpoint the beams that crossed the space before a wall
    // are sparser than the cells: seen free within a cell of the approach.
    if (in_neighbourhood(grid, *before, [](const DsMass& m) { return m.free >= kSeenFree && m.free > m.occupied; }))
      same_side += p.weight;
  }
  return inliers > 0.0 ? same_side / inliers : 0.0;
}

}  // namespace dsswarm
