// `dsswarm proximity`, `trigger` and `status` as separate processes on
// loopback, against robot inboxes and heartbeats played by this test.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "apps/swarm_scenario.hpp"
#include "apps/swarm_tools_test_util.hpp"
#include "net/swarm_link.hpp"
#include "protocol/gate.hpp"
#include "protocol/wire.hpp"

namespace dsswarm {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

constexpr auto kProcessTimeout = 20s;

net::SwarmLinkConfig link_config(const std::string& name, bool listen) {
  net::SwarmLinkConfig c;
  c.name = name;
  c.listen = listen;
  c.partition = net::swarm_partition(test::test_swarm());
  return c;
}

// A robot as the swarm tools see it: its inbox, read through an agent's gate.
class FakeRobot {
 public:
  FakeRobot(net::Participant& p, std::string name) : name_(std::move(name)), link_(p, link_config(name_, true)), gate_(name_) {}

  struct Arrival {
    protocol::Proximity event;
    Clock::time_point at;
  };
  // Takes what has arrived (waiting up to `timeout`); every message must pass the gate.
  void poll(std::chrono::milliseconds timeout) {
    for (const auto& bytes : link_.receive(timeout)) {
      const protocol::MessageGate::Verdict v = gate_.admit(bytes);
      EXPECT_TRUE(v.rejected.empty()) << v.rejected;
      if (!v.message) continue;
      EXPECT_EQ(v.message->header.recipient, name_);
      if (const auto* p = std::get_if<protocol::Proximity>(&v.message->body)) arrivals.push_back({*p, Clock::now()});
    }
  }
  std::vector<Arrival> arrivals;

 private:
  std::string name_;
  net::DdsSwarmLink link_;
  protocol::MessageGate gate_;
};

// Polls both robots until each has `count` events or the time is up.
void collect(FakeRobot& a, FakeRobot& b, std::size_t count, std::chrono::seconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while ((a.arrivals.size() < count || b.arrivals.size() < count) && Clock::now() < deadline) {
    a.poll(20ms);
    b.poll(20ms);
  }
}

std::string unix_time_in(double seconds) {
  const auto t = std::chrono::system_clock::now() + std::chrono::duration_cast<std::chrono::system_clock::duration>(
                                                        std::chrono::duration<double>(seconds));
  return fmt::format("{:.6f}", std::chrono::duration<double>(t.time_since_epoch()).count());
}

struct SwarmToolsTest : testing::Test {
  void SetUp() override { dir = test::fresh_dir("swarm_tools/" + net::test::test_id()); }
  void TearDown() override {
    group.stop_all(5s);
    fs::remove_all(dir);
  }
  std::size_t run(std::vector<std::string> args) {
    for (const std::string& a : test::swarm_net_args()) args.push_back(a);
    return test::start_cli(group, args, dir / "out.txt");
  }
  std::string output() const { return test::read_text(dir / "out.txt"); }

  fs::path dir;
  net::Participant participant{net::test::loopback_config()};
  ProcessGroup group;
};

void expect_same_stamp(double got, double want, const std::string& what) {
  if (std::isnan(want)) {
    EXPECT_TRUE(std::isnan(got)) << what << ": " << got;
  } else {
    EXPECT_EQ(got, want) << what;
  }
}

TEST_F(SwarmToolsTest, ProximitySendsTheScenariosEventsOnTimeWithTheScansToActAfter) {
  const fs::path yaml = test::write_tiny_scenario(dir);
  const SwarmScenario scenario = load_swarm_scenario(yaml);
  const auto stamp = [&](std::size_t agent, std::size_t scan) { return scenario.streams[agent].scans.at(scan).timestamp; };
  // Worked out from the scenario (see write_tiny_scenario): robot1 plays file
  // scans 0..25 from 0.5 s, robot2 scans 39..15 from 0 s, 0.1 s apart.
  const double nan = std::nan("");
  struct Want {
    std::string a, b;
    double a_stamp, b_stamp, time;
  };
  const std::vector<Want> want = {
      {"robot1", "robot2", nan, stamp(1, 2), 0.23},                  // robot1 not started; robot2 at file scan 37
      {"robot2", "robot1", stamp(1, 10), stamp(0, 5), 1.03},         // file scans 29 and 5
      {"robot1", "robot2", stamp(0, 15), stamp(1, 20), 2.07},        // file scans 15 and 19
  };
  ASSERT_EQ(stamp(1, 2), test::kLogStart + 37 * test::kScanPeriod);
  FakeRobot robot1(participant, "robot1"), robot2(participant, "robot2");
  constexpr double kRate = 2.0, kLead = 0.2, kStartIn = 2.0;
  const auto start = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kStartIn));
  const std::size_t tool = run({"proximity", yaml.string(), "--rate", "2", "--lead", "0.2", "--start-at",
                                unix_time_in(kStartIn)});
  collect(robot1, robot2, want.size(), 15s);
  EXPECT_EQ(group.wait(tool, kProcessTimeout), 0) << output();

  for (const FakeRobot* robot : {&robot1, &robot2}) {
    ASSERT_EQ(robot->arrivals.size(), want.size()) << output();
    for (std::size_t k = 0; k < want.size(); ++k) {
      const protocol::Proximity& got = robot->arrivals[k].event;
      EXPECT_EQ(got.event, k);
      EXPECT_EQ(got.a, want[k].a);
      EXPECT_EQ(got.b, want[k].b);
      expect_same_stamp(got.a_stamp, want[k].a_stamp, fmt::format("event {} a", k));
      expect_same_stamp(got.b_stamp, want[k].b_stamp, fmt::format("event {} b", k));
      // Due `lead` before its time on the session clock / rate (not before the start).
      const double due = std::max(0.0, want[k].time / kRate - kLead);
      const double at = std::chrono::duration<double>(robot->arrivals[k].at - start).count();
      EXPECT_GT(at, due - 0.1) << "event " << k;
      EXPECT_LT(at, due + 1.0) << "event " << k;
    }
  }
  const std::string out = output();
  EXPECT_NE(out.find("event 1 at 1.030 s: robot2 after"), std::string::npos) << out;
  EXPECT_NE(out.find("robot1 after (no scan yet)"), std::string::npos) << out;
}

// A robot that is not there costs the others no more than an attempt per event, and the tool fails.
TEST_F(SwarmToolsTest, ProximityWithARobotMissingStillReachesTheOtherAndFails) {
  const fs::path yaml = test::write_tiny_scenario(dir);
  FakeRobot robot1(participant, "robot1");
  const std::size_t tool = run({"proximity", yaml.string(), "--rate", "2", "--wait", "0.5"});
  const auto deadline = Clock::now() + 20s;
  while (robot1.arrivals.size() < 3 && Clock::now() < deadline) robot1.poll(50ms);
  EXPECT_EQ(group.wait(tool, kProcessTimeout), 1) << output();
  ASSERT_EQ(robot1.arrivals.size(), 3u) << output();
  EXPECT_EQ(robot1.arrivals[2].event.event, 2u);
  EXPECT_NE(output().find("error: 3 of 3 events did not reach both robots"), std::string::npos) << output();
  EXPECT_NE(output().find("NOT delivered to robot2"), std::string::npos) << output();
}

TEST_F(SwarmToolsTest, ProximityOfTheSimulatedSwarmFollowsItsSchedule) {
  FakeRobot robot1(participant, "robot1"), robot2(participant, "robot2");
  // At a high rate, without lead: the events of the simulator's first minutes arrive within seconds.
  const std::size_t tool = run({"proximity", "--sim", "1", "--robots", "2", "--rate", "200", "--lead", "0"});
  EXPECT_EQ(group.wait(tool, 60s), 0) << output();
  collect(robot1, robot2, 1, 2s);
  ASSERT_FALSE(robot1.arrivals.empty()) << output();
  ASSERT_EQ(robot1.arrivals.size(), robot2.arrivals.size());
  for (std::size_t k = 0; k < robot1.arrivals.size(); ++k) {
    EXPECT_EQ(robot1.arrivals[k].event.event, k);
    EXPECT_EQ(robot2.arrivals[k].event.event, k);
    EXPECT_FALSE(std::isnan(robot1.arrivals[k].event.a_stamp));  // the simulated robots all start at 0
  }
}

TEST_F(SwarmToolsTest, TriggerSendsOneEventForNowToBothRobots) {
  FakeRobot robot1(participant, "robot1"), robot2(participant, "robot2");
  EXPECT_EQ(group.wait(run({"trigger", "robot1", "robot2", "--event", "77"}), kProcessTimeout), 0) << output();
  const std::size_t second = run({"trigger", "robot2", "robot1"});  // a fresh id
  EXPECT_EQ(group.wait(second, kProcessTimeout), 0) << output();
  collect(robot1, robot2, 2, 5s);
  for (const FakeRobot* robot : {&robot1, &robot2}) {
    ASSERT_EQ(robot->arrivals.size(), 2u) << output();
    const protocol::Proximity& first = robot->arrivals[0].event;
    EXPECT_EQ(first.event, 77u);
    EXPECT_EQ(first.a, "robot1");
    EXPECT_EQ(first.b, "robot2");
    EXPECT_TRUE(std::isnan(first.a_stamp) && std::isnan(first.b_stamp));
    EXPECT_NE(robot->arrivals[1].event.event, 77u);
    EXPECT_EQ(robot->arrivals[1].event.a, "robot2");
  }
  EXPECT_EQ(robot1.arrivals[1].event.event, robot2.arrivals[1].event.event);
  EXPECT_NE(output().find("proximity event 77 sent to robot1 and robot2"), std::string::npos) << output();
}

TEST_F(SwarmToolsTest, TriggerToAnAbsentRobotFailsAndBadNamesAreConfigErrors) {
  FakeRobot robot1(participant, "robot1");
  EXPECT_EQ(group.wait(run({"trigger", "robot1", "nobody", "--wait", "0.5"}), kProcessTimeout), 1) << output();
  EXPECT_NE(output().find("error: nobody not reached within --wait 0.5 s"), std::string::npos) << output();
  EXPECT_EQ(group.wait(run({"trigger", "robot1", "robot1"}), kProcessTimeout), 2);
  EXPECT_EQ(group.wait(run({"trigger", "robot1", "bad name"}), kProcessTimeout), 2);
  EXPECT_EQ(group.wait(run({"proximity", (dir / "missing.yaml").string()}), kProcessTimeout), 1);
  EXPECT_EQ(group.wait(run({"proximity", "--sim", "1", "--rate", "0"}), kProcessTimeout), 2);
  EXPECT_NE(output().find("error: --rate 0 is not > 0"), std::string::npos) << output();
}

// Two agents' heartbeats, as AgentRuntime sends them; robot2 falls silent after `robot2_for`.
class FakeHeartbeats {
 public:
  FakeHeartbeats(net::Participant& p, std::chrono::milliseconds robot2_for) {
    thread_ = std::jthread([this, &p, robot2_for](std::stop_token stop) {
      net::DdsSwarmLink link1(p, link_config("robot1", false)), link2(p, link_config("robot2", false));
      protocol::MessageStamper stamp1("robot1", 11), stamp2("robot2", 22);
      const auto until2 = Clock::now() + robot2_for;
      while (!stop.stop_requested()) {
        link1.send("", protocol::encode(stamp1.stamp("", protocol::Heartbeat{status(12.5, 9.5, 118, 3, 1, 2, 1, 4.0, 5)})));
        if (Clock::now() < until2)
          link2.send("", protocol::encode(stamp2.stamp("", protocol::Heartbeat{status(7.0, 10.0, 70, 0, 0, 0, 0, -1.0, 0)})));
        std::this_thread::sleep_for(100ms);
      }
    });
  }

 private:
  static protocol::AgentStatus status(double uptime, double rate, std::uint64_t processed, std::uint64_t skipped,
                                      std::uint32_t peers, std::uint32_t decided, std::uint32_t accepted,
                                      double merge_age, std::uint64_t refused) {
    protocol::AgentStatus s;
    s.uptime = uptime;
    s.scans_per_second = rate;
    s.scans_received = s.scans_processed = s.map_version = processed;
    s.scans_skipped = skipped;
    s.peers_known = peers;
    s.encounters = decided;
    s.encounters_accepted = accepted;
    s.last_merge_age = merge_age;
    s.messages_rejected = refused;
    return s;
  }
  std::jthread thread_;
};

// The words of the last table line that starts with `name`.
std::vector<std::string> last_row(const std::string& out, const std::string& name) {
  std::vector<std::string> row;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (!w.empty() && w[0] == name) row = w;
  }
  return row;
}

TEST_F(SwarmToolsTest, StatusListsTheAgentsItHearsWithTheirNumbers) {
  const FakeHeartbeats agents(participant, 1h);
  EXPECT_EQ(group.wait(run({"status", "--timeout", "2"}), kProcessTimeout), 0) << output();
  const std::string out = output();
  EXPECT_NE(out.find("2 agent(s) live, 0 gone"), std::string::npos) << out;
  // AGENT STATE HEARD UPTIME SCANS/S PROCESSED SKIPPED PEERS ENCOUNTERS LAST-MERGE MAP REFUSED
  const std::vector<std::string> r1 = last_row(out, "robot1"), r2 = last_row(out, "robot2");
  ASSERT_EQ(r1.size(), 12u) << out;
  ASSERT_EQ(r2.size(), 12u) << out;
  EXPECT_EQ(r1[1], "live");
  EXPECT_EQ((std::vector<std::string>(r1.begin() + 3, r1.end())),
            (std::vector<std::string>{"12.5s", "9.5", "118", "3", "1", "1/2", "4.0s", "118", "5"}));
  EXPECT_EQ((std::vector<std::string>(r2.begin() + 3, r2.end())),
            (std::vector<std::string>{"7.0s", "10.0", "70", "0", "0", "0/0", "-", "70", "0"}));
}

TEST_F(SwarmToolsTest, StatusWatchShowsASilentAgentAsGone) {
  const FakeHeartbeats agents(participant, 1500ms);
  const std::size_t status = run({"status", "--watch", "--timeout", "4.5", "--peer-timeout", "1.5"});
  EXPECT_EQ(group.wait(status, kProcessTimeout), 0) << output();
  const std::string out = output();
  EXPECT_EQ(last_row(out, "robot1").at(1), "live") << out;
  EXPECT_EQ(last_row(out, "robot2").at(1), "gone") << out;
  EXPECT_NE(out.rfind("1 agent(s) live, 1 gone"), std::string::npos) << out;
}

TEST_F(SwarmToolsTest, StatusWithNobodyThereSaysSoAndSucceeds) {
  EXPECT_EQ(group.wait(run({"status", "--timeout", "1"}), kProcessTimeout), 0) << output();
  EXPECT_NE(output().find("no agents heard in swarm"), std::string::npos) << output();
}

}  // namespace
}  // namespace dsswarm
