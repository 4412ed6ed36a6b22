#include "slam/loop_search.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "matching/same_side.hpp"
#include "matching/scan_scorer.hpp"

namespace dsswarm {

void LoopSearchConfig::validate() const {
  if (points < 10) throw ConfigError("loop_closure.points must be >= 10");
  if (!(max_range > 0.0)) throw ConfigError("loop_closure.max_range must be > 0");
  if (max_depth < 1 || max_depth > 12) throw ConfigError("loop_closure.max_depth must be in [1, 12]");
  if (!(min_score > -1.0 && min_score < 1.0)) throw ConfigError("loop_closure.min_score must be in (-1, 1)");
  auto unit = [](double v) { return v >= 0.0 && v <= 1.0; };
  if (!unit(min_known) || !unit(min_inliers) || !unit(min_same_side) || !unit(max_runner_up))
    throw ConfigError("loop_closure.min_known, min_inliers, min_same_side and max_runner_up must be in [0, 1]");
  if (!unit(min_prior_known)) throw ConfigError("loop_closure.min_prior_known must be in [0, 1]");
  if (!(runner_up_xy > 0.0) || !(runner_up_theta > 0.0))
    throw ConfigError("loop_closure.runner_up_xy and runner_up_theta must be > 0");
  refine.validate();
}

const char* to_string(LoopRejection r) {
  switch (r) {
    case LoopRejection::none: return "accepted";
    case LoopRejection::no_match: return "no_match";
    case LoopRejection::unknown: return "unknown";
    case LoopRejection::inliers: return "inliers";
    case LoopRejection::same_side: return "same_side";
    case LoopRejection::ambiguous: return "ambiguous";
    case LoopRejection::prior_fits: return "prior_fits";
  }
  return "?";
}

namespace {

std::vector<ScanPoint> within(const std::vector<ScanPoint>& points, double max_range) {
  std::vector<ScanPoint> near;
  for (const ScanPoint& p : points)
    if (std::hypot(static_cast<double>(p.x), static_cast<double>(p.y)) <= max_range) near.push_back(p);
  return near;
}

// At most `n` of the points, evenly spread over the scan.
std::vector<ScanPoint> thinned(const std::vector<ScanPoint>& near, int n) {
  if (static_cast<int>(near.size()) <= n) return near;
  std::vector<ScanPoint> out;
  const double step = static_cast<double>(near.size()) / n;
  for (int k = 0; k < n; ++k) out.push_back(near[static_cast<std::size_t>(k * step)]);
  return out;
}

}  // namespace

LoopSearch search_loop_closure(const BranchAndBoundMatcher& matcher, const Submap& submap,
                               const std::vector<ScanPoint>& all_points, const Pose2& prior,
                               const SearchWindow& window, const LoopSearchConfig& config, std::uint64_t seed) {
  LoopSearch out;
  const std::vector<ScanPoint> near = within(all_points, config.max_range);
  const std::vector<ScanPoint> few = thinned(near, config.points);
  const auto best = matcher.match(few, prior, window, config.min_score);
  if (!best) return out;
  LoopCandidate& c = out.candidate;
  c.score = best->score;
  MonteCarloMatcher refiner(config.refine, seed);
  const Pose2 pose = refiner.match(submap.map, near, best->pose).pose;
  c.relative = between(submap.anchor, pose);
  const MatchQuality q = match_quality(submap.map.finest(), near, pose);
  c.known = q.known_fraction;
  c.inliers = q.inlier_ratio;
  if (c.known < config.min_known) return {LoopRejection::unknown, c};
  if (c.inliers < config.min_inliers) return {LoopRejection::inliers, c};
  c.same_side = same_side_ratio(submap.map.finest(), near, pose);
  if (c.same_side < config.min_same_side) return {LoopRejection::same_side, c};
  const auto second = matcher.match(few, prior, window, config.max_runner_up * best->score, best->pose,
                                    config.runner_up_xy, config.runner_up_theta);
  if (second) {
    c.runner_up = second->score / best->score;
    return {LoopRejection::ambiguous, c};
  }
  const Pose2 believed = refiner.match(submap.map, near, prior).pose;
  const Pose2 jump = between(believed, pose);
  if (std::hypot(jump.x, jump.y) > config.runner_up_xy || std::abs(jump.theta) > config.runner_up_theta) {
    const MatchQuality at_prior = match_quality(submap.map.finest(), near, believed);
    c.prior_known = at_prior.known_fraction;
    c.prior_inliers = at_prior.inlier_ratio;
    if (c.prior_known >= config.min_prior_known && c.prior_inliers >= config.min_inliers)
      return {LoopRejection::prior_fits, c};
  }
  out.rejection = LoopRejection::none;
  return out;
}

bool closures_agree(const PoseGraph& graph, const Constraint& a, const Constraint& b, double xy, double theta) {
  const auto node = [&](int i) { return graph.nodes[static_cast<std::size_t>(i)]; };
  const Pose2 along_trajectory = between(node(a.node), node(b.node));
  const Pose2 through_closures =
      a.relative.inverse() * between(reference_pose(graph, a), reference_pose(graph, b)) * b.relative;
  const Pose2 e = between(along_trajectory, through_closures);
  return std::hypot(e.x, e.y) <= xy && std::abs(e.theta) <= theta;
}

}  // namespace dsswarm
