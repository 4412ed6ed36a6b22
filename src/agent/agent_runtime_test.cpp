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
#include "protocol/memory_link.hpp"
#include "protocol/swarm_session.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm::agent {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// A robot driving a straight line through the L-shaped office at 10 Hz, odometry exact.
AgentStream drive(const std::string& name, const Pose2& from, const Pose2& to, int scans, std::uint64_t seed) {
  const World world = test::l_shaped_office();
  Rng rng(seed);
  AgentStream s{name, {}, {}};
  for (int k = 0; k < scans; ++k) {
    const Pose2 p = interpolate(from, to, static_cast<double>(k) / (scans - 1));
    LaserScan scan = simulate_scan(world, p, test::full_circle_lidar(), rng);
    scan.timestamp = 1000.0 + 0.1 * k;
    scan.odometry = from.inverse() * p;
    s.scans.push_back(std::move(scan));
    s.clock.push_back(0.1 * k);
  }
  return s;
}

std::vector<AgentStream> two_robots() {
  return {drive("a", {1.5, 1.5, 0.4}, {3.0, 2.0, 0.1}, 30, 1), drive("b", {8.5, 2.0, -2.5}, {5.0, 2.5, 2.9}, 30, 2)};
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(DSSWARM_TEST_TMP) / "agent" / name;
  fs::remove_all(dir);
  return dir;
}

AgentOptions options_for(const std::string& name, const fs::path& out) {
  AgentOptions o;
  o.name = name;
  o.out = out;
  o.linger = 3.0;
  o.heartbeat_period = 0.2;
  o.peer_timeout = 2.0;
  o.checkpoint_period = 0.0;
  return o;
}

// Runs each robot in its own runtime (threads, as separate processes would)
// over one bus, with proximity events sent ahead naming each robot's scan.
struct LiveSwarm {
  std::shared_ptr<protocol::MemoryBus> bus = std::make_shared<protocol::MemoryBus>();
  std::vector<std::unique_ptr<PacedFeed>> feeds;
  std::vector<std::unique_ptr<protocol::SwarmLink>> links;
  std::vector<std::unique_ptr<AgentRuntime>> runtimes;

  LiveSwarm(const std::vector<AgentStream>& streams, const fs::path& out, double rate) {
    for (const AgentStream& s : streams) {
      links.push_back(bus->join(s.name));
      runtimes.push_back(std::make_unique<AgentRuntime>(options_for(s.name, out / s.name), *feed_of(s, rate),
                                                        *links.back()));
    }
  }
  PacedFeed* feed_of(const AgentStream& s, double rate) {
    feeds.push_back(std::make_unique<PacedFeed>(s.scans, s.clock, paced(rate, 64)));
    return feeds.back().get();
  }
  void run() {
    std::atomic<bool> stop{false};
    std::vector<std::thread> threads;
    for (auto& r : runtimes) threads.emplace_back([&, rt = r.get()] { rt->run(stop); });
    for (auto& t : threads) t.join();
  }
};

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

TEST(AgentRuntime, ResumesFromItsCheckpointWithNothingLost) {
  const fs::path out = fresh_dir("resume");
  auto bus = std::make_shared<protocol::MemoryBus>();
  AgentStream s = two_robots()[0];
  AgentStream first{s.name, {s.scans.begin(), s.scans.begin() + 15}, {s.clock.begin(), s.clock.begin() + 15}};
  AgentStream second{s.name, {s.scans.begin() + 15, s.scans.end()}, {}};
  for (std::size_t i = 0; i < second.scans.size(); ++i) second.clock.push_back(0.1 * static_cast<double>(i));
  std::size_t version_before = 0;
  {
    PacedFeed feed(first.scans, first.clock, paced(5.0, 64));
    auto link = bus->join("a");
    AgentOptions o = options_for("a", out);
    o.linger = 0.0;
    AgentRuntime runtime(o, feed, *link);
    std::atomic<bool> stop{false};
    runtime.run(stop);
    const Checkpoint k = read_checkpoint(out, "a");
    version_before = k.snapshot.layers.at(0).version;
    // The odometry reading at the saved pose, for the resumed robot's first prediction.
    const auto at_stamp = std::find_if(first.scans.begin(), first.scans.end(),
                                       [&](const LaserScan& scan) { return scan.timestamp == k.stamp; });
    ASSERT_NE(at_stamp, first.scans.end());
    ASSERT_TRUE(at_stamp->odometry && k.odometry);
    EXPECT_DOUBLE_EQ(k.odometry->x, at_stamp->odometry->x);
    EXPECT_DOUBLE_EQ(k.odometry->theta, at_stamp->odometry->theta);
  }
  ASSERT_GT(version_before, 0u);
  PacedFeed feed(second.scans, second.clock, paced(5.0, 64));
  auto link = bus->join("a");
  AgentOptions o = options_for("a", out);
  o.linger = 0.0;
  o.resume = true;
  AgentRuntime runtime(o, feed, *link);
  std::atomic<bool> stop{false};
  runtime.run(stop);
  const Trajectory t = read_tum(out / "trajectory.tum");
  ASSERT_EQ(t.size(), 30u);  // the first run's poses, then the second's
  EXPECT_DOUBLE_EQ(t[15].timestamp, s.scans[15].timestamp);
  // It went on in its saved map: the pose stays on the straight drive.
  const Pose2 truth = Pose2{1.5, 1.5, 0.4}.inverse() * interpolate({1.5, 1.5, 0.4}, {3.0, 2.0, 0.1}, 29.0 / 29.0);
  EXPECT_NEAR(t.back().pose.x, truth.x, 0.05);
  EXPECT_NEAR(t.back().pose.y, truth.y, 0.05);
  EXPECT_GT(read_checkpoint(out, "a").snapshot.layers.at(0).version, version_before);
  EXPECT_EQ(runtime.report().status.scans_processed, 30u);
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

// A log or simulated run restarted from its start after a crash (`agent
// --sim/--log --resume`): the scans the checkpoint holds are passed over,
// the trajectory goes on in time order.
TEST(AgentRuntime, ResumedOnTheWholeRunAgainMapsOnlyWhatTheCheckpointLacks) {
  const fs::path out = fresh_dir("resume_whole");
  auto bus = std::make_shared<protocol::MemoryBus>();
  const AgentStream s = two_robots()[0];
  {
    PacedFeed feed({s.scans.begin(), s.scans.begin() + 15}, {s.clock.begin(), s.clock.begin() + 15}, paced(5.0, 64));
    auto link = bus->join("a");
    AgentOptions o = options_for("a", out);
    o.linger = 0.0;
    AgentRuntime runtime(o, feed, *link);
    std::atomic<bool> stop{false};
    runtime.run(stop);
  }
  PacedFeed feed(s.scans, s.clock, paced(5.0, 64));
  auto link = bus->join("a");
  AgentOptions o = options_for("a", out);
  o.linger = 0.0;
  o.resume = true;
  AgentRuntime runtime(o, feed, *link);
  std::atomic<bool> stop{false};
  runtime.run(stop);
  const Trajectory t = read_tum(out / "trajectory.tum");
  ASSERT_EQ(t.size(), 30u);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_DOUBLE_EQ(t[i].timestamp, s.scans[i].timestamp) << i;
  const AgentReport r = runtime.report();
  EXPECT_EQ(r.scans_in_checkpoint, 15u);
  EXPECT_EQ(r.status.scans_processed, 30u);
}

// Started again without --resume: the earlier run's checkpoint is not
// overwritten, it moves to previous/ (and --resume from there still works).
TEST(AgentRuntime, AFreshStartKeepsTheEarlierCheckpointAside) {
  const fs::path out = fresh_dir("fresh_again");
  auto bus = std::make_shared<protocol::MemoryBus>();
  const AgentStream s = two_robots()[0];
  auto run_once = [&](std::size_t scans) {
    PacedFeed feed({s.scans.begin(), s.scans.begin() + static_cast<long>(scans)},
                   {s.clock.begin(), s.clock.begin() + static_cast<long>(scans)}, paced(5.0, 64));
    auto link = bus->join("a");
    AgentOptions o = options_for("a", out);
    o.linger = 0.0;
    AgentRuntime runtime(o, feed, *link);
    std::atomic<bool> stop{false};
    runtime.run(stop);
  };
  run_once(20);
  run_once(5);
  EXPECT_EQ(read_checkpoint(out, "a").trajectory.size(), 5u);
  const Checkpoint earlier = read_checkpoint(out / "previous", "a");
  EXPECT_EQ(earlier.scans_processed, 20u);
  EXPECT_EQ(earlier.trajectory.size(), 20u);
}

// Killed while writing a checkpoint, after the poses but before
// checkpoint.json: the resumed robot goes on from the newer poses, not from
// the older state file's pose and count.
TEST(AgentRuntime, ACheckpointTornByAKillResumesFromItsNewestPoses) {
  const fs::path out = fresh_dir("torn");
  Checkpoint c;
  c.name = "a";
  c.snapshot.sender = "a";
  MapLayer own;
  own.origin = "a";
  own.version = 1;
  Rng rng(1);
  own.map = std::make_shared<MultiResMap>(test::map_from(test::l_shaped_office(), {{2.0, 2.0, 0.0}}, {2.0, 2.0, 0.0}, rng));
  c.snapshot.layers.push_back(own);
  for (int i = 0; i < 10; ++i) c.trajectory.push_back({100.0 + i, {0.1 * i, 0.0, 0.0}});
  c.pose = c.trajectory.back().pose;
  c.stamp = c.trajectory.back().timestamp;
  c.scans_processed = 10;
  c.odometry = Pose2{5.0, 6.0, 0.5};
  write_checkpoint(out, c);
  EXPECT_NEAR(read_checkpoint(out, "a").odometry.value_or(Pose2{}).y, 6.0, 1e-12);
  const std::string older_state = [&] {
    std::ifstream in(out / "checkpoint.json");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  for (int i = 10; i < 14; ++i) c.trajectory.push_back({100.0 + i, {0.1 * i, 0.0, 0.0}});
  c.pose = c.trajectory.back().pose;
  c.scans_processed = 14;
  write_checkpoint(out, c);
  std::ofstream(out / "checkpoint.json") << older_state;  // the kill came before the state file
  const Checkpoint r = read_checkpoint(out, "a");
  EXPECT_EQ(r.scans_processed, 14u);
  EXPECT_DOUBLE_EQ(r.stamp, 113.0);
  EXPECT_NEAR(r.pose.x, 1.3, 1e-9);
  EXPECT_FALSE(r.odometry) << "the state file's odometry reading belongs to its older pose";
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

TEST(AgentRuntime, ResumingWithoutACheckpointIsAClearError) {
  const fs::path out = fresh_dir("no_checkpoint");
  auto bus = std::make_shared<protocol::MemoryBus>();
  PacedFeed feed({}, {}, {});
  auto link = bus->join("a");
  AgentOptions o = options_for("a", out);
  o.resume = true;
  try {
    AgentRuntime runtime(o, feed, *link);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no checkpoint"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dsswarm::agent
