#include "agent/agent_runtime.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <fstream>
#include <future>
#include <mutex>
#include <thread>

#include "agent/checkpoint.hpp"
#include "agent/paced_feed.hpp"
#include "agent/paced_feed_test_util.hpp"
#include "agent/agent_runtime_test_util.hpp"
#include "protocol/memory_link.hpp"
#include "protocol/swarm_session.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm::agent {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using namespace runtime_test;

TEST(AgentRuntime, RobotsOnTheirOwnThreadsDecideAsTheInProcessSwarmDoes) {
  const std::vector<EncounterEvent> events{{2.45, 0, 1}, {2.95, 0, 1}};
  SwarmSession session(two_robots(), events, SwarmConfig{});
  session.run();
  ASSERT_EQ(session.encounters().size(), 2u);
  ASSERT_TRUE(session.encounters()[1].accepted) << session.encounters()[1].reason;

  const fs::path out = fresh_dir("live");
  LiveSwarm live(two_robots(), out, 3.0);
  auto proximity_link = live.bus->join("proximity");
  protocol::MessageStamper proximity("proximity", 1);
  // Sent ahead; each names the scan each robot plays last before the event.
  for (const auto& [id, stamp] : {std::pair{0ull, 1002.4}, std::pair{1ull, 1002.9}})
    for (const char* robot : {"a", "b"})
      proximity_link->send(robot, protocol::encode(proximity.stamp(robot, protocol::Proximity{"a", "b", id, stamp, stamp})));
  live.run();

  for (std::size_t i = 0; i < 2; ++i) {
    const AgentReport r = live.runtimes[i]->report();
    ASSERT_EQ(r.outcomes.size(), 2u) << i;
    EXPECT_EQ(r.status.scans_skipped, 0u);
    EXPECT_EQ(r.triggers_late, 0u);
    for (std::size_t k = 0; k < 2; ++k) {
      const EncounterRecord& expected = session.encounters()[k];
      const protocol::EncounterOutcome& o = r.outcomes[k];
      EXPECT_EQ(o.end == protocol::EncounterOutcome::End::accepted, expected.accepted)
          << "robot " << i << " encounter " << k << ": " << static_cast<int>(o.end) << " " << o.reason;
      const Pose2 d = between(expected.estimate.b_frame_in_a, o.estimate.b_frame_in_a);
      EXPECT_LT(std::hypot(d.x, d.y), 0.01);
      EXPECT_LT(std::abs(d.theta), 0.1 * std::numbers::pi / 180.0);
    }
  }
  // Each robot wrote its outputs, and knows the other.
  for (const char* robot : {"a", "b"}) {
    EXPECT_EQ(read_tum(out / robot / "trajectory.tum").size(), 30u);
    EXPECT_TRUE(fs::exists(out / robot / "merged_map.yaml"));
    EXPECT_TRUE(fs::exists(out / robot / "encounters.json"));
  }
  EXPECT_EQ(live.runtimes[0]->agent().with_agent([](const SwarmAgent& a) { return a.knowledge().size(); }), 1u);
}

TEST(AgentRuntime, GarbageAndReplayedMessagesAreCountedAndChangeNothing) {
  const fs::path out = fresh_dir("garbage");
  auto bus = std::make_shared<protocol::MemoryBus>();
  const AgentStream s = two_robots()[0];
  PacedFeed feed(s.scans, s.clock, paced(3.0, 64));
  auto link = bus->join("a");
  AgentOptions o = options_for("a", out);
  o.linger = 0.5;
  AgentRuntime runtime(o, feed, *link);
  auto attacker = bus->join("mallory");
  protocol::MessageStamper mallory("mallory", 7);
  const auto good = protocol::encode(mallory.stamp("a", protocol::Decline{1, "hello"}));
  attacker->send("a", good);
  attacker->send("a", good);  // replayed
  attacker->send("a", std::vector<std::uint8_t>(100, 0xff));
  auto cut = good;
  cut.resize(cut.size() / 2);
  attacker->send("a", cut);
  auto version = protocol::encode(mallory.stamp("a", protocol::Decline{2, "x"}));
  version[4] = 99;
  attacker->send("a", version);
  std::atomic<bool> stop{false};
  runtime.run(stop);
  const AgentReport r = runtime.report();
  EXPECT_EQ(r.rejected_by_reason.at("replayed"), 1u);
  EXPECT_EQ(r.rejected_by_reason.at("malformed"), 3u);
  EXPECT_EQ(r.status.messages_rejected, 4u);
  EXPECT_EQ(r.status.scans_processed, 30u);
  EXPECT_EQ(read_tum(out / "trajectory.tum").size(), 30u);
}


// A peer nobody can reach (no reader of its inbox: gone, or not
// authorized): the encounter ends at once, it does not hold a slot until
// the exchange times out.
TEST(AgentRuntime, AnEncounterWithAPeerThatCannotBeReachedEndsAtOnce) {
  const fs::path out = fresh_dir("unreachable");
  auto bus = std::make_shared<protocol::MemoryBus>();
  const AgentStream s = two_robots()[0];
  PacedFeed feed(s.scans, s.clock, paced(3.0, 64));
  auto link = bus->join("a");
  AgentOptions o = options_for("a", out);
  o.linger = 0.5;
  AgentRuntime runtime(o, feed, *link);
  std::thread ghost_event([&] {
    std::this_thread::sleep_for(300ms);  // after a first scan
    runtime.raise_proximity({"a", "ghost", 5});
  });
  std::atomic<bool> stop{false};
  runtime.run(stop);
  ghost_event.join();
  const AgentReport r = runtime.report();
  ASSERT_EQ(r.outcomes.size(), 1u);
  EXPECT_EQ(r.outcomes[0].end, protocol::EncounterOutcome::End::abandoned);
  EXPECT_NE(r.outcomes[0].reason.find("cannot be reached"), std::string::npos) << r.outcomes[0].reason;
  EXPECT_LT(r.outcomes[0].ended - r.outcomes[0].started, 1.0);
}


// A link whose messages to one robot are held up (a DDS writer waiting for
// that robot's reader) until released: the swarm thread is busy meanwhile.
class SlowLink : public protocol::SwarmLink {
 public:
  SlowLink(std::unique_ptr<protocol::SwarmLink> inner, std::string slow) : inner_(std::move(inner)), slow_(std::move(slow)) {}
  bool send(const std::string& recipient, std::span<const std::uint8_t> bytes) override {
    if (recipient == slow_) {
      std::unique_lock lock(mutex_);
      holding_ = true;
      changed_.notify_all();
      changed_.wait(lock, [&] { return released_; });
    }
    return inner_->send(recipient, bytes);
  }
  bool reachable(const std::string& recipient) override { return inner_->reachable(recipient); }
  std::vector<std::vector<std::uint8_t>> receive(std::chrono::milliseconds timeout) override {
    return inner_->receive(timeout);
  }
  void wake() override { inner_->wake(); }
  void wait_until_holding() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return holding_; });
  }
  void release() {
    std::lock_guard lock(mutex_);
    released_ = true;
    changed_.notify_all();
  }

 private:
  std::unique_ptr<protocol::SwarmLink> inner_;
  std::string slow_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool holding_ = false, released_ = false;
};

TEST(AgentRuntime, AStampedEventIsArmedWhileTheSwarmThreadIsBusy) {
  const fs::path out = fresh_dir("busy");
  auto bus = std::make_shared<protocol::MemoryBus>();
  const AgentStream s = two_robots()[0];
  PacedFeed feed(s.scans, s.clock, paced(1.0, 64));  // 3 s
  SlowLink link(bus->join("a"), "b");
  AgentOptions o = options_for("a", out);
  o.linger = 0.0;
  o.swarm.exchange_timeout = 0.5;
  AgentRuntime runtime(o, feed, link);
  std::atomic<bool> stop{false};
  std::thread robot([&] { runtime.run(stop); });
  // "Now" with b before the first scan: a declines, and its decline to b is held up.
  runtime.raise_proximity({"a", "b", 1, std::nan(""), std::nan("")});
  link.wait_until_holding();
  const double named = s.scans[10].timestamp;  // played at 1 s
  auto raised = std::async(std::launch::async, [&] { runtime.raise_proximity({"a", "c", 2, named, std::nan("")}); });
  const bool at_once = raised.wait_for(500ms) == std::future_status::ready;
  std::this_thread::sleep_for(2s);  // past the scan named
  link.release();
  raised.wait();
  robot.join();
  EXPECT_TRUE(at_once) << "raise_proximity waited for the busy swarm thread";
  const AgentReport r = runtime.report();
  EXPECT_EQ(r.triggers_late, 0u);
  const auto with_c = std::find_if(r.outcomes.begin(), r.outcomes.end(), [](const auto& x) { return x.encounter == 2; });
  ASSERT_NE(with_c, r.outcomes.end());
  EXPECT_DOUBLE_EQ(with_c->self_stamp, named);  // joined right after the scan named, not later
}


}  // namespace
}  // namespace dsswarm::agent
