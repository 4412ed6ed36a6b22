#include "swarm/relative_pose.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "common/errors.hpp"
#include "grid/sampling.hpp"
#include "matching/scan_scorer.hpp"

namespace dsswarm {

void RelativePoseConfig::validate() const {
  if (!(search_radius > 0.0 && search_radius <= 50.0)) throw ConfigError("encounter.search_radius must be in (0, 50] m");
  if (!(coarse_step_xy >= 0.01 && coarse_step_xy <= 1.0)) throw ConfigError("encounter.coarse_step_xy must be in [0.01, 1] m");
  if (!(coarse_step_theta >= 0.005 && coarse_step_theta <= 0.5))
    throw ConfigError("encounter.coarse_step_theta must be in [0.005, 0.5] rad");
  if (coarse_points < 10) throw ConfigError("encounter.coarse_points must be >= 10");
  if (candidates < 2 || candidates > 100) throw ConfigError("encounter.candidates must be in [2, 100]");
  if (!(surroundings_radius >= 0.0 && surroundings_radius <= 100.0))
    throw ConfigError("encounter.surroundings_radius must be in [0, 100] m");
  if (surroundings_points < 0) throw ConfigError("encounter.surroundings_points must be >= 0");
  if (!(merge_surroundings_radius >= 0.0 && merge_surroundings_radius <= 100.0))
    throw ConfigError("encounter.merge_surroundings_radius must be in [0, 100] m");
  if (merge_surroundings_points < 0) throw ConfigError("encounter.merge_surroundings_points must be >= 0");
  if (!(mode_separation_xy > 0.0) || !(mode_separation_theta > 0.0))
    throw ConfigError("encounter.mode_separation_xy and mode_separation_theta must be > 0");
  if (!(possible_same_side >= 0.0 && possible_same_side <= 1.0))
    throw ConfigError("encounter.possible_same_side must be in [0, 1]");
  refine.validate();
}

bool distinct_modes(const Pose2& a, const Pose2& b, const RelativePoseConfig& config) {
  return std::hypot(a.x - b.x, a.y - b.y) >= config.mode_separation_xy ||
         std::abs(normalize_angle(a.theta - b.theta)) >= config.mode_separation_theta;
}

namespace {

// How much the map agrees with points placed at `pose`: the mean over points
// of (occupied − free) mass, bilinear at each point. Points in unexplored
// space count 0, points in space the map has seen free count against — so a
// wrong placement is penalized for every wall it puts where the map saw
// nothing, which the plain score (occupied only) cannot tell from unexplored.
double evidence_agreement(const DsGrid& grid, const std::vector<ScanPoint>& points, const Pose2& pose) {
  if (points.empty()) return 0.0;
  const PointTransform to_world(pose);
  double sum = 0.0;
  for (const ScanPoint& p : points) {
    const Eigen::Vector2d w = to_world(p.x, p.y);
    // occupied − free = 2 × occupancy − 1 with unknown counting half.
    sum += 2.0 * interpolated_occupancy(grid, w.x(), w.y(), 0.5f) - 1.0;
  }
  return sum / static_cast<double>(points.size());
}

struct Coarse {
  float score;
  Pose2 pose;
};

// The coarse level's cell values (cell_value with unknown 0) over a box of
// cells, dense: the exhaustive search reads each cell thousands of times,
// and a tile lookup and mass decoding per read were most of its cost. Read
// through the same bilinear weights, so the same values as
// interpolated_occupancy to the bit.
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
        values_[index(x, y)] = cell_value(grid.packed_at({lo_.x + x, lo_.y + y}).mass(), 0.0f);
  }
  // The value at a world point, bilinear between cell centres (as
  // bilinear_point places it); 0 where the block around it leaves the box.
  float at(double wx, double wy) const {
    const double gx = wx * inv_res_ - 0.5, gy = wy * inv_res_ - 0.5;
    // Checked before the cell index is taken: a point however far is no overflow.
    if (!(gx >= lo_.x && gx < lo_.x + width_ - 1 && gy >= lo_.y && gy < lo_.y + height_ - 1)) return 0.0f;
    const BilinearPoint b = bilinear_cell_point(gx, gy);
    const float* row = &values_[index(b.corner.x - lo_.x, b.corner.y - lo_.y)];
    const float* above = row + width_;
    return b.interpolate(row[0], row[1], above[0], above[1]);
  }

 private:
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }

  double inv_res_;
  CellIndex lo_;
  int width_ = 0, height_ = 0;
  std::vector<float> values_;
};

// Step 1: every heading × every lattice position within the radius, on the coarsest level.
std::vector<Coarse> exhaustive_search(const DsGrid& grid, const std::vector<ScanPoint>& points,
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
  std::vector<Coarse> all;
  std::vector<Eigen::Vector2d> rotated(subset.size());
  for (int h = 0; h < headings; ++h) {
    const double theta = -std::numbers::pi + 2.0 * std::numbers::pi * h / headings;
    const PointTransform rotate = PointTransform::rotation(theta);
    for (std::size_t i = 0; i < subset.size(); ++i) rotated[i] = rotate(subset[i].x, subset[i].y);
    for (int iy = -steps_xy; iy <= steps_xy; ++iy)
      for (int ix = -steps_xy; ix <= steps_xy; ++ix) {
        if (ix * ix + iy * iy > steps_xy * steps_xy) continue;
        const double px = near.x() + ix * config.coarse_step_xy, py = near.y() + iy * config.coarse_step_xy;
        double sum = 0.0;
        for (std::size_t i = 0; i < subset.size(); ++i)
          sum += subset[i].weight * cells.at(px + rotated[i].x(), py + rotated[i].y());
        all.push_back({static_cast<float>(weight_sum > 0.0 ? sum / weight_sum : 0.0), Pose2{px, py, theta}});
      }
  }
  return all;
}

// The best `count` placements that are pairwise distinct modes.
std::vector<Pose2> distinct_best(std::vector<Coarse> all, int count, const RelativePoseConfig& config) {
  std::sort(all.begin(), all.end(), [](const Coarse& a, const Coarse& b) { return a.score > b.score; });
  std::vector<Pose2> chosen;
  for (const Coarse& c : all) {
    if (static_cast<int>(chosen.size()) >= count) break;
    bool distinct = true;
    for (const Pose2& p : chosen) distinct = distinct && distinct_modes(c.pose, p, config);
    if (distinct) chosen.push_back(c.pose);
  }
  return chosen;
}

}  // namespace

MatchResult refine_placement(const MultiResMap& map, const std::vector<ScanPoint>& points,
                       const std::vector<ScanPoint>& surroundings, const Pose2& start, const RelativePoseConfig& config,
                       std::uint64_t seed) {
  std::vector<ScanPoint> both = points;
  both.insert(both.end(), surroundings.begin(), surroundings.end());
  MatcherConfig fine = config.refine;
  fine.sigma_xy = 0.03;
  fine.sigma_theta = 0.01;
  MonteCarloMatcher polisher(fine, seed);
  return polisher.match(map, both, start);
}

std::vector<ScanPoint> surroundings_points(const MultiResMap& map, const Pose2& robot_pose, double radius,
                                           int max_points) {
  const DsGrid& grid = map.finest();
  const Pose2 to_base = robot_pose.inverse();
  std::vector<ScanPoint> all;
  const double r2 = radius * radius;
  grid.for_each_tile([&](CellIndex origin, const PackedMass* cells) {
    const Eigen::Vector2d corner = grid.cell_center(origin);
    const double reach = radius + DsGrid::kTileSize * grid.resolution() * 1.5;
    if ((corner - robot_pose.translation()).squaredNorm() > reach * reach) return;
    for (int i = 0; i < DsGrid::kTileCells; ++i) {
      const DsMass m = cells[i].mass();
      if (m.occupied < 0.5f || m.occupied <= m.free) continue;
      const Eigen::Vector2d w = grid.cell_center(DsGrid::tile_cell(origin, i));
      if ((w - robot_pose.translation()).squaredNorm() > r2) continue;
      const Eigen::Vector2d b = to_base * w;
      all.push_back({static_cast<float>(b.x()), static_cast<float>(b.y()), 1.0f});
    }
  });
  if (max_points <= 0 || static_cast<int>(all.size()) <= max_points) return all;
  std::vector<ScanPoint> thinned;
  const double step = static_cast<double>(all.size()) / max_points;
  for (int k = 0; k < max_points; ++k) thinned.push_back(all[static_cast<std::size_t>(k * step)]);
  return thinned;
}

RelativePoseResult locate_scan(const MultiResMap& map, const std::vector<ScanPoint>& points,
                               const Eigen::Vector2d& near, const RelativePoseConfig& config, std::uint64_t seed,
                               const std::vector<ScanPoint>& surroundings) {
  config.validate();
  RelativePoseResult result;
  if (points.empty()) return result;
  const DsGrid& coarse = map.level(map.levels() - 1);
  std::vector<Coarse> all = exhaustive_search(coarse, points, near, config);
  result.evaluations = static_cast<int>(all.size());
  const std::vector<Pose2> starts = distinct_best(std::move(all), config.candidates, config);

  MonteCarloMatcher matcher(config.refine, seed);
  std::vector<PoseHypothesis> refined;
  for (const Pose2& start : starts) {
    const MatchResult m = matcher.match(map, points, start);
    result.evaluations += m.evaluations;
    const double around = surroundings.empty() ? m.score : evidence_agreement(map.finest(), surroundings, m.pose);
    refined.push_back({m.pose, m.score, around, 0.0, 0.0});
  }
  if (refined.empty()) return result;
  const auto possible = [&](const PoseHypothesis& h) { return h.same_side_ratio >= config.possible_same_side; };
  for (PoseHypothesis& h : refined) h.same_side_ratio = same_side_ratio(map.finest(), points, h.pose);
  std::sort(refined.begin(), refined.end(), [&](const PoseHypothesis& a, const PoseHypothesis& b) {
    if (possible(a) != possible(b)) return possible(a);
    return a.surroundings_score > b.surroundings_score;
  });
  if (!surroundings.empty()) {
    // Final placement: the scan and the surroundings together.
    const MatchResult m = refine_placement(map, points, surroundings, refined.front().pose, config, seed + 1);
    result.evaluations += m.evaluations;
    const Pose2 pose = m.pose;
    refined.front().pose = pose;
    refined.front().score = score_pose(map.finest(), points, pose);
    refined.front().surroundings_score = evidence_agreement(map.finest(), surroundings, pose);
    refined.front().same_side_ratio = same_side_ratio(map.finest(), points, pose);
  }
  for (PoseHypothesis& h : refined) {
    const MatchQuality q = match_quality(map.finest(), points, h.pose);
    h.inlier_ratio = q.inlier_ratio;
    h.known_fraction = q.known_fraction;
  }
  result.best = refined.front();
  for (std::size_t i = 1; i < refined.size(); ++i)
    if (distinct_modes(refined[i].pose, result.best.pose, config) &&
        (possible(refined[i]) || !possible(result.best))) {
      result.runner_up = refined[i];
      break;
    }
  return result;
}

}  // namespace dsswarm
