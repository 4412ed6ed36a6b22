#include "matching/scan_scorer.hpp"

#include <limits>

namespace dsswarm {

ScanScorer::ScanScorer(const DsGrid& grid, const std::vector<ScanPoint>& points, std::size_t stride,
                       float unknown_value)
    : grid_(&grid), unknown_value_(unknown_value) {
  const double inv = 1.0 / grid.resolution();
  double weights = 0.0;
  for (std::size_t i = 0; i < points.size(); i += stride) weights += points[i].weight;
  if (weights <= 0.0) return;  // nothing to score: every pose scores 0
  const std::size_t n = (points.size() + stride - 1) / stride;
  x_.reserve(n);
  y_.reserve(n);
  w_.reserve(n);
  for (std::size_t i = 0; i < points.size(); i += stride) {
    x_.push_back(points[i].x * inv);
    y_.push_back(points[i].y * inv);
    w_.push_back(static_cast<float>(points[i].weight / weights));
  }
}

template <bool kCountsUnknown>
double ScanScorer::sum(const Pose2& pose) const {
  constexpr int kLast = DsGrid::kTileSize - 1;
  const auto value = [this](const DsMass& m) {
    if constexpr (kCountsUnknown) return cell_value(m, unknown_value_);
    else return m.occupied;
  };
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  const double inv = 1.0 / grid_->resolution();
  // Cell units from cell centres: the bilinear block's corner is the floor.
  const double ox = pose.x * inv - 0.5, oy = pose.y * inv - 0.5;
  const float vacuous = value(DsMass::vacuous());
  const DsMass* tile = nullptr;
  std::int32_t tile_x = std::numeric_limits<std::int32_t>::min(), tile_y = tile_x;
  double total = 0.0;
  for (std::size_t i = 0; i < x_.size(); ++i) {
    const BilinearPoint b = bilinear_cell_point(ox + c * x_[i] - s * y_[i], oy + s * x_[i] + c * y_[i]);
    const CellIndex k = b.corner;
    float v;
    if ((k.x & kLast) != kLast && (k.y & kLast) != kLast) {  // the 2×2 block lies in one tile
      if ((k.x >> DsGrid::kTileBits) != tile_x || (k.y >> DsGrid::kTileBits) != tile_y) {
        tile = grid_->tile_cells(k);
        tile_x = k.x >> DsGrid::kTileBits;
        tile_y = k.y >> DsGrid::kTileBits;
      }
      if (!tile) {
        v = vacuous;
      } else {
        const DsMass* q = tile + DsGrid::local_index(k);
        v = b.interpolate(value(q[0]), value(q[1]), value(q[DsGrid::kTileSize]), value(q[DsGrid::kTileSize + 1]));
      }
    } else {
      DsMass q[4];
      grid_->quad(k, q);
      v = b.interpolate(value(q[0]), value(q[1]), value(q[2]), value(q[3]));
    }
    total += static_cast<double>(w_[i] * v);
  }
  return total;
}

template double ScanScorer::sum<false>(const Pose2&) const;
template double ScanScorer::sum<true>(const Pose2&) const;

}  // namespace dsswarm
