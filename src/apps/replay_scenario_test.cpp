// `dsswarm replay --scenario --agent` as a separate process on loopback, read
// back by a LiveScanSource: exactly that agent's stream of the scenario, on
// its session clock, forward and backward.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <string>

#include "apps/swarm_scenario.hpp"
#include "apps/swarm_tools_test_util.hpp"
#include "net/ros2_input.hpp"

namespace dsswarm {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

struct ReplayScenarioTest : testing::TestWithParam<std::size_t> {
  void SetUp() override { dir = test::fresh_dir("replay_scenario/" + net::test::test_id()); }
  void TearDown() override {
    group.stop_all(5s);
    fs::remove_all(dir);
  }
  fs::path dir;
  ProcessGroup group;
};

// robot1 plays forward from session time 0.5 s, robot2 backward from 0.
TEST_P(ReplayScenarioTest, ALiveSourceGetsExactlyTheAgentsStreamOnItsClock) {
  const fs::path yaml = test::write_tiny_scenario(dir);
  const SwarmScenario scenario = load_swarm_scenario(yaml);
  const AgentStream& want = scenario.streams.at(GetParam());
  net::Participant agent(net::test::loopback_config());
  net::LiveInputConfig config;
  config.ns = net::test::test_namespace();
  config.queue_capacity = 64;
  config.wait_for_odometry = 5.0;  // a loaded machine may deliver a scan's odometry after the default 0.25 s
  net::LiveScanSource input(agent, config);

  constexpr double kRate = 4.0, kStartIn = 1.5;
  const auto start = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kStartIn));
  const double start_at =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count() + kStartIn;
  const std::size_t replay = test::start_cli(
      group,
      {"replay", "--scenario", yaml.string(), "--agent", want.name, "--namespace", config.ns, "--rate", "4",
       "--start-at", fmt::format("{:.6f}", start_at), "--wait-for-subscribers", "1", "--domain",
       std::to_string(net::test::test_domain()), "--interface", "lo"},
      dir / "replay.txt");

  for (std::size_t i = 0; i < want.scans.size(); ++i) {
    const std::optional<LaserScan> got = input.next(10s);
    ASSERT_TRUE(got.has_value()) << "scan " << i << "\n" << test::read_text(dir / "replay.txt");
    if (i == 0) {  // not before its time: clock 0 is --start-at, the agent starts later
      EXPECT_GT(Clock::now() - start, std::chrono::duration<double>(want.clock[0] / kRate - 0.05)) << want.name;
    }
    const LaserScan& w = want.scans[i];
    EXPECT_EQ(got->timestamp, w.timestamp) << "scan " << i;
    EXPECT_EQ(net::test::bits(got->ranges), net::test::bits(w.ranges)) << "scan " << i;
    ASSERT_TRUE(got->odometry.has_value()) << "scan " << i;
    EXPECT_NEAR(got->odometry->x, w.odometry->x, 1e-9) << "scan " << i;
    EXPECT_NEAR(got->odometry->y, w.odometry->y, 1e-9) << "scan " << i;
    EXPECT_NEAR(got->odometry->theta, w.odometry->theta, 1e-9) << "scan " << i;
    EXPECT_NEAR(got->laser_offset.x, w.laser_offset.x, 1e-9);
  }
  // The whole stream took its session time / rate.
  const double took = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_GT(took, want.clock.back() / kRate - 0.05);
  EXPECT_LT(took, want.clock.back() / kRate + 1.5);
  EXPECT_EQ(group.wait(replay, 10s), 0) << test::read_text(dir / "replay.txt");
  EXPECT_NE(test::read_text(dir / "replay.txt").find(fmt::format("replayed {} scans", want.scans.size())),
            std::string::npos);
  EXPECT_EQ(input.stats().scans_dropped, 0u);
}

INSTANTIATE_TEST_SUITE_P(ForwardAndBackward, ReplayScenarioTest, testing::Values(std::size_t{0}, std::size_t{1}),
                         [](const testing::TestParamInfo<std::size_t>& p) {
                           return p.param == 0 ? std::string("Forward") : std::string("Backward");
                         });

TEST(ReplayScenario, AnUnknownAgentOrAMixOfModesIsAConfigError) {
  const fs::path dir = test::fresh_dir("replay_scenario/" + net::test::test_id());
  const fs::path yaml = test::write_tiny_scenario(dir);
  ProcessGroup group;
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"replay", "--scenario", yaml.string(), "--agent", "robot9"},
           {"replay", "--scenario", yaml.string()},
           {"replay", (dir / "tiny.log").string(), "--scenario", yaml.string(), "--agent", "robot1"},
           {"replay", "--scenario", yaml.string(), "--agent", "robot1", "--loop"},
           {"replay", "--scenario", yaml.string(), "--agent", "robot1", "--start-at", "nan"}}) {
    EXPECT_EQ(group.wait(test::start_cli(group, args, dir / "out.txt"), 10s), 2) << args.back();
  }
  const std::string out = test::read_text(dir / "out.txt");
  EXPECT_NE(out.find("error: --agent robot9: " + yaml.string() + " has no such agent (it has robot1, robot2)"),
            std::string::npos)
      << out;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dsswarm
