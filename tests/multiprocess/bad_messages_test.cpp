// A test publisher (a plain DDS participant, "mallory") writes malformed,
// truncated, oversized, wrong-version, non-finite, misdirected and replayed
// swarm messages into a running robot's inbox: every one is refused and
// counted by reason in its stats.json, and the robot goes on mapping and
// merging with its honest peer as if nothing had happened.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <unistd.h>

#include <fstream>
#include <thread>

#include "apps/sim_swarm_run.hpp"
#include "multiprocess.hpp"

namespace dsswarm::mp {
namespace {

TEST(MultiProcessFaults, BadMessagesAreRefusedAndCountedTheRobotMapsAndMergesOn) {
  Rig rig;
  const int domain = test_domain();
  const std::string swarm = fmt::format("bad{}", getpid());
  const fs::path config = rig.dir() / "config.json";
  std::ofstream(config) << R"({"swarm": {"exchange_timeout": 10}})";
  const double start_at = unix_in(3.0);
  for (int k = 1; k <= 2; ++k) {
    SimAgent a;
    a.name = fmt::format("robot{}", k);
    a.robot = k;
    a.robots = 2;
    a.start_at = start_at;
    a.domain = domain;
    a.out = rig.dir() / a.name;
    a.extra = {"--swarm", swarm, "--config", config.string(), "--linger", "3"};
    rig.start(a.name, agent_args(a));
  }
  SwarmTap tap(domain, net::swarm_partition(swarm), "mallory");
  ASSERT_TRUE(wait_for_heartbeat(tap, "robot1", 30s)) << "robot1 never came up";
  std::map<std::string, std::uint64_t> expected;
  protocol::MessageStamper mallory("mallory", 7);
  // Twice: before and while the robots map and meet.
  for (int round = 0; round < 2; ++round) {
    for (const auto& [reason, bytes] : bad_messages(mallory, "robot1")) {
      ASSERT_TRUE(tap.link.send("robot1", bytes)) << "could not send to robot1's inbox";
      if (!reason.empty()) ++expected[reason];
    }
    std::this_thread::sleep_for(5s);
  }

  for (std::size_t p = 0; p < 2; ++p) EXPECT_EQ(rig.wait(p, 90s), 0) << "robot" << p + 1;
  const SimSwarmRun sim = simulate_swarm_run({2, 1, 1, 3.0});
  const fs::path r1 = rig.dir() / "robot1", r2 = rig.dir() / "robot2";
  const nlohmann::json s1 = read_json(r1 / "stats.json"), s2 = read_json(r2 / "stats.json");
  using Counts = std::map<std::string, std::uint64_t>;
  EXPECT_EQ(s1.at("messages_rejected").get<Counts>(), expected) << s1.at("messages_rejected");
  EXPECT_TRUE(s2.at("messages_rejected").empty()) << s2.at("messages_rejected");
  // Mapping went on: every scan processed or counted as skipped, a pose for each.
  expect_complete_outputs(r1, sim.streams[0].scans.size());
  expect_complete_outputs(r2, sim.streams[1].scans.size());
  // ... and the honest pair merged: an encounter accepted on both sides, each holding the other's map.
  const std::size_t both = accepted_by_both(r1, r2);
  EXPECT_GE(both, 1u);
  EXPECT_TRUE(holds(s1, "robot2")) << "robot1 lacks robot2's map";
  EXPECT_TRUE(holds(s2, "robot1")) << "robot2 lacks robot1's map";
  std::cout << "robot1 refused " << s1.at("messages_rejected") << "; " << both << " encounters accepted by both\n";
}

}  // namespace
}  // namespace dsswarm::mp
