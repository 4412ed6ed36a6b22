#include "agent/shared_agent.hpp"

#include <gtest/gtest.h>

#include "sim/lidar.hpp"
#include "grid/test_cells.hpp"
#include "swarm/map_merge.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm::agent {
namespace {

// A robot that has driven a straight line through the L-shaped office.
std::unique_ptr<SwarmAgent> robot_after_drive(const std::string& name, const Pose2& from, const Pose2& to,
                                              std::uint64_t seed) {
  auto agent = std::make_unique<SwarmAgent>(name, without_loop_closure(SlamConfig{}));
  const World world = test::l_shaped_office();
  Rng rng(seed);
  for (int k = 0; k < 20; ++k) {
    const Pose2 p = interpolate(from, to, k / 19.0);
    LaserScan scan = simulate_scan(world, p, test::full_circle_lidar(), rng);
    scan.timestamp = 1000.0 + 0.1 * k;
    scan.odometry = from.inverse() * p;
    agent->process(scan);
  }
  return agent;
}

bool same_cells(const MultiResMap& x, const MultiResMap& y) {
  return test::same_cells(x.finest().to_raster(), y.finest().to_raster());
}

const Pose2 kStartA{1.5, 1.5, 0.4}, kStartB{8.5, 2.0, -2.5};

// A view is taken at the scan an event names; a merge from an earlier
// encounter comes in after it but before this encounter opens. In one process
// that merge would be in the map this encounter locates on: so it must be here,
// though the background composer has not had it installed.
TEST(SharedAgent, AViewTakenBeforeAMergeIsBroughtUpToTheKnowledgeWhenItsEncounterOpens) {
  std::unique_ptr<SwarmAgent> b = robot_after_drive("b", kStartB, {5.0, 2.5, 2.9}, 2);
  const MapSnapshot from_b = b->snapshot();
  SharedAgent a(robot_after_drive("a", kStartA, {3.0, 2.0, 0.1}, 1), RelativePoseConfig{});
  const MultiResMap own = a.with_agent([](const SwarmAgent& x) { return x.slam().own_map(); });

  a.stage_view("c", 1);  // nothing merged since: the view's map is the own map
  const std::optional<protocol::CapturedView> plain = a.capture_view("c", 1);
  ASSERT_TRUE(plain);
  EXPECT_TRUE(same_cells(*plain->view.map, own));

  a.stage_view("c", 2);
  const Pose2 b_in_a = kStartA.inverse() * kStartB;
  a.merge(b->snapshot(), b_in_a, protocol::CapturedView{}, 7);  // an earlier encounter's merge; nothing installed
  const std::optional<protocol::CapturedView> v = a.capture_view("c", 2);
  ASSERT_TRUE(v);
  const MultiResMap want = compose_working_map(own, a.with_agent([](const SwarmAgent& x) { return x.knowledge().layers(); }));
  EXPECT_FALSE(same_cells(want, own));  // b's map adds to a's
  EXPECT_TRUE(same_cells(*v->view.map, want));
  EXPECT_EQ(v->stamp, 1000.0 + 0.1 * 19);  // still the staged scan's
}

// The snapshot an encounter sends holds the own map as at the view's scan,
// however many scans came in while the exchange ran (as in one process).
TEST(SharedAgent, TheSnapshotSendsTheOwnMapAsAtTheViewsScan) {
  SharedAgent a(robot_after_drive("a", kStartA, {3.0, 2.0, 0.1}, 1), RelativePoseConfig{});
  a.stage_view("b", 1);
  const std::optional<protocol::CapturedView> v = a.capture_view("b", 1);
  ASSERT_TRUE(v);
  const std::uint64_t at_view = a.with_agent([](const SwarmAgent& x) { return x.own_version(); });
  EXPECT_EQ(v->own_version, at_view);
  Rng rng(5);
  const Pose2 next{3.2, 2.0, 0.1};
  LaserScan scan = simulate_scan(test::l_shaped_office(), next, test::full_circle_lidar(), rng);
  scan.timestamp = 1002.0;
  scan.odometry = kStartA.inverse() * next;
  a.process(scan);
  ASSERT_GT(a.with_agent([](const SwarmAgent& x) { return x.own_version(); }), at_view);
  const MapSnapshot sent = a.snapshot(*v);
  ASSERT_FALSE(sent.layers.empty());
  EXPECT_EQ(sent.layers[0].origin, "a");
  EXPECT_EQ(sent.layers[0].version, at_view);
  EXPECT_EQ(sent.layers[0].map.get(), v->own.get());
}

}  // namespace
}  // namespace dsswarm::agent
