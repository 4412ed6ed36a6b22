#include "sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dsswarm {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

double point_segment_distance(const Eigen::Vector2d& p, const Segment& s) {
  const Eigen::Vector2d e = s.b - s.a;
  const double len2 = e.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - s.a).dot(e) / len2, 0.0, 1.0) : 0.0;
  return (s.a + t * e - p).norm();
}

// Proper or touching crossing. Collinear pairs return false: for them the
// endpoint distances below are already exact (0 when they overlap).
bool segments_cross(const Segment& s, const Segment& r) {
  const double d1 = cross(s.b - s.a, r.a - s.a), d2 = cross(s.b - s.a, r.b - s.a);
  const double d3 = cross(r.b - r.a, s.a - r.a), d4 = cross(r.b - r.a, s.b - r.a);
  if (d1 == 0 && d2 == 0) return false;
  return d1 * d2 <= 0 && d3 * d4 <= 0;
}

double segment_segment_distance(const Segment& s, const Segment& r) {
  if (segments_cross(s, r)) return 0.0;
  return std::min({point_segment_distance(s.a, r), point_segment_distance(s.b, r), point_segment_distance(r.a, s),
                   point_segment_distance(r.b, s)});
}

}  // namespace

World::World(std::vector<Segment> walls, std::vector<Box> solids, BuildingLayout layout)
    : segments_(std::move(walls)), solids_(std::move(solids)), layout_(std::move(layout)) {
  for (const Box& b : solids_) {
    const Eigen::Vector2d c1 = b.min, c2(b.max.x(), b.min.y()), c3 = b.max, c4(b.min.x(), b.max.y());
    segments_.push_back({c1, c2});
    segments_.push_back({c2, c3});
    segments_.push_back({c3, c4});
    segments_.push_back({c4, c1});
  }
  bounds_ = {Eigen::Vector2d(kInf, kInf), Eigen::Vector2d(-kInf, -kInf)};
  for (const Segment& s : segments_) {
    bounds_.min = bounds_.min.cwiseMin(s.a).cwiseMin(s.b);
    bounds_.max = bounds_.max.cwiseMax(s.a).cwiseMax(s.b);
  }
  if (segments_.empty()) bounds_ = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  build_grid();
}

void World::build_grid() {
  // About 1 m cells: a beam crosses a few dozen cells, each holding a handful
  // of segments, instead of testing every segment of the building.
  constexpr int kMaxCellsPerAxis = 1024;
  const Eigen::Vector2d pad(0.5, 0.5);
  grid_min_ = bounds_.min - pad;
  const Eigen::Vector2d extent = bounds_.max + pad - grid_min_;
  cell_size_ = std::max({1.0, extent.x() / kMaxCellsPerAxis, extent.y() / kMaxCellsPerAxis});
  grid_nx_ = std::max(1, static_cast<int>(std::ceil(extent.x() / cell_size_)));
  grid_ny_ = std::max(1, static_cast<int>(std::ceil(extent.y() / cell_size_)));

  // Each segment goes into every cell its (slightly grown) bounding box touches;
  // the grid is only a filter, the exact test happens per segment.
  auto for_each_cell_of = [&](const Segment& s, auto&& visit) {
    const double eps = 1e-9;
    const Eigen::Vector2d lo = s.a.cwiseMin(s.b) - grid_min_, hi = s.a.cwiseMax(s.b) - grid_min_;
    auto cell = [&](double v, int n) { return std::clamp(static_cast<int>(std::floor(v / cell_size_)), 0, n - 1); };
    for (int y = cell(lo.y() - eps, grid_ny_); y <= cell(hi.y() + eps, grid_ny_); ++y)
      for (int x = cell(lo.x() - eps, grid_nx_); x <= cell(hi.x() + eps, grid_nx_); ++x)
        visit(static_cast<std::size_t>(y) * static_cast<std::size_t>(grid_nx_) + static_cast<std::size_t>(x));
  };
  const std::size_t n_cells = static_cast<std::size_t>(grid_nx_) * static_cast<std::size_t>(grid_ny_);
  cell_begin_.assign(n_cells + 1, 0);
  for (const Segment& s : segments_) for_each_cell_of(s, [&](std::size_t c) { ++cell_begin_[c + 1]; });
  for (std::size_t i = 1; i <= n_cells; ++i) cell_begin_[i] += cell_begin_[i - 1];
  cell_segments_.assign(cell_begin_.back(), 0);
  std::vector<std::uint32_t> fill(cell_begin_.begin(), cell_begin_.end() - 1);
  for (std::size_t k = 0; k < segments_.size(); ++k)
    for_each_cell_of(segments_[k], [&](std::size_t c) { cell_segments_[fill[c]++] = static_cast<std::uint32_t>(k); });
}

bool World::clip_to_grid(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double& t_enter,
                         double& t_leave) const {
  const Eigen::Vector2d grid_max = grid_min_ + cell_size_ * Eigen::Vector2d(grid_nx_, grid_ny_);
  for (int k = 0; k < 2; ++k) {
    if (dir[k] == 0.0) {
      if (origin[k] < grid_min_[k] || origin[k] > grid_max[k]) return false;
      continue;
    }
    double ta = (grid_min_[k] - origin[k]) / dir[k], tb = (grid_max[k] - origin[k]) / dir[k];
    if (ta > tb) std::swap(ta, tb);
    t_enter = std::max(t_enter, ta);
    t_leave = std::min(t_leave, tb);
    if (t_enter > t_leave) return false;
  }
  return true;
}

double World::nearest_in_cell(std::size_t cell, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                              double best) const {
  for (std::uint32_t i = cell_begin_[cell]; i < cell_begin_[cell + 1]; ++i) {
    const Segment& s = segments_[cell_segments_[i]];
    const Eigen::Vector2d e = s.b - s.a;
    const double denom = cross(dir, e);
    if (std::abs(denom) < 1e-12) continue;  // parallel: a beam grazing a wall end-on sees its neighbours
    const Eigen::Vector2d ao = s.a - origin;
    const double t = cross(ao, e) / denom;
    const double u = cross(ao, dir) / denom;
    if (t >= 0.0 && t < best && u >= 0.0 && u <= 1.0) best = t;
  }
  return best;
}

double World::raycast(const Eigen::Vector2d& origin, double angle, double max_range) const {
  if (segments_.empty() || !(max_range > 0.0)) return kInf;
  const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
  double t_enter = 0.0, t_leave = max_range;
  if (!clip_to_grid(origin, dir, t_enter, t_leave)) return kInf;

  // Walk the cells along the ray (Amanatides & Woo) and stop at the first cell
  // whose exit lies beyond the nearest hit found so far.
  const Eigen::Vector2d start = origin + t_enter * dir - grid_min_;
  int cx = std::clamp(static_cast<int>(std::floor(start.x() / cell_size_)), 0, grid_nx_ - 1);
  int cy = std::clamp(static_cast<int>(std::floor(start.y() / cell_size_)), 0, grid_ny_ - 1);
  const int step_x = dir.x() > 0 ? 1 : -1, step_y = dir.y() > 0 ? 1 : -1;
  auto first_boundary = [&](int c, int step, int k) {
    if (dir[k] == 0.0) return kInf;
    const double boundary = grid_min_[k] + (c + (step > 0 ? 1 : 0)) * cell_size_;
    return (boundary - origin[k]) / dir[k];
  };
  double t_next_x = first_boundary(cx, step_x, 0), t_next_y = first_boundary(cy, step_y, 1);
  const double dt_x = dir.x() != 0.0 ? cell_size_ / std::abs(dir.x()) : kInf;
  const double dt_y = dir.y() != 0.0 ? cell_size_ / std::abs(dir.y()) : kInf;

  double best = kInf;
  for (;;) {
    const std::size_t cell = static_cast<std::size_t>(cy) * static_cast<std::size_t>(grid_nx_) + static_cast<std::size_t>(cx);
    best = nearest_in_cell(cell, origin, dir, best);
    const double t_exit = std::min(t_next_x, t_next_y);
    if (best <= t_exit || t_exit > t_leave) break;
    if (t_next_x < t_next_y) {
      cx += step_x;
      t_next_x += dt_x;
      if (cx < 0 || cx >= grid_nx_) break;
    } else {
      cy += step_y;
      t_next_y += dt_y;
      if (cy < 0 || cy >= grid_ny_) break;
    }
  }
  return best <= max_range ? best : kInf;
}

double World::clearance(const Eigen::Vector2d& p) const {
  for (const Box& b : solids_)
    if (b.contains(p)) return 0.0;
  double d = kInf;
  for (const Segment& s : segments_) d = std::min(d, point_segment_distance(p, s));
  return d;
}

bool World::is_free(const Eigen::Vector2d& p, double required) const { return clearance(p) >= required; }

bool World::is_segment_free(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double required) const {
  // Free ends and no wall within `required` of the segment: the segment can
  // then not enter a solid box either (it would have to cross an edge).
  if (!is_free(a, required) || !is_free(b, required)) return false;
  const Segment path{a, b};
  for (const Segment& s : segments_)
    if (segment_segment_distance(path, s) < required) return false;
  return true;
}

}  // namespace dsswarm
