#include "slam/loop_search.hpp"

#include <gtest/gtest.h>

#include "common/rng.hpp"
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

std::vector<ScanPoint> scan_at(const World& world, const Pose2& pose, Rng& rng, double range = 30.0) {
  LidarConfig lidar;
  lidar.beams = 180;
  lidar.range_max = range;
  return scan_to_points(simulate_scan(world, pose, lidar, rng));
}

// A finished submap of scans taken along `path` (truth = local frame here).
Submap submap_of(const World& world, const std::vector<Pose2>& path, Rng& rng, double range = 30.0) {
  Submap s;
  s.anchor = path.front();
  s.finished = true;
  for (const Pose2& p : path) s.map.insert_scan(p, Pose2(), scan_at(world, p, rng, range));
  s.scans = static_cast<int>(path.size());
  return s;
}

LoopSearch search(const Submap& s, const std::vector<ScanPoint>& points, const Pose2& prior, const SearchWindow& w,
                  const LoopSearchConfig& config = {}) {
  const BranchAndBoundMatcher matcher(s.map.finest(), w.xy, config.max_depth);
  return search_loop_closure(matcher, s, points, prior, w, config, 7);
}

TEST(LoopSearch, FindsTheNodeInTheSubmapFromAPriorOffByHalfAMetre) {
  const World world = office();
  Rng rng(1);
  // Local SLAM drove 3 m across the room, a scan every 10 cm.
  std::vector<Pose2> path;
  for (int k = 0; k <= 30; ++k) path.push_back(Pose2(2 + 0.1 * k, 2 + 0.03 * k, 0.2 + 0.01 * k));
  const Submap s = submap_of(world, path, rng);
  const Pose2 truth(3.5, 2.2, -0.3);
  const LoopSearch r = search(s, scan_at(world, truth, rng), truth * Pose2(0.4, -0.3, 0.08), {0.8, 0.15});
  ASSERT_EQ(r.rejection, LoopRejection::none) << to_string(r.rejection);
  const Pose2 e = between(between(s.anchor, truth), r.candidate.relative);
  EXPECT_LT(std::hypot(e.x, e.y), 0.03);
  EXPECT_LT(std::abs(e.theta), 0.01);
  EXPECT_GT(r.candidate.inliers, 0.8);
  EXPECT_GT(r.candidate.same_side, 0.8);
}

TEST(LoopSearch, AScanOfAnotherPlaceIsRejected) {
  const World world = office();
  // Somewhere else: a long corridor with alcoves, nothing like the office.
  const World corridor({{{0, 0}, {20, 0}}, {{0, 2}, {20, 2}}, {{6, 2}, {6, 3}}, {{7, 2}, {7, 3}}, {{6, 3}, {7, 3}}});
  Rng rng(2);
  const Submap s = submap_of(world, {Pose2(2, 2, 0.2), Pose2(3, 2.5, 0.4)}, rng);
  const Pose2 elsewhere(5, 1, 0.0);
  const LoopSearch r = search(s, scan_at(corridor, elsewhere, rng), Pose2(3, 2.4, 0.1), {1.0, 0.3});
  EXPECT_NE(r.rejection, LoopRejection::none);
}

TEST(LoopSearch, AThinWallSeenFromItsOtherSideIsRejected) {
  // A 4 m room below a 3 m one, one thin wall between them. The submap saw
  // the lower room only; a scan from the upper room, 1 m above the wall,
  // fits the wall where it is, from behind (its other wall lies in space the
  // submap never saw): only the same-side check tells.
  const World rooms({{{0, 0}, {10, 0}}, {{0, 4}, {10, 4}}, {{0, 7}, {10, 7}}, {{0, 0}, {0, 7}}, {{10, 0}, {10, 7}}});
  Rng rng(3);
  std::vector<Pose2> path;
  for (int k = 0; k <= 30; ++k) path.push_back(Pose2(2 + 0.2 * k, 2, 0.03 * k));
  const Submap s = submap_of(rooms, path, rng, 3.5);
  const Pose2 above(5, 5, 0.0);
  const LoopSearch r = search(s, scan_at(rooms, above, rng, 3.5), above, {0.3, 0.05});
  EXPECT_EQ(r.rejection, LoopRejection::same_side) << to_string(r.rejection);
  EXPECT_LT(r.candidate.same_side, 0.3);
}

TEST(LoopSearch, AFeaturelessCorridorIsAmbiguous) {
  const World corridor({{{0, 0}, {30, 0}}, {{0, 2}, {30, 2}}});
  Rng rng(4);
  std::vector<Pose2> path;
  for (double x = 5; x <= 25; x += 2.5) path.push_back(Pose2(x, 1, 0));
  const Submap s = submap_of(corridor, path, rng, 6.0);
  const Pose2 truth(14.0, 1.1, 0.05);
  const LoopSearch r = search(s, scan_at(corridor, truth, rng, 6.0), truth * Pose2(0.5, 0.0, 0.0), {1.5, 0.1});
  EXPECT_EQ(r.rejection, LoopRejection::ambiguous) << to_string(r.rejection);
  EXPECT_GT(r.candidate.runner_up, 0.9);
}

TEST(LoopSearch, AScanThatOnlyGrazesTheSubmapIsNotSlidOntoIt) {
  // A corridor with a niche every 3 m. The submap saw it from x = 6 to 12,
  // looking ahead; the robot comes back from behind, at x = 1: only the far
  // end of its scan reaches what the submap saw. One niche further on, all
  // of the scan lands on mapped cells and fits as well as it does here.
  std::vector<Segment> walls{{{-10, 0}, {40, 0}}, {{-10, 2}, {40, 2}}};
  for (double x = -9; x < 40; x += 3.0) {
    walls.push_back({{x, 2}, {x, 2.6}});
    walls.push_back({{x, 2.6}, {x + 0.8, 2.6}});
    walls.push_back({{x + 0.8, 2.6}, {x + 0.8, 2}});
  }
  const World corridor(std::move(walls));
  Rng rng(5);
  std::vector<Pose2> path;
  for (double x = 6; x <= 12; x += 0.5) path.push_back(Pose2(x, 1, 0));
  const Submap s = submap_of(corridor, path, rng, 8.0);
  const Pose2 truth(1.0, 1.0, 0.0);
  const std::vector<ScanPoint> points = scan_at(corridor, truth, rng, 8.0);
  const SearchWindow window{4.0, 0.1};
  const LoopSearch r = search(s, points, truth, window);
  EXPECT_EQ(r.rejection, LoopRejection::prior_fits) << to_string(r.rejection);
  EXPECT_GE(r.candidate.prior_inliers, 0.75);
  // Without the check, the scan would be slid a niche along onto the submap.
  LoopSearchConfig unchecked;
  unchecked.min_prior_known = 1.0;
  const LoopSearch slid = search(s, points, truth, window, unchecked);
  ASSERT_EQ(slid.rejection, LoopRejection::none) << to_string(slid.rejection);
  const Pose2 e = between(between(s.anchor, truth), slid.candidate.relative);
  EXPECT_GT(std::hypot(e.x, e.y), 1.0);
}

TEST(LoopSearch, ClosuresAgreeWhenTheyImplyTheSameMotion) {
  // Two nodes 1 m apart, each closed into one submap exactly as the graph has it.
  PoseGraph g;
  g.nodes = {Pose2(10, 0, 0.1), Pose2(11, 0.1, 0.1)};
  g.submaps = {Pose2(0, 0, 0.0)};
  const Constraint a{Constraint::Kind::loop, 0, 0, between(g.submaps[0], g.nodes[0])};
  Constraint b{Constraint::Kind::loop, 0, 1, between(g.submaps[0], g.nodes[1])};
  EXPECT_TRUE(closures_agree(g, a, b, 0.1, 0.035));
  // Both shifted by the same correction (the trajectory drifted): still agree.
  Constraint a2 = a, b2 = b;
  a2.relative = Pose2(0.5, 0.2, 0.05) * a.relative;
  b2.relative = Pose2(0.5, 0.2, 0.05) * b.relative;
  EXPECT_TRUE(closures_agree(g, a2, b2, 0.1, 0.035));
  // One of them placed 0.4 m off: they disagree.
  b.relative = b.relative * Pose2(0.4, 0.0, 0.0);
  EXPECT_FALSE(closures_agree(g, a, b, 0.1, 0.035));
}

}  // namespace
}  // namespace dsswarm
