#include "agent/shared_agent.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "sim/lidar.hpp"
#include "grid/test_cells.hpp"
#include "swarm/map_merge.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm::agent {
namespace {

// 20 scans 0.1 s apart along a straight line through the L-shaped office.
std::vector<LaserScan> drive(const Pose2& start, const Pose2& from, const Pose2& to, std::uint64_t seed, double t0) {
  const World world = test::l_shaped_office();
  Rng rng(seed);
  std::vector<LaserScan> scans;
  for (int k = 0; k < 20; ++k) {
    const Pose2 p = interpolate(from, to, k / 19.0);
    LaserScan scan = simulate_scan(world, p, test::full_circle_lidar(), rng);
    scan.timestamp = t0 + 0.1 * k;
    scan.odometry = start.inverse() * p;
    scans.push_back(std::move(scan));
  }
  return scans;
}

// A robot that has driven a straight line through the L-shaped office.
std::unique_ptr<SwarmAgent> robot_after_drive(const std::string& name, const Pose2& from, const Pose2& to,
                                              std::uint64_t seed, double merge_delay = 0.0) {
  auto agent = std::make_unique<SwarmAgent>(name, without_loop_closure(SlamConfig{}));
  agent->set_merge_delay(merge_delay);
  for (const LaserScan& scan : drive(from, from, to, seed, 1000.0)) agent->process(scan);
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

// The two paths to a merge: in one process it is composed on the spot; a
// robot process composes it on another thread while scans go on. Either way
// it takes effect before the same scan, and the maps are the same to the bit.
TEST(SharedAgent, AMergeTakesEffectAtTheSameScanAndTheSameMapAsInOneProcess) {
  const double delay = 0.55;  // between scans: no tie to break
  std::unique_ptr<SwarmAgent> b = robot_after_drive("b", kStartB, {5.0, 2.5, 2.9}, 2);
  const Pose2 b_in_a = kStartA.inverse() * kStartB;
  std::unique_ptr<SwarmAgent> alone = robot_after_drive("a", kStartA, {3.0, 2.0, 0.1}, 1, delay);
  SharedAgent shared(robot_after_drive("a", kStartA, {3.0, 2.0, 0.1}, 1, delay), RelativePoseConfig{});

  // One process: the encounter at the last scan, merged at once.
  ASSERT_TRUE(alone->absorb(b->snapshot(), b_in_a));
  alone->schedule_merge(1, alone->last_scan()->timestamp);
  // A robot process: the view at that scan, the merge a few scans later.
  shared.stage_view("b", 1);
  const std::optional<protocol::CapturedView> at = shared.capture_view("b", 1);
  ASSERT_TRUE(at);
  const std::vector<LaserScan> more = drive(kStartA, {3.0, 2.0, 0.1}, {4.0, 2.2, 0.1}, 3, 1002.0);
  std::size_t k = 0;
  std::optional<std::size_t> alone_at, shared_at;
  const auto step = [&] {
    if (alone->install_due(more[k].timestamp, true)) alone_at = k;
    if (shared.install_due(more[k].timestamp)) shared_at = k;
    alone->process(more[k]);
    shared.process(more[k]);
    ++k;
  };
  for (int i = 0; i < 2; ++i) step();
  shared.merge(b->snapshot(), b_in_a, *at, 1);
  const auto deadline = SteadyClock::now() + std::chrono::seconds(30);
  while (shared.take_composed().empty() && SteadyClock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  while (k < more.size()) step();

  ASSERT_TRUE(alone_at);
  EXPECT_EQ(shared_at, alone_at);
  EXPECT_GE(more[*alone_at].timestamp, at->stamp + delay);
  const MultiResMap got = shared.with_agent([](const SwarmAgent& x) { return x.slam().map(); });
  EXPECT_GT(test::largest_difference(got.finest(), shared.with_agent([](const SwarmAgent& x) { return x.slam().own_map().finest(); })), 0.1);
  for (int level = 0; level < got.levels(); ++level)
    EXPECT_EQ(test::largest_difference(got.level(level), alone->slam().map().level(level)), 0.0) << "level " << level;
  const Pose2 pose = shared.with_agent([](const SwarmAgent& x) { return x.slam().pose(); });
  EXPECT_EQ(pose.x, alone->slam().pose().x);
  EXPECT_EQ(pose.y, alone->slam().pose().y);
  EXPECT_EQ(pose.theta, alone->slam().pose().theta);
}

}  // namespace
}  // namespace dsswarm::agent
