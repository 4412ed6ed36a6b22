#include "matching/monte_carlo_matcher.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "matching/scan_scorer.hpp"

namespace dsswarm {

void MatcherConfig::validate() const {
  if (evaluations < 1 || evaluations > 100000) throw ConfigError("matcher.evaluations must be in [1, 100000]");
  if (!(sigma_xy > 0.0 && sigma_xy < 10.0)) throw ConfigError("matcher.sigma_xy must be in (0, 10) m");
  if (!(sigma_theta > 0.0 && sigma_theta < 3.2)) throw ConfigError("matcher.sigma_theta must be in (0, 3.2) rad");
  if (!(shrink_on_success > 0.0 && shrink_on_success <= 1.0))
    throw ConfigError("matcher.shrink_on_success must be in (0, 1]");
  if (patience < 1) throw ConfigError("matcher.patience must be >= 1");
}

MonteCarloMatcher::MonteCarloMatcher(const MatcherConfig& config, std::uint64_t seed)
    : config_(config), rng_(seed) {
  config_.validate();
}

namespace {

struct Search {
  const DsGrid& grid;
  const std::vector<ScanPoint>& points;
  std::size_t stride;
  float unknown_value;
  int budget;  // evaluations left at this level
  int used = 0;

  bool exhausted() const { return used >= budget; }
  double score(const Pose2& p) {
    ++used;
    return score_pose(grid, points, p, stride, unknown_value);
  }
};

// Deterministic coordinate ascent: try ± a step along x, y and θ, move to the
// best improvement, halve the steps when none improves. Random samples rarely
// move along exactly one axis, yet in a corridor that is the only direction
// with signal; this finds it and converges to a local maximum precisely.
void polish(Search& search, Pose2& best, double& best_score, double step_xy, double step_th) {
  const double min_step_xy = step_xy / 16.0;
  while (!search.exhausted() && step_xy >= min_step_xy) {
    const Pose2 moves[6] = {{best.x + step_xy, best.y, best.theta}, {best.x - step_xy, best.y, best.theta},
                            {best.x, best.y + step_xy, best.theta}, {best.x, best.y - step_xy, best.theta},
                            {best.x, best.y, best.theta + step_th}, {best.x, best.y, best.theta - step_th}};
    int winner = -1;
    double winner_score = best_score;
    for (int k = 0; k < 6 && !search.exhausted(); ++k) {
      const double s = search.score(moves[k]);
      if (s > winner_score) {
        winner = k;
        winner_score = s;
      }
    }
    if (winner >= 0) {
      best = moves[winner];
      best_score = winner_score;
    } else {
      step_xy *= 0.5;
      step_th *= 0.5;
    }
  }
}

}  // namespace

MatchResult MonteCarloMatcher::match(const MultiResMap& map, const std::vector<ScanPoint>& points,
                                     const std::vector<Pose2>& priors) {
  // Several predictions (odometry, constant velocity, standing still) may
  // disagree when odometry lags or jumps. Search from each distinct one and
  // keep the best-scoring answer; the first prior is the one reported as
  // `prior_score`.
  std::vector<Pose2> distinct;
  for (const Pose2& p : priors) {
    const bool duplicate = std::any_of(distinct.begin(), distinct.end(), [&](const Pose2& q) {
      return std::hypot(p.x - q.x, p.y - q.y) < config_.min_sigma_xy * 5 &&
             std::abs(normalize_angle(p.theta - q.theta)) < config_.min_sigma_theta * 5;
    });
    if (!duplicate) distinct.push_back(p);
  }
  if (distinct.empty()) return {};
  MatchResult best;
  int evaluations = 0;
  for (std::size_t i = 0; i < distinct.size(); ++i) {
    const MatchResult r = match_from(map, points, distinct[i]);
    evaluations += r.evaluations;
    if (i == 0 || r.score > best.score) best = r;
  }
  best.evaluations = evaluations;
  best.prior_score = score_pose(map.finest(), points, priors.front(), 1, config_.unknown_value);
  return best;
}

MatchResult MonteCarloMatcher::match(const MultiResMap& map, const std::vector<ScanPoint>& points,
                                     const Pose2& prior) {
  return match_from(map, points, prior);
}

MatchResult MonteCarloMatcher::match_from(const MultiResMap& map, const std::vector<ScanPoint>& points,
                                          const Pose2& prior) {
  MatchResult result;
  result.pose = prior;
  if (points.empty()) return result;

  const int levels = map.levels();
  // Coarse levels are cheap to search but only place the scan roughly; give
  // the finest level the largest share of the budget.
  const int fine_budget = levels == 1 ? config_.evaluations : config_.evaluations / 2;
  const int coarse_budget = levels > 1 ? (config_.evaluations - fine_budget) / (levels - 1) : 0;

  Pose2 best = prior;
  double sigma_xy = config_.sigma_xy, sigma_th = config_.sigma_theta;
  for (int level = levels - 1; level >= 0; --level) {
    Search search{map.level(level), points, std::size_t{1} << std::min(level, 2), config_.unknown_value,
                  level == 0 ? fine_budget : coarse_budget};
    double best_score = search.score(best);
    if (level == 0 && levels > 1) {
      // The coarse levels can only have helped if the fine map agrees: fall
      // back to the prior when it scores better there.
      const double prior_fine = search.score(prior);
      if (prior_fine > best_score) {
        best = prior;
        best_score = prior_fine;
      }
    }
    const int random_budget = std::max(0, search.budget - config_.polish_evaluations);
    int failures = 0;
    while (search.used < random_budget) {
      const Pose2 candidate(best.x + rng_.normal() * sigma_xy, best.y + rng_.normal() * sigma_xy,
                            best.theta + rng_.normal() * sigma_th);
      const double s = search.score(candidate);
      if (s > best_score) {
        best = candidate;
        best_score = s;
        sigma_xy = std::max(config_.min_sigma_xy, sigma_xy * config_.shrink_on_success);
        sigma_th = std::max(config_.min_sigma_theta, sigma_th * config_.shrink_on_success);
        failures = 0;
      } else if (++failures >= config_.patience) {
        sigma_xy = std::max(config_.min_sigma_xy, sigma_xy * 0.5);
        sigma_th = std::max(config_.min_sigma_theta, sigma_th * 0.5);
        failures = 0;
      }
    }
    const double res = search.grid.resolution();
    polish(search, best, best_score, res * 0.5, config_.polish_step_theta * static_cast<double>(1 << level));
    result.evaluations += search.used;
    // The next (finer) level starts no narrower than its own cell size.
    if (level > 0) {
      sigma_xy = std::max(sigma_xy, map.level(level - 1).resolution());
      sigma_th = std::max(sigma_th, config_.sigma_theta * 0.25);
    }
    if (level == 0) result.score = best_score;
  }
  result.prior_score = score_pose(map.finest(), points, prior, 1, config_.unknown_value);
  result.pose = best;
  return result;
}

}  // namespace dsswarm
