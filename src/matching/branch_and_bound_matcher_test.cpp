#include "matching/branch_and_bound_matcher.hpp"

#include <gtest/gtest.h>

#include "common/rng.hpp"
#include "grid/multires_map.hpp"
#include "sim/lidar.hpp"
#include "sim/world.hpp"

namespace dsswarm {
namespace {

// An office with asymmetric clutter: one unambiguous place to be.
World office() {
  std::vector<Segment> w{{{0, 0}, {12, 0}}, {{12, 0}, {12, 5}}, {{12, 5}, {5, 5}}, {{5, 5}, {5, 10}},
                         {{5, 10}, {0, 10}}, {{0, 10}, {0, 0}}};
  std::vector<Box> solids{{{8.0, 1.0}, {8.6, 1.4}}, {{1.0, 7.0}, {1.5, 8.2}}, {{2.2, 2.0}, {2.5, 2.3}}};
  return World(std::move(w), std::move(solids));
}

std::vector<ScanPoint> scan_at(const World& world, const Pose2& pose, Rng& rng) {
  LidarConfig lidar;
  lidar.beams = 180;
  lidar.noise_std = 0.01;
  return scan_to_points(simulate_scan(world, pose, lidar, rng));
}

MultiResMap map_of(const World& world, Rng& rng) {
  MultiResMap map;
  for (const Pose2& p : {Pose2(2, 2, 0.3), Pose2(6, 2.5, 2.5), Pose2(10, 3, -2.8), Pose2(2.5, 8, -1.2)})
    map.insert_scan(p, Pose2(), scan_at(world, p, rng));
  return map;
}

TEST(BranchAndBoundMatcher, FindsThePoseFromAPriorOffByAMetreAndDegrees) {
  const World world = office();
  Rng rng(3);
  const MultiResMap map = map_of(world, rng);
  const BranchAndBoundMatcher matcher(map.finest(), 1.5);
  const Pose2 truth(3.3, 3.1, 0.7);
  const std::vector<ScanPoint> points = scan_at(world, truth, rng);
  const Pose2 prior = truth * Pose2(0.8, -0.6, 0.21);
  const auto r = matcher.match(points, prior, {1.5, 0.3}, 0.1);
  ASSERT_TRUE(r);
  EXPECT_LT(std::hypot(r->pose.x - truth.x, r->pose.y - truth.y), 0.06);
  EXPECT_LT(std::abs(normalize_angle(r->pose.theta - truth.theta)), 0.02);
  EXPECT_GT(r->score, 0.3);
  // The prior itself scores far worse.
  EXPECT_LT(matcher.score(points, prior), 0.5 * r->score);
}

TEST(BranchAndBoundMatcher, EqualsTheExhaustiveSearchOfTheSameCandidates) {
  const World world = office();
  Rng rng(5);
  const MultiResMap map = map_of(world, rng);
  const BranchAndBoundMatcher matcher(map.finest(), 0.4);
  const Pose2 truth(6.2, 2.2, -0.4);
  const std::vector<ScanPoint> points = scan_at(world, truth, rng);
  const Pose2 prior = truth * Pose2(0.2, 0.15, -0.05);
  const SearchWindow window{0.4, 0.1};
  const auto r = matcher.match(points, prior, window, 0.0);
  ASSERT_TRUE(r);
  // Every heading step and every cell offset of the window, scored one by one.
  const double step = matcher.heading_step(points), res = matcher.resolution();
  const int steps = static_cast<int>(std::ceil(window.theta / step)), half = static_cast<int>(std::ceil(window.xy / res));
  double best = 0.0;
  for (int k = -steps; k <= steps; ++k)
    for (int y = -half; y <= half; ++y)
      for (int x = -half; x <= half; ++x)
        best = std::max(best, matcher.score(points, Pose2(prior.x + x * res, prior.y + y * res, prior.theta + k * step)));
  EXPECT_DOUBLE_EQ(r->score, best);
  EXPECT_DOUBLE_EQ(matcher.score(points, r->pose), r->score);
}

TEST(BranchAndBoundMatcher, NothingAboveTheMinimumScoreIsNoMatch) {
  const World world = office();
  Rng rng(7);
  const MultiResMap map = map_of(world, rng);
  const BranchAndBoundMatcher matcher(map.finest(), 0.5);
  const Pose2 truth(2.1, 6.0, 1.0);
  const std::vector<ScanPoint> points = scan_at(world, truth, rng);
  const auto r = matcher.match(points, truth, {0.5, 0.1}, 0.0);
  ASSERT_TRUE(r);
  EXPECT_FALSE(matcher.match(points, truth, {0.5, 0.1}, r->score));
  EXPECT_FALSE(matcher.match({}, truth, {0.5, 0.1}, 0.0));
}

// The runner-up search: the best pose outside the best one's mode.
std::optional<BranchAndBoundResult> runner_up(const BranchAndBoundMatcher& matcher, const std::vector<ScanPoint>& points,
                                              const Pose2& prior, const SearchWindow& window,
                                              const BranchAndBoundResult& best) {
  const auto second = matcher.match(points, prior, window, -1.0, best.pose, 0.5, 0.26);
  if (second) {
    const bool outside = std::hypot(second->pose.x - best.pose.x, second->pose.y - best.pose.y) >= 0.5 ||
                         std::abs(normalize_angle(second->pose.theta - best.pose.theta)) >= 0.26;
    EXPECT_TRUE(outside);
    EXPECT_LE(second->score, best.score);
  }
  return second;
}

TEST(BranchAndBoundMatcher, TheRunnerUpOfAFeaturelessCorridorLiesAlongItAndScoresAlmostAsWell) {
  // 30 m of straight corridor, 2 m wide: shifted along it, a scan fits as well.
  const World corridor({{{0, 0}, {30, 0}}, {{0, 2}, {30, 2}}});
  Rng rng(11);
  MultiResMap map;
  for (double x = 5; x <= 25; x += 2.5) map.insert_scan(Pose2(x, 1, 0), Pose2(), scan_at(corridor, Pose2(x, 1, 0), rng));
  const BranchAndBoundMatcher matcher(map.finest(), 2.0);
  LidarConfig short_range;
  short_range.beams = 180;
  short_range.range_max = 5.0;  // the corridor's ends out of sight
  const Pose2 truth(14.0, 1.1, 0.05);
  const std::vector<ScanPoint> points = scan_to_points(simulate_scan(corridor, truth, short_range, rng));
  const SearchWindow window{2.0, 0.2};
  const auto best = matcher.match(points, truth, window, 0.0);
  ASSERT_TRUE(best);
  const auto second = runner_up(matcher, points, truth, window, *best);
  ASSERT_TRUE(second);
  EXPECT_GT(second->score, 0.9 * best->score);
  EXPECT_GE(std::abs(second->pose.x - best->pose.x), 0.5);
  EXPECT_LT(std::abs(second->pose.y - best->pose.y), 0.06);
}

TEST(BranchAndBoundMatcher, TheRunnerUpInAnOfficeScoresLess) {
  const World world = office();
  Rng rng(9);
  const MultiResMap map = map_of(world, rng);
  const BranchAndBoundMatcher matcher(map.finest(), 2.0);
  const Pose2 truth(3.0, 2.5, 0.2);
  const std::vector<ScanPoint> points = scan_at(world, truth, rng);
  const auto best = matcher.match(points, truth, {2.0, 0.3}, 0.0);
  ASSERT_TRUE(best);
  const auto second = runner_up(matcher, points, truth, {2.0, 0.3}, *best);
  ASSERT_TRUE(second);
  EXPECT_LT(second->score, best->score);
}

TEST(BranchAndBoundMatcher, RebuiltForAnotherGridItMatchesAsOneBuiltFresh) {
  // Rebuilding reuses the bounds' memory: nothing of the grid before may show.
  const World world = office();
  Rng rng(11);
  const MultiResMap small = map_of(world, rng);
  MultiResMap big;
  for (const Pose2& p : {Pose2(2, 2, 0.3), Pose2(10, 3, -2.8)}) big.insert_scan(p, Pose2(), scan_at(world, p, rng));
  // The other map far away, so that stale bounds would be garbage where the search looks.
  big.insert_scan(Pose2(-30, 40, 0.0), Pose2(), scan_at(world, Pose2(2, 2, 0.3), rng));
  const Pose2 truth(3.3, 3.1, 0.7);
  const std::vector<ScanPoint> points = scan_at(world, truth, rng);
  const Pose2 prior = truth * Pose2(0.2, -0.15, 0.1);
  BranchAndBoundMatcher reused(big.finest(), 2.5, 9);
  ASSERT_EQ(reused.depth(), 8);
  // Fewer levels than before, then as many again.
  for (const double window : {0.3, 2.5}) {
    reused.rebuild(small.finest(), window, 9, CellIndex{-20, -20}, CellIndex{260, 220});
    const BranchAndBoundMatcher fresh(small.finest(), window, 9, CellIndex{-20, -20}, CellIndex{260, 220});
    EXPECT_EQ(reused.depth(), fresh.depth());
    const auto a = reused.match(points, prior, {window, 0.15}, 0.1), b = fresh.match(points, prior, {window, 0.15}, 0.1);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->score, b->score);
    EXPECT_EQ(a->pose.x, b->pose.x);
    EXPECT_EQ(a->pose.y, b->pose.y);
    EXPECT_EQ(a->pose.theta, b->pose.theta);
    EXPECT_LT(std::hypot(a->pose.x - truth.x, a->pose.y - truth.y), 0.08);
    for (const Pose2& p : {prior, truth, Pose2(1.0, 1.0, 0.0), Pose2(8.0, 4.0, 1.0)})
      EXPECT_EQ(reused.score(points, p), fresh.score(points, p));
  }
}

TEST(BranchAndBoundMatcher, LookupsWithoutBoundsChecksFindWhatTheCheckedOnesFind) {
  // A grid whose cells reach far beyond the office: every lookup of a search
  // lands inside its bounds, so match() reads the bounds without checks; on
  // the office's own grid candidates near its edge are checked point by point.
  const World world = office();
  Rng rng(17);
  const MultiResMap map = map_of(world, rng);
  DsGrid wide = map.finest();
  wide.set({-200, -200}, DsMass{0.3f, 0.2f});
  wide.set({500, 500}, DsMass{0.3f, 0.2f});
  const BranchAndBoundMatcher checked(map.finest(), 0.6), unchecked(wide, 0.6);
  for (const Pose2& truth : {Pose2(3.3, 3.1, 0.7), Pose2(6.2, 2.2, -0.4), Pose2(2.0, 7.5, 2.0)}) {
    const std::vector<ScanPoint> points = scan_at(world, truth, rng);
    const Pose2 prior = truth * Pose2(0.3, -0.2, 0.08);
    const SearchWindow window{0.6, 0.12};
    const auto a = checked.match(points, prior, window, 0.0), b = unchecked.match(points, prior, window, 0.0);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->score, b->score);
    EXPECT_EQ(a->pose.x, b->pose.x);
    EXPECT_EQ(a->pose.y, b->pose.y);
    EXPECT_EQ(a->pose.theta, b->pose.theta);
    EXPECT_DOUBLE_EQ(unchecked.score(points, b->pose), b->score);
    // The runner-up search too.
    const auto a2 = checked.match(points, prior, window, 0.0, a->pose, 0.2, 0.1);
    const auto b2 = unchecked.match(points, prior, window, 0.0, b->pose, 0.2, 0.1);
    ASSERT_EQ(a2.has_value(), b2.has_value());
    if (a2) {
      EXPECT_EQ(a2->score, b2->score);
    }
  }
}

}  // namespace
}  // namespace dsswarm
