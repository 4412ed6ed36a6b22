#include "matching/monte_carlo_matcher.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "matching/scan_scorer.hpp"

namespace dsswarm {
namespace {

// A small asymmetric room (L-shaped walls plus a pillar) and an exact ray caster.
struct Segment {
  Eigen::Vector2d a, b;
};
const std::vector<Segment> kRoom = {
    {{-3, -2}, {6, -2}}, {{6, -2}, {6, 4}}, {{6, 4}, {1, 4}}, {{1, 4}, {1, 6}}, {{1, 6}, {-3, 6}},
    {{-3, 6}, {-3, -2}}, {{2, 1}, {2.6, 1}}, {{2.6, 1}, {2.6, 1.4}}, {{2.6, 1.4}, {2, 1.4}}, {{2, 1.4}, {2, 1}}};

// Walls sit off the cell grid (as real walls do): a wall exactly on a cell
// boundary biases any grid map by half a cell.
const Eigen::Vector2d kShift(0.0137, 0.0311);

double cast(const Eigen::Vector2d& o, double angle, const Eigen::Vector2d& shift = kShift) {
  const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : kRoom) {
    const Eigen::Vector2d e = s.b - s.a;
    const double den = d.x() * e.y() - d.y() * e.x();
    if (std::abs(den) < 1e-12) continue;
    const Eigen::Vector2d w = s.a + shift - o;
    const double t = (w.x() * e.y() - w.y() * e.x()) / den;
    const double u = (w.x() * d.y() - w.y() * d.x()) / den;
    if (t > 0 && u >= 0 && u <= 1) best = std::min(best, t);
  }
  return best;
}

LaserScan scan_from(const Pose2& pose, const Eigen::Vector2d& shift = kShift) {
  LaserScan s;
  s.angle_min = -std::numbers::pi / 2;
  s.angle_increment = std::numbers::pi / 360;
  s.range_max = 30;
  for (int i = 0; i <= 360; ++i)
    s.ranges.push_back(static_cast<float>(cast(pose.translation(), pose.theta + s.beam_angle(i), shift)));
  return s;
}

MultiResMap map_from_views(const std::vector<Pose2>& views, const Eigen::Vector2d& shift = kShift) {
  MultiResMap map;
  for (const Pose2& v : views) map.insert_scan(v, Pose2(), scan_to_points(scan_from(v, shift)));
  return map;
}

TEST(ScanScorer, TruePoseScoresHigherThanShiftedPose) {
  const Pose2 truth(0.5, 0.5, 0.3);
  const MultiResMap map = map_from_views({truth, Pose2(-1, 3, 2.0), Pose2(4, 0, -2.5)});
  const auto pts = scan_to_points(scan_from(truth));
  const double s_true = score_pose(map.finest(), pts, truth);
  EXPECT_GT(s_true, score_pose(map.finest(), pts, Pose2(0.6, 0.5, 0.3)));
  EXPECT_GT(s_true, score_pose(map.finest(), pts, Pose2(0.5, 0.5, 0.35)));
  EXPECT_GT(s_true, 0.3);
}

// Of 20 priors up to 10 cm and 3° off, how many the matcher brings within 2 cm and 0.6°.
int recovered_poses(const MatcherConfig& config) {
  const MultiResMap map = map_from_views({Pose2(0, 0, 0), Pose2(-1, 3, 2.0), Pose2(4, 0, -2.5), Pose2(3, 2, 1.0)});
  const Pose2 truth(0.8, 0.9, 0.4);
  const auto pts = scan_to_points(scan_from(truth));
  MonteCarloMatcher matcher(config, 42);
  int good = 0;
  Rng rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Pose2 prior(truth.x + rng.uniform(-0.1, 0.1), truth.y + rng.uniform(-0.1, 0.1),
                      truth.theta + rng.uniform(-0.05, 0.05));
    const MatchResult r = matcher.match(map, pts, prior);
    EXPECT_GE(r.score, r.prior_score - 1e-9);
    EXPECT_LE(r.evaluations, matcher.config().evaluations);
    if (std::hypot(r.pose.x - truth.x, r.pose.y - truth.y) < 0.02 && std::abs(r.pose.theta - truth.theta) < 0.01)
      ++good;
  }
  return good;
}

TEST(MonteCarloMatcher, RecoversPoseFromOffsetPrior) { EXPECT_GE(recovered_poses({}), 18); }

// Walls along the grid's axes, on the cells' centres (a map whose axes were
// turned to the walls): across such a wall the finest level's score falls
// from its peak to half within half a cell. A coarse answer that lands there,
// close to a prior on the peak, must not lead the search off to another ridge.
TEST(MonteCarloMatcher, NeverEndsBelowAPriorOnTheRidgeOfWallsAlongTheGrid) {
  const Eigen::Vector2d on_centres(0.025, 0.025);
  const MultiResMap map =
      map_from_views({Pose2(0, 0, 0), Pose2(-1, 3, 1.5708), Pose2(4, 0, 3.1416), Pose2(3, 2, -1.5708)}, on_centres);
  MonteCarloMatcher matcher(MatcherConfig{}, 7);
  Rng rng(11);
  int below = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Pose2 truth(rng.uniform(-1.0, 3.0), rng.uniform(-1.0, 2.0), rng.uniform(-0.02, 0.02));
    const auto pts = scan_to_points(scan_from(truth, on_centres));
    const Pose2 prior(truth.x + rng.uniform(-0.01, 0.01), truth.y + rng.uniform(-0.01, 0.01), truth.theta);
    const MatchResult r = matcher.match(map, pts, prior);
    if (r.score < r.prior_score - 1e-9) ++below;
    EXPECT_LE(r.evaluations, matcher.config().evaluations);
  }
  EXPECT_EQ(below, 0);
}

// The cheaper schedules (fewer points in the random phase and on the coarse
// levels) must still place the scan: the polish sees every point.
TEST(MonteCarloMatcher, RecoversPoseSearchingOnFewerPoints) {
  MatcherConfig fewer;
  fewer.fine_search_stride = 2;
  EXPECT_GE(recovered_poses(fewer), 18);
  fewer.coarse_stride = 4;
  EXPECT_GE(recovered_poses(fewer), 18);
}

// From two starts the polishes race: whatever share each gets before the
// leader finishes alone, the scan is placed, and a shorter heat costs fewer
// evaluations.
TEST(MonteCarloMatcher, RecoversPoseWhateverThePolishHeat) {
  const MultiResMap map = map_from_views({Pose2(0, 0, 0), Pose2(-1, 3, 2.0), Pose2(4, 0, -2.5), Pose2(3, 2, 1.0)});
  const Pose2 truth(0.8, 0.9, 0.4);
  const auto pts = scan_to_points(scan_from(truth));
  const Pose2 prior(truth.x + 0.08, truth.y - 0.06, truth.theta + 0.04);  // far enough for two starts
  int previous = 0;
  for (const int heat : {36, 12, 0}) {
    MatcherConfig config;
    config.polish_heat_evaluations = heat;
    EXPECT_GE(recovered_poses(config), 18) << "heat " << heat;
    MonteCarloMatcher matcher(config, 5);
    const MatchResult r = matcher.match(map, pts, prior);
    if (previous > 0) {
      EXPECT_LT(r.evaluations, previous) << "heat " << heat;
    }
    previous = r.evaluations;
  }
}

// Merged points (the default) and every point place the scan alike; merging
// wider still places it, on fewer points.
TEST(MonteCarloMatcher, RecoversPoseWhateverTheMerge) {
  for (const double cells : {0.0, 0.75, 2.0}) {
    MatcherConfig config;
    config.fine_merge_cells = cells;
    config.coarse_merge_cells = 2 * cells;
    EXPECT_GE(recovered_poses(config), 18) << "merge " << cells;
  }
}

TEST(MonteCarloMatcher, SameSeedSameResult) {
  const MultiResMap map = map_from_views({Pose2(0, 0, 0), Pose2(3, 2, 1.0)});
  const auto pts = scan_to_points(scan_from(Pose2(0.2, 0.1, 0.05)));
  MonteCarloMatcher a({}, 7), b({}, 7);
  const MatchResult ra = a.match(map, pts, Pose2()), rb = b.match(map, pts, Pose2());
  EXPECT_EQ(ra.pose.x, rb.pose.x);
  EXPECT_EQ(ra.pose.theta, rb.pose.theta);
}

TEST(MonteCarloMatcher, EmptyScanReturnsPrior) {
  const MultiResMap map;
  MonteCarloMatcher m;
  const MatchResult r = m.match(map, {}, Pose2(1, 2, 3));
  EXPECT_EQ(r.pose.x, 1.0);
  EXPECT_EQ(r.evaluations, 0);
}

TEST(MatcherConfig, RejectsBadValues) {
  MatcherConfig c;
  c.evaluations = 0;
  EXPECT_THROW(c.validate(), ConfigError);
  c = {};
  c.sigma_xy = -1;
  EXPECT_THROW(c.validate(), ConfigError);
  c = {};
  c.fine_search_stride = 0;
  EXPECT_THROW(c.validate(), ConfigError);
  c = {};
  c.coarse_stride = 17;
  EXPECT_THROW(c.validate(), ConfigError);
  c = {};
  c.polish_heat_evaluations = c.polish_evaluations + 1;
  EXPECT_THROW(c.validate(), ConfigError);
  c.polish_heat_evaluations = -1;
  EXPECT_THROW(c.validate(), ConfigError);
}

}  // namespace
}  // namespace dsswarm
