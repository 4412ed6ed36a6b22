#pragma once
// Pose score of the chapter's eq. (1): Σ over scan points of the occupancy of
// the cell the point falls in, times the point's weight — normalised by Σ w so
// scores of different scans compare (0 = every point in free space, 1 = every
// point on a surely occupied cell). Occupancy is interpolated bilinearly
// between the four nearest cell centres, which makes the score continuous in
// the pose and gives the matcher a slope to climb within a cell.
#include <array>
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/ds_grid.hpp"
#include "grid/sampling.hpp"
#include "sensor/scan_points.hpp"

namespace dsswarm {

// One scan made ready to score many poses against one grid: the matcher's
// inner loop. The points are kept in the grid's cell units with weights that
// sum to 1. A pose is scored in three passes: all points are placed (a
// rotation and a floor each, written so the compiler does several per
// instruction); the four stored cells around each are fetched (consecutive
// points mostly fall in one tile, whose lookup is kept from the point
// before); then all are interpolated and weighted, again several at a time.
// Not for concurrent use: scoring writes the scorer's scratch arrays.
class ScanScorer {
 public:
  // Uses every `stride`-th point (coarse levels need fewer points).
  // `unknown_value`: the share of a cell's unknown mass that counts as
  // occupancy (see cell_value in grid/sampling.hpp).
  ScanScorer(const DsGrid& grid, const std::vector<ScanPoint>& points, std::size_t stride = 1,
             float unknown_value = 0.0f);

  // Weighted mean occupancy under the points placed at `pose`, in [0, 1].
  double score(const Pose2& pose) const {
    return unknown_value_ == 0.0f ? sum<false>(pose) : sum<true>(pose);
  }

  const DsGrid& grid() const { return *grid_; }

 private:
  template <bool kCountsUnknown>
  double sum(const Pose2& pose) const;
  // Each point's bilinear block and offsets at `pose`, into the scratch arrays.
  void place(const Pose2& pose) const;
  // The stored masses of each point's block (DsGrid::quad order), into the
  // scratch arrays: the only pass that looks cells up.
  template <bool kWithFree>
  void gather() const;

  const DsGrid* grid_;
  std::vector<float> x_, y_;  // the points, in cells
  std::vector<float> w_;      // their weights, normalised to sum 1
  float unknown_value_;
  mutable std::vector<std::int32_t> ix_, iy_;  // scratch for place()
  mutable std::vector<float> ax_, ay_;
  mutable std::vector<std::uint32_t> tile_;  // each point's tile key (top bit: its block straddles tiles)
  mutable std::vector<std::int32_t> local_;  // the block's lower-left cell's index in its tile
  mutable std::array<std::vector<std::int32_t>, 4> occupied_, free_;  // scratch for gather()
};

// Weighted mean occupancy under every `stride`-th point of `points` at `pose`.
inline double score_pose(const DsGrid& grid, const std::vector<ScanPoint>& points, const Pose2& pose,
                         std::size_t stride = 1, float unknown_value = 0.0f) {
  return ScanScorer(grid, points, stride, unknown_value).score(pose);
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
  const PointTransform to_world(pose);
  double total = 0.0, known = 0.0, inliers = 0.0;
  for (const ScanPoint& p : points) {
    const CellIndex c = grid.cell_of(to_world(p.x, p.y));
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
