#include "swarm/live_map.hpp"

#include <gtest/gtest.h>

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
  ASSERT_TRUE(a.follow("b", b.moves({})));
  const MultiResMap after = live.compose(*a.live_map_parts());
  EXPECT_EQ(live.base_compositions(), 2u);
  EXPECT_LE(live_apart(after, expected()), kRounding);
  EXPECT_GT(test::cells_apart(after.finest(), before.finest()), 0.1);
}

}  // namespace
}  // namespace dsswarm
