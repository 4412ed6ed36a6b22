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
  tile_.resize(n);
  local_.resize(n);
  for (auto& v : occupied_) v.resize(n);
  if (unknown_value_ != 0.0f)
    for (auto& v : free_) v.resize(n);
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
  std::uint32_t* tile = tile_.data();
  std::int32_t* local = local_.data();
  constexpr std::int32_t kBits = DsGrid::kTileBits, kLast = DsGrid::kTileSize - 1;
  for (std::size_t i = 0; i < n; ++i) {
    const float gx = fx + c * x[i] - s * y[i], gy = fy + s * x[i] + c * y[i];
    const std::int32_t fx_cell = floor_to_cell(gx), fy_cell = floor_to_cell(gy);
    ax[i] = gx - static_cast<float>(fx_cell);
    ay[i] = gy - static_cast<float>(fy_cell);
    ix[i] = bx + fx_cell;
    iy[i] = by + fy_cell;
  }
  // A loop of its own: with more arrays in one loop the compiler no longer vectorises it.
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t cx = ix[i], cy = iy[i];
    const std::int32_t lx = cx & kLast, ly = cy & kLast;
    const std::uint32_t straddles = (lx == kLast) | (ly == kLast);  // no branch: the loop stays vectorised
    // The tile's coordinates in one number, 15 and 16 bits (they tell apart
    // every tile within kTileSize · 2^15 cells, far beyond a scan), and in
    // the top bit whether the block straddles tiles.
    tile[i] = (static_cast<std::uint32_t>((cy >> kBits) & 0x7fff) << 16) |
              static_cast<std::uint32_t>((cx >> kBits) & 0xffff) | (straddles << 31);
    local[i] = (ly << kBits) | lx;
  }
}

template <bool kWithFree>
void ScanScorer::gather() const {
  // Read where no tile was allocated: no branch per point for it.
  static const std::array<PackedMass, DsGrid::kTileCells> kNothing{};
  const std::size_t n = x_.size();
  if (n == 0) return;
  // The first point's tile, never a straddling key: those always take the slow path.
  std::uint32_t current = tile_[0] & 0x7fffffffU;
  const PackedMass* cells = grid_->tile_cells({ix_[0], iy_[0]});
  if (!cells) cells = kNothing.data();
  // Plain pointers: the compiler then keeps them in registers, not reloading
  // each array's from its vector for every store.
  std::int32_t* const occupied[4] = {occupied_[0].data(), occupied_[1].data(), occupied_[2].data(),
                                     occupied_[3].data()};
  std::int32_t* const free[4] = {free_[0].data(), free_[1].data(), free_[2].data(), free_[3].data()};
  const std::uint32_t* const tile = tile_.data();
  const std::int32_t* const local = local_.data();
  for (std::size_t i = 0; i < n; ++i) {
    if (tile[i] != current) {
      if (tile[i] >> 31) {  // the 2×2 block straddles tiles
        PackedMass q[4];
        grid_->packed_quad({ix_[i], iy_[i]}, q);
        for (std::size_t j = 0; j < 4; ++j) {
          occupied[j][i] = q[j].occupied;
          if constexpr (kWithFree) free[j][i] = q[j].free;
        }
        continue;
      }
      current = tile[i];
      cells = grid_->tile_cells({ix_[i], iy_[i]});
      if (!cells) cells = kNothing.data();
    }
    const PackedMass* c = cells + local[i];
    constexpr std::size_t kUp = DsGrid::kTileSize;
    occupied[0][i] = c[0].occupied;
    occupied[1][i] = c[1].occupied;
    occupied[2][i] = c[kUp].occupied;
    occupied[3][i] = c[kUp + 1].occupied;
    if constexpr (kWithFree) {
      free[0][i] = c[0].free;
      free[1][i] = c[1].free;
      free[2][i] = c[kUp].free;
      free[3][i] = c[kUp + 1].free;
    }
  }
}

template <bool kCountsUnknown>
double ScanScorer::sum(const Pose2& pose) const {
  place(pose);
  gather<kCountsUnknown>();
  // Cells are read in their stored units (1 = PackedMass::kOne) and the sum
  // scaled once at the end. This pass has no branches and no lookups: the
  // compiler does several points per instruction, in kLanes partial sums.
  const float u = unknown_value_, kept = 1.0f - unknown_value_, base = unknown_value_ * PackedMass::kOne;
  const auto value = [&](std::size_t j, std::size_t i) {
    const auto o = static_cast<float>(occupied_[j][i]);
    if constexpr (kCountsUnknown) return base + kept * o - u * static_cast<float>(free_[j][i]);
    else return o;
  };
  const auto weighted = [&](std::size_t i) {
    const float ax = ax_[i], ay = ay_[i];
    return w_[i] * ((1 - ay) * ((1 - ax) * value(0, i) + ax * value(1, i)) +
                    ay * ((1 - ax) * value(2, i) + ax * value(3, i)));
  };
  constexpr std::size_t kLanes = 8;
  float lanes[kLanes] = {};
  const std::size_t n = x_.size(), whole = n - n % kLanes;
  for (std::size_t i = 0; i < whole; i += kLanes)
    for (std::size_t l = 0; l < kLanes; ++l) lanes[l] += weighted(i + l);
  float total = 0.0f;
  for (std::size_t i = whole; i < n; ++i) total += weighted(i);
  for (const float l : lanes) total += l;
  return static_cast<double>(total) / static_cast<double>(PackedMass::kOne);
}

template double ScanScorer::sum<false>(const Pose2&) const;
template double ScanScorer::sum<true>(const Pose2&) const;

}  // namespace dsswarm
