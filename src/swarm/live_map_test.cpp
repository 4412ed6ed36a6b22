#include "swarm/live_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"

#include "grid/test_cells.hpp"
#include "sim/test_laps.hpp"
#include "swarm/map_merge.hpp"
#include "swarm/swarm_agent.hpp"

namespace dsswarm {
namespace {

// The live map holds the finest level only.
double live_apart(const MultiResMap& live, const MultiResMap& b) {
  EXPECT_EQ(live.levels(), 1);
  return test::cells_apart(live.finest(), b.finest());
}

// The live map is the robot's own map as its graph places the submaps now —
// before and after a loop closure — and what did not move is not composed again.
TEST(LiveMap, IsTheOwnMapAsTheGraphPlacesItNowAndComposesAgainOnlyWhatMoved) {
  const SimulatedRun run = test::long_loop(1.3, 1);
  SwarmAgent b("b", with_loop_closure());
  const std::size_t half = run.log.scans.size() / 2;
  for (std::size_t i = 0; i < half; ++i) b.process(run.log.scans[i]);
  LiveMap live;
  std::optional<LiveMapParts> parts = b.live_map_parts();
  ASSERT_TRUE(parts);
  ASSERT_GT(parts->finished.size(), 1u);
  ASSERT_TRUE(parts->growing);
  EXPECT_EQ(live_apart(live.compose(*parts), b.slam().own_map()), 0.0);
  EXPECT_EQ(live.base_compositions(), 1u);

  // One more scan into the growing submap: the rest is reused.
  const std::uint64_t revision = b.graph_revision();
  b.process(run.log.scans[half]);
  parts = b.live_map_parts();
  ASSERT_EQ(b.graph_revision(), revision);
  ASSERT_EQ(parts->finished.size(), b.slam().submaps().finished().size());
  const MultiResMap one_more = live.compose(*parts);
  EXPECT_EQ(live.base_compositions(), 1u);
  EXPECT_EQ(live_apart(one_more, b.slam().own_map()), 0.0);

  // The rest of the ring closes the loop: every submap moves, and the live map with them.
  for (std::size_t i = half + 1; i < run.log.scans.size(); ++i) b.process(run.log.scans[i]);
  b.finish();
  ASSERT_GT(b.graph_revision(), revision);
  EXPECT_EQ(live_apart(live.compose(*b.live_map_parts()), b.slam().own_map()), 0.0);
  EXPECT_EQ(live.base_compositions(), 2u);

  SlamConfig one_map;
  one_map.loop_closure.enabled = false;
  SwarmAgent plain("p", one_map);  // one map without loop closure: nothing to compose
  plain.process(run.log.scans[0]);
  EXPECT_FALSE(plain.live_map_parts());
}

// With another robot's layer held, the live map is own ⊕ that layer where it
// lies now: it follows the other robot's word that its map moved.
TEST(LiveMap, HoldsTheOtherRobotsLayerWhereItLiesNow) {
  const SimulatedRun rb = test::long_loop(1.3, 1), ra = test::lap(0, 1);
  SwarmAgent a("a", with_loop_closure()), b("b", with_loop_closure());
  for (std::size_t i = 0; i < rb.log.scans.size() / 3; ++i) b.process(rb.log.scans[i]);
  for (std::size_t i = 0; i < 60; ++i) a.process(ra.log.scans[i]);
  const Pose2 b_in_a(1.0, 2.0, 0.3);
  ASSERT_TRUE(a.absorb(b.snapshot(), b_in_a));
  LiveMap live;
  // Up to the cells' rounding: the layers go in before a's growing submap, not after.
  constexpr double kRounding = 1e-3;
  auto expected = [&a] { return compose_working_map(a.slam().own_map(), a.knowledge().layers()); };
  const MultiResMap before = live.compose(*a.live_map_parts());
  EXPECT_LE(live_apart(before, expected()), kRounding);
  EXPECT_GT(test::cells_apart(before.finest(), a.slam().own_map().finest()), 0.1);  // b's evidence is in

  for (std::size_t i = rb.log.scans.size() / 3; i < rb.log.scans.size(); ++i) b.process(rb.log.scans[i]);
  b.finish();  // closes its loop: its submaps move
  ASSERT_TRUE(a.follow("b", b.moves("a", {}, 4096)));
  const MultiResMap after = live.compose(*a.live_map_parts());
  EXPECT_EQ(live.base_compositions(), 2u);
  EXPECT_LE(live_apart(after, expected()), kRounding);
  EXPECT_GT(test::cells_apart(after.finest(), before.finest()), 0.1);
}

// A pose-graph round moves every submap a little: a move under
// redraw_cells keeps the part composed before; one beyond it, by a shift or
// by a turn whose sweep at the submap's far cells is beyond it, does not.
TEST(LiveMap, KeepsItsPartThroughMovesUnderAFractionOfACell) {
  const SimulatedRun run = test::long_loop(1.3, 1);
  SwarmAgent b("b", with_loop_closure());
  for (std::size_t i = 0; i < run.log.scans.size() / 2; ++i) b.process(run.log.scans[i]);
  LiveMapParts parts = *b.live_map_parts();
  ASSERT_GT(parts.finished.size(), 1u);
  const double cell = parts.config.resolution;
  LiveMap live(LiveMapConfig{.redraw_cells = 0.5});
  const MultiResMap first = live.compose(parts);
  ASSERT_EQ(live.base_compositions(), 1u);

  const Pose2 at = parts.finished_poses[0];
  parts.finished_poses[0] = Pose2(at.x + 0.3 * cell, at.y, at.theta);
  EXPECT_EQ(test::cells_apart(live.compose(parts).finest(), first.finest()), 0.0);  // kept as it was
  EXPECT_EQ(live.base_compositions(), 1u);

  // A turn that moves the submap's centre by nothing but its far cells by more.
  CellIndex lo, hi;
  parts.finished[0]->frozen.bounds(lo, hi);
  const double reach = 0.5 * cell * std::hypot(double(hi.x - lo.x), double(hi.y - lo.y));
  ASSERT_GT(reach, 10 * cell);
  const Eigen::Vector2d centre = Eigen::Vector2d(lo.x + hi.x, lo.y + hi.y) * (0.5 * cell);
  const Eigen::Vector2d c = at * centre;
  const Pose2 turn_about_centre = Pose2(c.x(), c.y(), 0) * Pose2(0, 0, 0.8 * cell / reach) * Pose2(-c.x(), -c.y(), 0);
  parts.finished_poses[0] = turn_about_centre * at;
  const MultiResMap turned = live.compose(parts);
  EXPECT_EQ(live.base_compositions(), 2u);
  EXPECT_EQ(test::cells_apart(turned.finest(), LiveMap(LiveMapConfig{.redraw_cells = 0.0}).compose(parts).finest()), 0.0);

  // Measured from the poses it was composed at: small steps do not add up unseen.
  parts.finished_poses[1] = Pose2(parts.finished_poses[1].x, parts.finished_poses[1].y + 0.3 * cell,
                                  parts.finished_poses[1].theta);
  live.compose(parts);
  EXPECT_EQ(live.base_compositions(), 2u);
  parts.finished_poses[1] = Pose2(parts.finished_poses[1].x, parts.finished_poses[1].y + 0.3 * cell,
                                  parts.finished_poses[1].theta);
  live.compose(parts);
  EXPECT_EQ(live.base_compositions(), 3u);
  EXPECT_THROW(LiveMap(LiveMapConfig{.redraw_cells = -1.0}), ConfigError);
}

// A submap finished since the last picture is added to the kept part, not
// composed again with everything else: the same map, cell for cell.
TEST(LiveMap, AddsASubmapFinishedSinceToWhatItKept) {
  const SimulatedRun run = test::long_loop(1.3, 1);
  SwarmAgent b("b", with_loop_closure());
  for (std::size_t i = 0; i < run.log.scans.size() / 2; ++i) b.process(run.log.scans[i]);
  const LiveMapParts now = *b.live_map_parts();
  ASSERT_GT(now.finished.size(), 2u);
  LiveMapParts before = now;
  before.finished.resize(now.finished.size() - 2);
  before.finished_poses.resize(now.finished.size() - 2);
  LiveMap live;
  live.compose(before);
  const MultiResMap added = live.compose(now);
  EXPECT_EQ(live.base_compositions(), 1u);
  EXPECT_EQ(live.base_additions(), 1u);
  EXPECT_EQ(test::cells_apart(added.finest(), LiveMap().compose(now).finest()), 0.0);

  // Had an older one moved as well, everything is composed again.
  LiveMap moved;
  moved.compose(before);
  LiveMapParts shifted = now;
  shifted.finished_poses[0].x += 0.5;
  moved.compose(shifted);
  EXPECT_EQ(moved.base_compositions(), 2u);
  EXPECT_EQ(moved.base_additions(), 0u);
}

}  // namespace
}  // namespace dsswarm
