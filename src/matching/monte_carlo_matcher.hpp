#pragma once
// Monte-Carlo scan matcher (the chapter's §3.1, after vinySLAM).
//
// Random poses are drawn around the best pose so far; a better one becomes the
// new centre and the search radius shrinks around it; a run of failures also
// shrinks it. The search runs coarse-to-fine over the map's resolution levels,
// each level starting from the previous level's answer and ending with a short
// deterministic coordinate ascent, and stops after a fixed budget of pose
// evaluations — so its cost per scan is bounded.
#include <cstdint>
#include <optional>

#include "common/rng.hpp"
#include "geometry/pose2.hpp"
#include "grid/multires_map.hpp"
#include "sensor/scan_points.hpp"

namespace dsswarm {

class ScanScorer;

namespace matcher_detail {
struct MotionPrior;
struct Search;
struct Polish;
}

struct MatcherConfig {
  int evaluations = 240;         // pose evaluations per scan, over all levels
  double sigma_xy = 0.10;        // m: initial spread on the coarsest level
  double sigma_theta = 0.05;     // rad: initial heading spread on the coarsest level
  double shrink_on_success = 0.75;  // spread factor after each improvement
  int patience = 10;             // failures in a row before the spread halves
  double min_sigma_xy = 0.002;   // spreads never shrink below these
  double min_sigma_theta = 0.0005;
  // The finest level's random phase stops once the spread is below this share
  // of its cell size (the budget is a ceiling, not a quota).
  double converged_fraction = 0.1;
  // Evaluations per level kept for the final deterministic coordinate ascent.
  int polish_evaluations = 36;
  // When the finest level searched from two starts, each start's polish first
  // gets this many evaluations, then the better one the rest of its budget.
  int polish_heat_evaluations = 12;
  // The finest level's random phase may score every n-th point only (it has
  // to find the basin); the polish always scores all of them. 1 (all points
  // throughout) by default: see docs/performance.md for what 2 gains and costs.
  int fine_search_stride = 1;
  // Near the lidar several beams end in one cell: the finest level can score
  // each run of consecutive points within this share of its cell as one
  // point at their weighted centroid (merge_close_points), the coarse levels
  // likewise within coarse_merge_cells of their own cells. 0 scores every
  // point. Merging cuts the instructions per scan by a quarter at the same
  // relations error (docs/performance.md, "Merged points, hit runs").
  double fine_merge_cells = 0.75;
  double coarse_merge_cells = 1.5;
  // The coarse levels then score every n-th of their points (the second
  // coarse level and beyond every 2n-th): their cells are wide and they
  // only place the scan roughly. 1 with merging: it already thinned them.
  int coarse_stride = 1;
  double polish_step_theta = 0.005;  // rad, first θ step on the finest level (doubles per level)
  // Motion prior: every candidate's score is reduced by
  // prior_weight × (|Δxy|²/prior_sigma_xy² + Δθ²/prior_sigma_theta²) relative
  // to the prior it was searched from (0 disables).
  double prior_weight = 0.01;
  double prior_sigma_xy = 0.1;     // m
  double prior_sigma_theta = 0.1;  // rad
  // Share of a cell's unknown mass that counts as occupancy when scoring
  // (0: only evidence of obstacles scores; 0.5: pignistic occupancy).
  float unknown_value = 0.0f;

  void validate() const;
};

struct MatchResult {
  Pose2 pose;
  double score = 0.0;        // weighted mean occupancy on the finest level, [0, 1]
  double prior_score = 0.0;  // same at the prior pose
  int evaluations = 0;
};

class MonteCarloMatcher {
 public:
  explicit MonteCarloMatcher(const MatcherConfig& config = {}, std::uint64_t seed = 1);

  MatchResult match(const MultiResMap& map, const std::vector<ScanPoint>& points, const Pose2& prior);
  // Searches from each distinct prior and returns the best-scoring result.
  MatchResult match(const MultiResMap& map, const std::vector<ScanPoint>& points, const std::vector<Pose2>& priors);

  const MatcherConfig& config() const { return config_; }

 private:
  // The scan's points for each level (index 0 the finest), merged as the
  // configuration says; a level that does not merge uses the caller's points.
  struct LevelPoints {
    LevelPoints() = default;
    LevelPoints(LevelPoints&&) = default;       // moving keeps `merged`'s buffer: `level` stays valid
    LevelPoints(const LevelPoints&) = delete;  // a copy's `level` would point into the original
    std::vector<std::vector<ScanPoint>> merged;
    std::vector<const std::vector<ScanPoint>*> level;
  };
  LevelPoints merge_per_level(const MultiResMap& map, const std::vector<ScanPoint>& points) const;
  MatchResult match_from(const MultiResMap& map, const LevelPoints& points, const Pose2& prior);
  // Where a level's search starts, and its spreads.
  struct SearchStart {
    Pose2 pose;
    double sigma_xy, sigma_th;
    std::optional<double> fine_score = std::nullopt;  // at `pose` on the finest level less the penalty, if scored
  };
  // The coarse levels, coarsest first, each from the last one's answer:
  // leaves `best` where the finest level starts, with its spreads.
  void search_coarse(const MultiResMap& map, const LevelPoints& points, const matcher_detail::MotionPrior& motion,
                     int budget, SearchStart& best, int& evaluations);
  // The finest level from each start (its budget shared): the best pose.
  Pose2 search_fine(const ScanScorer& fine_scorer, const std::vector<ScanPoint>& fine_points,
                    const matcher_detail::MotionPrior& motion, std::vector<SearchStart> starts, int budget,
                    int& evaluations);
  // Random phase then coordinate ascent on one level, updating the best pose and the spreads.
  void search_level(matcher_detail::Search& search, int level, Pose2& best, double& best_score, double& sigma_xy,
                    double& sigma_th);
  // The random phase alone: samples around `best` until the level's budget
  // less its polish share is spent (or, on the finest level, the spread collapsed).
  void random_phase(matcher_detail::Search& search, int level, Pose2& best, double& best_score, double& sigma_xy,
                    double& sigma_th);
  // A polish starting at `pose` with the first steps of `level` (whose grid is `grid`).
  matcher_detail::Polish polish_from(const Pose2& pose, double score, const DsGrid& grid, int level) const;

  MatcherConfig config_;
  Rng rng_;
};

}  // namespace dsswarm
