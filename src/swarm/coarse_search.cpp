#include "swarm/coarse_search.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "grid/sampling.hpp"

namespace dsswarm {
namespace {

// Where a coordinate falls between the cells of one axis of DenseCells.
struct AxisSample {
  std::size_t offset = 0;  // of the block's first cell along this axis, in values_ steps
  float fraction = 0.0f;   // bilinear weight of the block's second cell
  bool inside = false;     // the block lies within the box
};

// The coarse level's cell values (cell_value with unknown 0) over a box of
// cells, dense: the exhaustive search reads each cell thousands of times,
// and a tile lookup and mass decoding per read were most of its cost. Read
// through the same bilinear weights, so the same values as
// interpolated_occupancy to the bit. A lattice pose's x and y enter apart,
// so each axis is sampled once per heading and lattice column or row.
class DenseCells {
 public:
  // The cells a point within `reach` of `centre` can touch, cut to the
  // grid's bounds: beyond them every cell is vacuous (value 0), so the box
  // stops two cells past them and a block of four that leaves it holds only
  // vacuous cells. A scan point however far (another robot's, off the wire)
  // costs no memory.
  DenseCells(const DsGrid& grid, const Eigen::Vector2d& centre, double reach) : inv_res_(1.0 / grid.resolution()) {
    CellIndex held_lo, held_hi;
    grid.bounds(held_lo, held_hi);
    const auto first = [&](double c, std::int32_t held) {
      return floor_to_cell(std::max((c - reach) * inv_res_ - 2.0, static_cast<double>(held) - 2.0));
    };
    const auto last = [&](double c, std::int32_t held) {  // one past
      return floor_to_cell(std::min((c + reach) * inv_res_ + 3.0, static_cast<double>(held) + 2.0));
    };
    lo_ = {first(centre.x(), held_lo.x), first(centre.y(), held_lo.y)};
    width_ = std::max(0, last(centre.x(), held_hi.x) - lo_.x);
    height_ = std::max(0, last(centre.y(), held_hi.y) - lo_.y);
    values_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x)
        values_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)] =
            cell_value(grid.packed_at({lo_.x + x, lo_.y + y}).mass(), 0.0f);
  }

  // A world x or y, bilinear between cell centres (as bilinear_point places
  // it). Checked before the cell index is taken: a point however far is no overflow.
  AxisSample x_sample(double wx) const { return sample(wx, lo_.x, width_, 1); }
  AxisSample y_sample(double wy) const { return sample(wy, lo_.y, height_, static_cast<std::size_t>(width_)); }

  // The value at the point the two samples make; 0 where its block leaves the box.
  float at(const AxisSample& x, const AxisSample& y) const {
    if (!x.inside || !y.inside) return 0.0f;
    const float* row = &values_[y.offset + x.offset];
    const float* above = row + width_;
    return BilinearPoint{{}, x.fraction, y.fraction}.interpolate(row[0], row[1], above[0], above[1]);
  }

 private:
  AxisSample sample(double w, std::int32_t lo, int size, std::size_t step) const {
    const double g = w * inv_res_ - 0.5;
    if (!(g >= lo && g < lo + size - 1)) return {};
    const std::int32_t cell = floor_to_cell(g);
    return {static_cast<std::size_t>(cell - lo) * step, static_cast<float>(g - cell), true};
  }

  double inv_res_;
  CellIndex lo_;
  int width_ = 0, height_ = 0;
  std::vector<float> values_;
};

// The ranking: higher score first, ties in search order (a strict total
// order, so sorting any slice of it agrees with sorting the whole).
bool ranks_before(const CoarsePlacement& a, const CoarsePlacement& b) {
  return a.score > b.score || (a.score == b.score && a.rank_tie < b.rank_tie);
}

}  // namespace

std::vector<CoarsePlacement> exhaustive_search(const DsGrid& grid, const std::vector<ScanPoint>& points,
                                               const Eigen::Vector2d& near, const RelativePoseConfig& config) {
  const std::size_t stride = std::max<std::size_t>(1, points.size() / static_cast<std::size_t>(config.coarse_points));
  std::vector<ScanPoint> subset;
  for (std::size_t i = 0; i < points.size(); i += stride) subset.push_back(points[i]);
  double weight_sum = 0.0, farthest = 0.0;
  for (const ScanPoint& p : subset) {
    weight_sum += p.weight;
    farthest = std::max(farthest, std::hypot(double(p.x), double(p.y)));
  }

  const int steps_xy = static_cast<int>(std::floor(config.search_radius / config.coarse_step_xy));
  const int headings = std::max(1, static_cast<int>(std::lround(2.0 * std::numbers::pi / config.coarse_step_theta)));
  const DenseCells cells(grid, near, steps_xy * config.coarse_step_xy + farthest);
  const std::size_t n = subset.size(), side = static_cast<std::size_t>(2 * steps_xy + 1);
  std::vector<AxisSample> xs(side * n), ys(side * n);  // [lattice column or row][point]
  std::vector<CoarsePlacement> all;
  for (int h = 0; h < headings; ++h) {
    const double theta = -std::numbers::pi + 2.0 * std::numbers::pi * h / headings;
    const PointTransform rotate = PointTransform::rotation(theta);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d r = rotate(subset[i].x, subset[i].y);
      for (int k = -steps_xy; k <= steps_xy; ++k) {
        const std::size_t at = static_cast<std::size_t>(k + steps_xy) * n + i;
        xs[at] = cells.x_sample(near.x() + k * config.coarse_step_xy + r.x());
        ys[at] = cells.y_sample(near.y() + k * config.coarse_step_xy + r.y());
      }
    }
    for (int iy = -steps_xy; iy <= steps_xy; ++iy)
      for (int ix = -steps_xy; ix <= steps_xy; ++ix) {
        if (ix * ix + iy * iy > steps_xy * steps_xy) continue;
        const AxisSample* x = &xs[static_cast<std::size_t>(ix + steps_xy) * n];
        const AxisSample* y = &ys[static_cast<std::size_t>(iy + steps_xy) * n];
        double sum = 0.0;
        for (std::size_t i = 0; i < n; ++i) sum += subset[i].weight * cells.at(x[i], y[i]);
        const double px = near.x() + ix * config.coarse_step_xy, py = near.y() + iy * config.coarse_step_xy;
        all.push_back({static_cast<float>(weight_sum > 0.0 ? sum / weight_sum : 0.0),
                       static_cast<std::uint32_t>(all.size()), Pose2{px, py, theta}});
      }
  }
  return all;
}

std::vector<Pose2> distinct_best(std::vector<CoarsePlacement> all, int count, const RelativePoseConfig& config) {
  // Only the top of the ranking is read (each mode rules out its few hundred
  // lattice neighbours), so it is sorted a slice at a time, not whole.
  constexpr std::size_t kFirstSlice = 4096;
  std::vector<Pose2> chosen;
  std::size_t sorted = 0;
  for (std::size_t next = 0; static_cast<int>(chosen.size()) < count && next < all.size(); ++next) {
    if (next == sorted) {
      const std::size_t end = std::min(all.size(), std::max(kFirstSlice, 4 * sorted));
      const auto first = all.begin() + static_cast<std::ptrdiff_t>(sorted);
      const auto last = all.begin() + static_cast<std::ptrdiff_t>(end);
      if (last != all.end()) std::nth_element(first, last, all.end(), ranks_before);
      std::sort(first, last, ranks_before);
      sorted = end;
    }
    const Pose2& candidate = all[next].pose;
    bool distinct = true;
    for (const Pose2& p : chosen) distinct = distinct && distinct_modes(candidate, p, config);
    if (distinct) chosen.push_back(candidate);
  }
  return chosen;
}

}  // namespace dsswarm
