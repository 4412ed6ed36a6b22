#include "matching/scan_scorer.hpp"

#include <cmath>
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
    x_.push_back(static_cast<float>(points[i].x * inv));
    y_.push_back(static_cast<float>(points[i].y * inv));
    w_.push_back(static_cast<float>(points[i].weight / weights));
  }
  ix_.resize(n);
  iy_.resize(n);
  ax_.resize(n);
  ay_.resize(n);
}

void ScanScorer::place(const Pose2& pose) const {
  // Single precision is ample relative to the cell the pose is in (points lie
  // within the lidar's range, a few thousand cells at most), and lets the
  // compiler transform and floor several points per instruction.
  const double inv = 1.0 / grid_->resolution();
  const double ox = pose.x * inv - 0.5, oy = pose.y * inv - 0.5;  // from cell centres
  const CellIndex base{floor_to_cell(ox), floor_to_cell(oy)};
  const auto c = static_cast<float>(std::cos(pose.theta)), s = static_cast<float>(std::sin(pose.theta));
  const auto fx = static_cast<float>(ox - base.x), fy = static_cast<float>(oy - base.y);
  const std::int32_t bx = base.x, by = base.y;
  const std::size_t n = x_.size();
  const float* x = x_.data();
  const float* y = y_.data();
  std::int32_t* ix = ix_.data();
  std::int32_t* iy = iy_.data();
  float* ax = ax_.data();
  float* ay = ay_.data();
  for (std::size_t i = 0; i < n; ++i) {
    const float gx = fx + c * x[i] - s * y[i], gy = fy + s * x[i] + c * y[i];
    const std::int32_t fx_cell = floor_to_cell(gx), fy_cell = floor_to_cell(gy);
    ax[i] = gx - static_cast<float>(fx_cell);
    ay[i] = gy - static_cast<float>(fy_cell);
    ix[i] = bx + fx_cell;
    iy[i] = by + fy_cell;
  }
}

template <bool kCountsUnknown>
double ScanScorer::sum(const Pose2& pose) const {
  constexpr int kLast = DsGrid::kTileSize - 1;
  const auto value = [&](const DsMass& m) {
    if constexpr (kCountsUnknown) return cell_value(m, unknown_value_);
    else return m.occupied;
  };
  place(pose);
  const float vacuous = value(DsMass::vacuous());
  const DsMass* tile = nullptr;
  std::int32_t tile_x = std::numeric_limits<std::int32_t>::min(), tile_y = tile_x;
  float total = 0.0f;
  for (std::size_t i = 0; i < x_.size(); ++i) {
    const BilinearPoint b{{ix_[i], iy_[i]}, ax_[i], ay_[i]};
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
    total += w_[i] * v;
  }
  return static_cast<double>(total);
}

template double ScanScorer::sum<false>(const Pose2&) const;
template double ScanScorer::sum<true>(const Pose2&) const;

}  // namespace dsswarm
