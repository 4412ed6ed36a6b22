#include "matching/monte_carlo_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

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
  if (fine_search_stride < 1 || fine_search_stride > 16)
    throw ConfigError("matcher.fine_search_stride must be in [1, 16]");
  if (coarse_stride < 1 || coarse_stride > 16) throw ConfigError("matcher.coarse_stride must be in [1, 16]");
  if (!(fine_merge_cells >= 0.0 && fine_merge_cells <= 4.0))
    throw ConfigError("matcher.fine_merge_cells must be in [0, 4]");
  if (!(coarse_merge_cells >= 0.0 && coarse_merge_cells <= 4.0))
    throw ConfigError("matcher.coarse_merge_cells must be in [0, 4]");
  if (polish_heat_evaluations < 0 || polish_heat_evaluations > polish_evaluations)
    throw ConfigError("matcher.polish_heat_evaluations must be in [0, matcher.polish_evaluations]");
}

MonteCarloMatcher::MonteCarloMatcher(const MatcherConfig& config, std::uint64_t seed)
    : config_(config), rng_(seed) {
  config_.validate();
}

namespace matcher_detail {

// Pose score minus a small penalty for straying from the prior: the motion
// model's voice in the search. Near the optimum it is negligible (1 cm costs
// 1e-4 at the defaults, where the scan score changes by ~0.05); it only stops
// the search from jumping tens of centimetres for a marginally better fit.
struct MotionPrior {
  Pose2 pose;
  double weight = 0.0;  // 0: no penalty
  double sigma_xy = 0.1;
  double sigma_theta = 0.1;

  double penalty(const Pose2& p) const {
    if (weight == 0.0) return 0.0;
    const double dx = (p.x - pose.x) / sigma_xy, dy = (p.y - pose.y) / sigma_xy;
    const double dt = normalize_angle(p.theta - pose.theta) / sigma_theta;
    return weight * (dx * dx + dy * dy + dt * dt);
  }
};

struct Search {
  const ScanScorer& scorer;
  int budget;  // evaluations left at this level
  MotionPrior prior;
  const ScanScorer* sampler = nullptr;  // the random phase's scorer, where it uses fewer points
  int used = 0;

  const DsGrid& grid() const { return scorer.grid(); }
  bool exhausted() const { return used >= budget; }
  double score(const Pose2& p) {
    ++used;
    return scorer.score(p) - prior.penalty(p);
  }
  // A pose scored before the search began: charged like any evaluation
  // (the budget counts poses considered), not scored again.
  double known(double s) {
    ++used;
    return s;
  }
  double sample(const Pose2& p) {
    ++used;
    return (sampler ? *sampler : scorer).score(p) - prior.penalty(p);
  }
};

// Deterministic coordinate ascent: try ± a step along x, y and θ, move to the
// best improvement, halve the steps when none improves. Random samples rarely
// move along exactly one axis, yet in a corridor that is the only direction
// with signal; this finds it and converges to a local maximum precisely.
// Resumable: run() spends what the search allows and keeps its steps.
struct Polish {
  Pose2 best;
  double best_score;
  double step_xy, step_th;
  double min_step_xy = step_xy / 16.0;
  int back = -1;  // the move that returns to the previous best, after an improvement

  bool converged() const { return step_xy < min_step_xy; }
  void run(Search& search) {
    while (!search.exhausted() && !converged()) round(search);
  }

 private:
  void round(Search& search) {
    const Pose2 moves[6] = {{best.x + step_xy, best.y, best.theta}, {best.x - step_xy, best.y, best.theta},
                            {best.x, best.y + step_xy, best.theta}, {best.x, best.y - step_xy, best.theta},
                            {best.x, best.y, best.theta + step_th}, {best.x, best.y, best.theta - step_th}};
    int winner = -1;
    double winner_score = best_score;
    for (int k = 0; k < 6 && !search.exhausted(); ++k) {
      if (k == back) {  // the pose just left, known to score less: its turn passes unscored
        ++search.used;
        continue;
      }
      const double s = search.score(moves[k]);
      if (s > winner_score) {
        winner = k;
        winner_score = s;
      }
    }
    if (winner >= 0) {
      best = moves[winner];
      best_score = winner_score;
      back = winner ^ 1;  // moves come in ± pairs
    } else {
      step_xy *= 0.5;
      step_th *= 0.5;
      back = -1;
    }
  }
};

}  // namespace matcher_detail

using matcher_detail::MotionPrior;
using matcher_detail::Search;
using matcher_detail::Polish;

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
  const LevelPoints level_points = merge_per_level(map, points);
  MatchResult best;
  int evaluations = 0;
  double first_prior_score = 0.0;
  for (std::size_t i = 0; i < distinct.size(); ++i) {
    const MatchResult r = match_from(map, level_points, distinct[i]);
    evaluations += r.evaluations;
    if (i == 0) first_prior_score = r.prior_score;
    if (i == 0 || r.score > best.score) best = r;
  }
  best.evaluations = evaluations;
  best.prior_score = first_prior_score;  // distinct[0] is priors.front()
  return best;
}

MatchResult MonteCarloMatcher::match(const MultiResMap& map, const std::vector<ScanPoint>& points,
                                     const Pose2& prior) {
  return match_from(map, merge_per_level(map, points), prior);
}

MonteCarloMatcher::LevelPoints MonteCarloMatcher::merge_per_level(const MultiResMap& map,
                                                                  const std::vector<ScanPoint>& points) const {
  LevelPoints out;
  out.merged.reserve(static_cast<std::size_t>(map.levels()));  // no reallocation: `level` points into it
  for (int level = 0; level < map.levels(); ++level) {
    const double cells = level == 0 ? config_.fine_merge_cells : config_.coarse_merge_cells;
    if (cells > 0.0) {
      out.merged.push_back(merge_close_points(points, cells * map.level(level).resolution()));
      out.level.push_back(&out.merged.back());
    } else {
      out.level.push_back(&points);
    }
  }
  return out;
}

void MonteCarloMatcher::search_level(Search& search, int level, Pose2& best, double& best_score, double& sigma_xy,
                                     double& sigma_th) {
  random_phase(search, level, best, best_score, sigma_xy, sigma_th);
  Polish polish = polish_from(best, best_score, search.grid(), level);
  polish.run(search);
  best = polish.best;
  best_score = polish.best_score;
}

// The polish's first steps: half a cell of the level's grid, and the
// heading step doubled per level above the finest.
Polish MonteCarloMatcher::polish_from(const Pose2& pose, double score, const DsGrid& grid, int level) const {
  return {pose, score, grid.resolution() * 0.5, config_.polish_step_theta * static_cast<double>(1 << level)};
}

void MonteCarloMatcher::random_phase(Search& search, int level, Pose2& best, double& best_score, double& sigma_xy,
                                     double& sigma_th) {
  const int random_budget = std::max(0, search.budget - config_.polish_evaluations);
  // On the finest level the random phase ends early once the spread has
  // collapsed well below a cell: further samples can only confirm what the
  // polish will refine. Coarse levels are cheap and do the wide search, so
  // they always use their budget.
  const double converged_xy = level == 0 ? search.grid().resolution() * config_.converged_fraction : 0.0;
  int failures = 0;
  // With a sampler the random phase compares scores over its points only.
  if (search.sampler) best_score = search.sample(best);
  while (search.used < random_budget && sigma_xy > converged_xy) {
    const Pose2 candidate(best.x + rng_.normal() * sigma_xy, best.y + rng_.normal() * sigma_xy,
                          best.theta + rng_.normal() * sigma_th);
    const double s = search.sample(candidate);
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
  if (search.sampler) best_score = search.score(best);
}

MatchResult MonteCarloMatcher::match_from(const MultiResMap& map, const LevelPoints& points, const Pose2& prior) {
  MatchResult result;
  result.pose = prior;
  if (points.level.front()->empty()) return result;

  const int levels = map.levels();
  // Coarse levels are cheap to search but only place the scan roughly; give
  // the finest level the largest share of the budget.
  int fine_budget = levels == 1 ? config_.evaluations : config_.evaluations / 2;
  const int coarse_budget = levels > 1 ? (config_.evaluations - fine_budget) / (levels - 1) : 0;

  const MotionPrior motion{prior, config_.prior_weight, config_.prior_sigma_xy, config_.prior_sigma_theta};
  SearchStart coarse{prior, config_.sigma_xy, config_.sigma_theta};
  search_coarse(map, points, motion, coarse_budget, coarse, result.evaluations);

  // The finest level searches from the coarse answer and, when it differs,
  // from the prior too (half the budget each). The coarse levels can lead
  // astray; and the prior often sits on a small local maximum of its own (the
  // last scan's viewpoint) that only a search from elsewhere climbs past.
  const DsGrid& fine = map.finest();
  const Pose2 d = between(prior, coarse.pose);
  const bool two_starts = levels > 1 && (std::hypot(d.x, d.y) > fine.resolution() * 0.5 ||
                                         std::abs(d.theta) > config_.polish_step_theta);
  const ScanScorer fine_scorer(fine, *points.level.front(), 1, config_.unknown_value);
  result.prior_score = fine_scorer.score(prior);
  const double prior_start_score = result.prior_score - motion.penalty(prior);  // as a search scores it
  std::vector<SearchStart> starts{coarse};
  if (two_starts) {
    starts.push_back({prior, fine.resolution(), config_.sigma_theta * 0.25, prior_start_score});
  } else if (levels > 1) {
    // Within half a cell of each other, yet on the fine level a wall that
    // lies along the grid makes the score steep: start from the better one,
    // not from a flank the random phase may leave for another ridge.
    fine_budget -= 2;
    result.evaluations += 2;
    const double coarse_score = fine_scorer.score(coarse.pose) - motion.penalty(coarse.pose);
    const bool from_prior = result.prior_score > coarse_score;
    if (from_prior) starts.front().pose = prior;
    starts.front().fine_score = from_prior ? prior_start_score : coarse_score;
  }
  result.pose = search_fine(fine_scorer, *points.level.front(), motion, starts, fine_budget, result.evaluations);
  result.score = fine_scorer.score(result.pose);  // without the penalty
  return result;
}

void MonteCarloMatcher::search_coarse(const MultiResMap& map, const LevelPoints& points, const MotionPrior& motion,
                                      int budget, SearchStart& best, int& evaluations) {
  for (int level = map.levels() - 1; level >= 1; --level) {
    const auto stride = static_cast<std::size_t>(config_.coarse_stride) << std::min(level - 1, 1);
    const ScanScorer scorer(map.level(level), *points.level[static_cast<std::size_t>(level)], stride, config_.unknown_value);
    Search search{scorer, budget, motion};
    double score = search.score(best.pose);
    search_level(search, level, best.pose, score, best.sigma_xy, best.sigma_th);
    evaluations += search.used;
    // The next (finer) level starts no narrower than its own cell size.
    best.sigma_xy = std::max(best.sigma_xy, map.level(level - 1).resolution());
    best.sigma_th = std::max(best.sigma_th, config_.sigma_theta * 0.25);
  }
}

Pose2 MonteCarloMatcher::search_fine(const ScanScorer& fine_scorer, const std::vector<ScanPoint>& fine_points,
                                     const MotionPrior& motion, std::vector<SearchStart> starts, int budget,
                                     int& evaluations) {
  const int per_start = budget / static_cast<int>(starts.size());
  const auto stride = static_cast<std::size_t>(config_.fine_search_stride);
  const std::optional<ScanScorer> sampler =
      stride > 1 ? std::optional<ScanScorer>(std::in_place, fine_scorer.grid(), fine_points, stride, config_.unknown_value)
                 : std::nullopt;
  // Each start's random phase, then their polishes race: each gets a few
  // rounds, then the leader finishes alone with what its start has left
  // (a random phase that converged early leaves its polish more). The polish
  // is the costlier part, and a start behind after a few rounds rarely overtakes.
  struct Racer {
    Polish polish;
    int left;  // evaluations of its start's budget not yet spent
  };
  std::vector<Racer> racers;
  for (SearchStart& start : starts) {
    Search search{fine_scorer, per_start, motion, sampler ? &*sampler : nullptr};
    double score = start.fine_score ? search.known(*start.fine_score) : search.score(start.pose);
    random_phase(search, 0, start.pose, score, start.sigma_xy, start.sigma_th);
    evaluations += search.used;
    racers.push_back({polish_from(start.pose, score, fine_scorer.grid(), 0), per_start - search.used});
  }
  const auto run = [&](Racer& racer, int run_budget) {
    Search search{fine_scorer, std::min(run_budget, racer.left), motion};
    racer.polish.run(search);
    racer.left -= search.used;
    evaluations += search.used;
  };
  if (racers.size() > 1)
    for (Racer& racer : racers) run(racer, config_.polish_heat_evaluations);
  Racer& leader = *std::max_element(racers.begin(), racers.end(), [](const Racer& a, const Racer& b) {
    return a.polish.best_score < b.polish.best_score;
  });
  run(leader, leader.left);
  return leader.polish.best;
}

}  // namespace dsswarm
