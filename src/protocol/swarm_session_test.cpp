#include "protocol/swarm_session.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm {
namespace {

// A robot driving a straight line through the L-shaped office, with exact
// odometry starting at identity where it starts (its own map frame).
AgentStream drive(const std::string& name, const World& world, const Pose2& from, const Pose2& to, int scans,
                  std::uint64_t seed) {
  Rng rng(seed);
  AgentStream s{name, {}, {}};
  for (int k = 0; k < scans; ++k) {
    const Pose2 p = interpolate(from, to, static_cast<double>(k) / (scans - 1));
    LaserScan scan = simulate_scan(world, p, test::full_circle_lidar(), rng);
    scan.timestamp = 0.1 * k;
    scan.odometry = from.inverse() * p;
    s.scans.push_back(std::move(scan));
    s.clock.push_back(0.1 * k);
  }
  return s;
}

std::size_t obstacle_cells(const DsGrid& grid) {
  std::size_t n = 0;
  grid.for_each_tile([&](CellIndex, const PackedMass* cells) {
    for (int i = 0; i < DsGrid::kTileCells; ++i) n += cells[i].mass().occupied > 0.3f ? 1 : 0;
  });
  return n;
}

std::vector<AgentStream> two_robots(const World& world) {
  return {drive("a", world, {1.5, 1.5, 0.4}, {3.0, 2.0, 0.1}, 30, 1),
          drive("b", world, {8.5, 2.0, -2.5}, {5.0, 2.5, 2.9}, 30, 2)};
}

TEST(SwarmSession, RobotsThatMeetMergeAndKnowEachOther) {
  const World world = test::l_shaped_office();
  // Two proximity events: the first verified estimate waits for the second to confirm it.
  SwarmSession session(two_robots(world), {{2.45, 0, 1}, {2.95, 0, 1}}, SwarmConfig{});
  session.run();
  ASSERT_EQ(session.encounters().size(), 2u);
  EXPECT_FALSE(session.encounters().front().accepted) << session.encounters().front().reason;
  EXPECT_NE(session.encounters().front().reason.find("confirm"), std::string::npos);
  const EncounterRecord& r = session.encounters().back();
  ASSERT_TRUE(r.accepted) << r.reason;
  EXPECT_EQ(r.confirmed_by, "earlier encounter");
  // b's frame in a's frame, by construction of the two drives: each map
  // frame is its robot's start, turned to the office's walls (first pose).
  const auto frame = [&](std::size_t i, const Pose2& start) {
    return start * session.agent(i).slam().trajectory().front().inverse();
  };
  const Pose2 truth = frame(0, {1.5, 1.5, 0.4}).inverse() * frame(1, {8.5, 2.0, -2.5});
  EXPECT_NEAR(r.b_frame_in_a.x, truth.x, 0.05);
  EXPECT_NEAR(r.b_frame_in_a.y, truth.y, 0.05);
  EXPECT_NEAR(normalize_angle(r.b_frame_in_a.theta - truth.theta), 0.0, 0.01);
  ASSERT_NE(session.agent(0).knowledge().find("b"), nullptr);
  ASSERT_NE(session.agent(1).knowledge().find("a"), nullptr);
  // Merged: each working map sees obstacles its own scans never did.
  for (std::size_t i = 0; i < 2; ++i)
    EXPECT_GT(obstacle_cells(session.agent(i).slam().map().finest()),
              obstacle_cells(session.agent(i).slam().own_map().finest()) + 50);
  EXPECT_EQ(session.track(0).steps.size(), 30u);
  EXPECT_EQ(session.track(1).steps.size(), 30u);
}

TEST(SwarmSession, WithoutConfirmationOneVerifiedEncounterMerges) {
  const World world = test::l_shaped_office();
  SwarmConfig config;
  config.confirm = false;
  SwarmSession session(two_robots(world), {{2.95, 0, 1}}, config);
  session.run();
  ASSERT_EQ(session.encounters().size(), 1u);
  EXPECT_TRUE(session.encounters().front().accepted) << session.encounters().front().reason;
  EXPECT_NE(session.agent(0).knowledge().find("b"), nullptr);
}

TEST(SwarmSession, WithoutMergingEveryRobotMapsAlone) {
  const World world = test::l_shaped_office();
  SwarmConfig config;
  config.merge = false;
  SwarmSession session(two_robots(world), {{2.95, 0, 1}}, config);
  session.run();
  EXPECT_TRUE(session.encounters().empty());
  EXPECT_EQ(session.agent(0).knowledge().size(), 0u);
  EXPECT_EQ(session.track(0).steps.size(), 30u);
}

TEST(SwarmSession, AnEncounterBeforeARobotStartsIsSkipped) {
  const World world = test::l_shaped_office();
  auto streams = two_robots(world);
  for (double& t : streams[1].clock) t += 100.0;  // b starts late
  SwarmSession session(std::move(streams), {{1.0, 0, 1}}, SwarmConfig{});
  session.run();
  EXPECT_TRUE(session.encounters().empty());
  EXPECT_EQ(session.events_skipped(), 1u);
  EXPECT_EQ(session.skipped().at(0), "b had not started");
  EXPECT_EQ(session.track(1).steps.size(), 30u);  // and b still plays all its scans
}

TEST(SwarmSession, RejectsBadInput) {
  const World world = test::l_shaped_office();
  EXPECT_THROW(SwarmSession({}, {}, SwarmConfig{}), ConfigError);
  EXPECT_THROW(SwarmSession(two_robots(world), {{1.0, 0, 5}}, SwarmConfig{}), ConfigError);
  EXPECT_THROW(SwarmSession(two_robots(world), {{1.0, 1, 1}}, SwarmConfig{}), ConfigError);
  auto same_names = two_robots(world);
  same_names[1].name = same_names[0].name;
  EXPECT_THROW(SwarmSession(std::move(same_names), {}, SwarmConfig{}), ConfigError);
  auto backwards = two_robots(world);
  backwards[0].clock[5] = -1.0;
  EXPECT_THROW(SwarmSession(std::move(backwards), {}, SwarmConfig{}), ConfigError);
}

}  // namespace
}  // namespace dsswarm
