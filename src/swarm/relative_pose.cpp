#include "swarm/relative_pose.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "common/errors.hpp"
#include "grid/sampling.hpp"
#include "matching/scan_scorer.hpp"
#include "swarm/coarse_search.hpp"

namespace dsswarm {

void RelativePoseConfig::validate() const {
  if (!(search_radius > 0.0 && search_radius <= 50.0)) throw ConfigError("encounter.search_radius must be in (0, 50] m");
  if (!(coarse_step_xy >= 0.01 && coarse_step_xy <= 1.0)) throw ConfigError("encounter.coarse_step_xy must be in [0.01, 1] m");
  if (!(coarse_step_theta >= 0.005 && coarse_step_theta <= 0.5))
    throw ConfigError("encounter.coarse_step_theta must be in [0.005, 0.5] rad");
  if (coarse_points < 10) throw ConfigError("encounter.coarse_points must be >= 10");
  // The exhaustive search holds every pose of its lattice at once (32 bytes
  // each, coarse_search.hpp): the default lattice has about 0.15 M.
  constexpr double kMaxLatticePoses = 5e6;
  const double cells_across = search_radius / coarse_step_xy;
  const double lattice = std::numbers::pi * cells_across * cells_across * (2.0 * std::numbers::pi / coarse_step_theta);
  if (lattice > kMaxLatticePoses)
    throw ConfigError("encounter.search_radius, coarse_step_xy and coarse_step_theta ask the exhaustive search for " +
                      std::to_string(std::lround(lattice / 1e6)) + " M poses; at most " +
                      std::to_string(std::lround(kMaxLatticePoses / 1e6)) + " M fit (a coarser lattice or a smaller radius)");
  if (candidates < 2 || candidates > 100) throw ConfigError("encounter.candidates must be in [2, 100]");
  if (!(surroundings_radius >= 0.0 && surroundings_radius <= 100.0))
    throw ConfigError("encounter.surroundings_radius must be in [0, 100] m");
  if (surroundings_points < 0) throw ConfigError("encounter.surroundings_points must be >= 0");
  if (!(merge_surroundings_radius >= 0.0 && merge_surroundings_radius <= 100.0))
    throw ConfigError("encounter.merge_surroundings_radius must be in [0, 100] m");
  if (merge_surroundings_points < 0) throw ConfigError("encounter.merge_surroundings_points must be >= 0");
  if (!(polish_sigma_xy > 0.0) || !(polish_sigma_theta > 0.0))
    throw ConfigError("encounter.polish_sigma_xy and polish_sigma_theta must be > 0");
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

}  // namespace

MatchResult refine_placement(const MultiResMap& map, const std::vector<ScanPoint>& points,
                       const std::vector<ScanPoint>& surroundings, const Pose2& start, const RelativePoseConfig& config,
                       std::uint64_t seed) {
  std::vector<ScanPoint> both = points;
  both.insert(both.end(), surroundings.begin(), surroundings.end());
  MatcherConfig fine = config.refine;
  fine.sigma_xy = config.polish_sigma_xy;
  fine.sigma_theta = config.polish_sigma_theta;
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
  std::vector<CoarsePlacement> all = exhaustive_search(coarse, points, near, config);
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
