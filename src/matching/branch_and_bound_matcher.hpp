#pragma once
// Global scan matching by multi-resolution branch and bound (the fast
// correlative matcher of Hess et al. 2016, Cartographer): the exact best pose
// of a scan within a search window (x, y, θ) around a prior, without trying
// every pose. It is what loop closure needs: after a long loop the prior is
// off by metres and degrees, far beyond the Monte-Carlo matcher's basin.
//
//   * Each cell's value is its occupied minus its free mass, quantized to a
//     byte: points in space the map has seen free count against a pose,
//     unexplored space counts nothing (so a scan shifted along a corridor,
//     whose far wall lands in free space, scores less). Bound
//     level h holds, per cell, the maximum over the 2^h × 2^h block of cells
//     starting there: the best any of the 2^h × 2^h translations of a
//     candidate could score at each point, so a block's score bounds every
//     pose inside it.
//   * Headings are tried in steps small enough that the farthest point moves
//     by at most one cell; per heading the scan is rotated and discretized
//     once, and a pose's score is a sum of table lookups.
//   * Depth-first over the blocks, best first; a block whose bound is no
//     better than the best pose found so far is pruned with all it contains.
//
// The score is the weighted mean value under the points, in [-1, 1], on the
// cells as they are (no interpolation): the evidence agreement the swarm
// ranks placements by (swarm/relative_pose).
#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/pose2.hpp"
#include "grid/ds_grid.hpp"
#include "sensor/scan_points.hpp"

namespace dsswarm {

struct SearchWindow {
  double xy = 1.0;     // m, half-width of the square of positions searched
  double theta = 0.3;  // rad, half-width of the headings searched
};

struct BranchAndBoundResult {
  Pose2 pose;
  double score = 0.0;
};

class BranchAndBoundMatcher {
 public:
  static constexpr std::uint8_t kUnknownByte = 128;  // a vacuous cell's value (0, rounded)

  // Precomputes the bounds of `grid` deep enough for windows up to
  // `max_window_xy` metres (the deepest level's blocks span the whole
  // window) but at most `max_depth` levels (wider windows start from several
  // blocks), over the cells [region_min, region_max) only when given (scan
  // points outside it read as unknown): bounds cost a byte per cell and level.
  BranchAndBoundMatcher(const DsGrid& grid, double max_window_xy, int max_depth = 16,
                        std::optional<CellIndex> region_min = std::nullopt,
                        std::optional<CellIndex> region_max = std::nullopt);
  // No bounds yet: rebuild() before match().
  BranchAndBoundMatcher() = default;
  // The same for another grid, in this matcher's memory: bounds are
  // megabytes, and faulting fresh pages in for each target cost more than
  // building them (loop closure builds one per submap it searches).
  void rebuild(const DsGrid& grid, double max_window_xy, int max_depth = 16,
               std::optional<CellIndex> region_min = std::nullopt,
               std::optional<CellIndex> region_max = std::nullopt);

  // The best pose within `window` around `prior` scoring more than
  // `min_score`, if any. `points` are in the robot frame; pass few (a couple
  // of hundred) and none far beyond the structure to be matched: the
  // farthest point sets the heading step. With `exclude`, poses within
  // `exclude_xy` and `exclude_theta` of it do not count (the runner-up search).
  std::optional<BranchAndBoundResult> match(const std::vector<ScanPoint>& points, const Pose2& prior,
                                            const SearchWindow& window, double min_score,
                                            const std::optional<Pose2>& exclude = std::nullopt,
                                            double exclude_xy = 0.0, double exclude_theta = 0.0) const;

  // The score match() maximizes, of `points` placed at `pose`.
  double score(const std::vector<ScanPoint>& points, const Pose2& pose) const;
  // The heading step match() takes for `points`: the farthest moves one cell.
  double heading_step(const std::vector<ScanPoint>& points) const;

  double resolution() const { return resolution_; }
  int depth() const { return static_cast<int>(levels_.size()); }
  std::size_t memory_bytes() const;

 private:
  // Bound level h: values over [origin, origin + size) in cells, row-major;
  // cells outside read as unknown.
  struct Level {
    CellIndex origin;
    std::int32_t width = 0, height = 0;
    std::vector<std::uint8_t> values;
    std::uint8_t at(std::int32_t x, std::int32_t y) const {
      const std::int32_t lx = x - origin.x, ly = y - origin.y;
      if (lx < 0 || ly < 0 || lx >= width || ly >= height) return kUnknownByte;
      return values[static_cast<std::size_t>(ly) * static_cast<std::size_t>(width) + static_cast<std::size_t>(lx)];
    }
  };
  struct Search;
  // `next`: the level of blocks twice as wide as `prev`'s (blocks of s cells).
  void double_into(const Level& prev, std::int32_t s, Level& next);

  double resolution_ = 0.0;
  std::vector<Level> levels_;       // levels_[h]: blocks of 2^h cells
  std::vector<std::uint8_t> along_x_;  // double_into's scratch
};

}  // namespace dsswarm
