// A secured swarm of robot processes (`dsswarm keys`): robot1 and robot2
// hold valid certificates; robot3's are from another CA, robot4's was
// revoked, and a plain participant without any tries the swarm's topics.
// None of the three gets a byte of theirs through: their maps never reach
// the valid robots, which merge with each other as usual.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>

#include "multiprocess.hpp"
#include "protocol/gate.hpp"
#include "protocol/wire.hpp"

namespace dsswarm::mp {
namespace {

// `dsswarm keys ...`, to the end.
void keys(Rig& rig, const std::string& log, const std::vector<std::string>& args) {
  std::vector<std::string> argv{"keys"};
  argv.insert(argv.end(), args.begin(), args.end());
  ASSERT_EQ(rig.wait(rig.start(log, argv), 30s), 0) << rig.log_tail(log);
}

TEST(MultiProcessFaults, RobotsWithoutAValidCertificateNeverReachTheSwarm) {
  Rig rig;
  const int domain = test_domain();
  const fs::path swarm_keys = rig.dir() / "keys", other_keys = rig.dir() / "other_ca";
  for (const fs::path& k : {swarm_keys, other_keys})
    ASSERT_NO_FATAL_FAILURE(keys(rig, "keys_init_" + k.filename().string(), {"init", k.string(), "--swarm",
                                                                              std::to_string(domain)}));
  for (const char* r : {"robot1", "robot2", "robot4"})
    ASSERT_NO_FATAL_FAILURE(keys(rig, std::string("keys_add_") + r, {"add", swarm_keys.string(), r}));
  ASSERT_NO_FATAL_FAILURE(keys(rig, "keys_add_robot3_other_ca", {"add", other_keys.string(), "robot3"}));
  // robot4 keeps its copy from before it was revoked; the others get the new CRL.
  const fs::path robot4_keys = rig.dir() / "robot4_keys";
  fs::copy(swarm_keys, robot4_keys, fs::copy_options::recursive);
  ASSERT_NO_FATAL_FAILURE(keys(rig, "keys_revoke_robot4", {"revoke", swarm_keys.string(), "robot4"}));

  const fs::path config = rig.dir() / "config.json";
  std::ofstream(config) << R"({"swarm": {"exchange_timeout": 10}})";
  const double start_at = unix_in(4.0);
  std::vector<std::size_t> agents;
  for (int k = 1; k <= 4; ++k) {
    SimAgent a;
    a.name = fmt::format("robot{}", k);
    a.robot = k;
    a.robots = 4;
    a.start_at = start_at;
    a.out = rig.dir() / a.name;
    a.keys = k == 3 ? other_keys : k == 4 ? robot4_keys : swarm_keys;
    a.extra = {"--config", config.string(), "--linger", "3"};
    agents.push_back(rig.start(a.name, agent_args(a)));
  }

  // No certificate at all: a plain participant on the secured domain, where
  // the robots' swarm topics live (default partition), hears nobody and
  // reaches nobody.
  {
    SwarmTap intruder(domain, "", "intruder");
    protocol::MessageStamper stamper("intruder", 1);
    const auto hello = protocol::encode(stamper.stamp("robot1", protocol::Decline{1, "let me in"}));
    EXPECT_FALSE(intruder.link.send("robot1", hello)) << "an unsecured participant reached robot1's inbox";
    std::size_t heard = 0;
    for (auto until = std::chrono::steady_clock::now() + 5s; std::chrono::steady_clock::now() < until;)
      heard += intruder.link.receive(100ms).size();
    EXPECT_EQ(heard, 0u) << "an unsecured participant heard the secured swarm";
  }

  for (std::size_t p = 0; p < agents.size(); ++p) EXPECT_EQ(rig.wait(agents[p], 90s), 0) << "robot" << p + 1;
  std::map<std::string, nlohmann::json> stats;
  std::map<std::string, std::map<std::uint64_t, nlohmann::json>> outcomes;
  for (int k = 1; k <= 4; ++k) {
    const std::string name = fmt::format("robot{}", k);
    stats[name] = read_json(rig.dir() / name / "stats.json");
    outcomes[name] = outcomes_by_id(rig.dir() / name / "encounters.json");
  }
  auto knows = [&](const std::string& holder, const std::string& origin) { return holds(stats.at(holder), origin); };
  std::size_t tried = 0;  // encounters the valid robots opened with an unauthorized one
  for (const char* valid : {"robot1", "robot2"}) {
    for (const char* outsider : {"robot3", "robot4"}) {
      EXPECT_FALSE(knows(valid, outsider)) << valid << " holds " << outsider << "'s map";
      EXPECT_FALSE(knows(outsider, valid)) << outsider << " holds " << valid << "'s map";
      for (const auto& [id, o] : outcomes.at(valid))
        if (o.at("peer") == outsider) {
          ++tried;
          EXPECT_NE(o.at("end"), "accepted") << o.dump();
          EXPECT_EQ(o.at("bytes_received"), 0) << valid << " heard " << outsider << ": " << o.dump();
        }
    }
    EXPECT_TRUE(stats.at(valid).at("messages_rejected").empty()) << stats.at(valid).at("messages_rejected");
  }
  EXPECT_GT(tried, 0u) << "the scenario never brought a valid robot near an unauthorized one";
  // The control: the valid pair hears each other. Whether they also merge
  // depends on timing here (each offer to an unreachable intruder holds the
  // sender's swarm thread; docs/faults.md), so merges are reported, not required.
  std::size_t heard = 0;
  for (const auto& [a, b] : {std::pair{"robot1", "robot2"}, std::pair{"robot2", "robot1"}})
    for (const auto& [id, o] : outcomes.at(a))
      if (o.at("peer") == b && o.at("bytes_received").get<std::uint64_t>() > 0) ++heard;
  EXPECT_GE(heard, 2u) << "the valid robots did not hear each other";
  const std::size_t both = accepted_by_both(rig.dir() / "robot1", rig.dir() / "robot2");
  std::cout << "valid robots: " << heard << " encounters with bytes received, " << both
            << " accepted by both (robot1 knows robot2: " << knows("robot1", "robot2") << "); " << tried
            << " attempts with unauthorized robots, none heard\n";
}

}  // namespace
}  // namespace dsswarm::mp
