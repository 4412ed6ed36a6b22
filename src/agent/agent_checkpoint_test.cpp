// A robot's checkpoint: resuming from it (after a crash, on a live feed or
// the whole run again), a fresh start that keeps it aside, one torn by a kill.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "agent/agent_runtime.hpp"
#include "agent/agent_runtime_test_util.hpp"
#include "agent/checkpoint.hpp"
#include "protocol/memory_link.hpp"

namespace dsswarm::agent {
namespace {

namespace fs = std::filesystem;
using namespace runtime_test;

// Runs robot "a" alone over the first `n` scans of `s` (all when n is 0),
// paced 5x, into `out` until its feed ends; its report.
AgentReport run_a(protocol::MemoryBus& bus, const fs::path& out, const AgentStream& s, std::size_t n, bool resume) {
  const auto end = static_cast<long>(n == 0 ? s.scans.size() : n);
  PacedFeed feed({s.scans.begin(), s.scans.begin() + end}, {s.clock.begin(), s.clock.begin() + end}, paced(5.0, 64));
  auto link = bus.join("a");
  AgentOptions o = options_for("a", out);
  o.linger = 0.0;
  o.resume = resume;
  AgentRuntime runtime(o, feed, *link);
  std::atomic<bool> stop{false};
  runtime.run(stop);
  return runtime.report();
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
    run_a(*bus, out, first, 0, false);
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
  const AgentReport resumed = run_a(*bus, out, second, 0, true);
  const Trajectory t = read_tum(out / "trajectory.tum");
  ASSERT_EQ(t.size(), 30u);  // the first run's poses, then the second's
  EXPECT_DOUBLE_EQ(t[15].timestamp, s.scans[15].timestamp);
  // It went on in its saved map: the pose stays on the straight drive (the
  // map frame is the start turned to the walls: the first pose).
  const Pose2 truth =
      t.front().pose * Pose2{1.5, 1.5, 0.4}.inverse() * interpolate({1.5, 1.5, 0.4}, {3.0, 2.0, 0.1}, 29.0 / 29.0);
  EXPECT_NEAR(t.back().pose.x, truth.x, 0.05);
  EXPECT_NEAR(t.back().pose.y, truth.y, 0.05);
  EXPECT_GT(read_checkpoint(out, "a").snapshot.layers.at(0).version, version_before);
  EXPECT_EQ(resumed.status.scans_processed, 30u);
}

// A log or simulated run restarted from its start after a crash (`agent
// --sim/--log --resume`): the scans the checkpoint holds are passed over,
// the trajectory goes on in time order.
TEST(AgentRuntime, ResumedOnTheWholeRunAgainMapsOnlyWhatTheCheckpointLacks) {
  const fs::path out = fresh_dir("resume_whole");
  auto bus = std::make_shared<protocol::MemoryBus>();
  const AgentStream s = two_robots()[0];
  run_a(*bus, out, s, 15, false);
  const AgentReport r = run_a(*bus, out, s, 0, true);
  const Trajectory t = read_tum(out / "trajectory.tum");
  ASSERT_EQ(t.size(), 30u);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_DOUBLE_EQ(t[i].timestamp, s.scans[i].timestamp) << i;
  EXPECT_EQ(r.scans_in_checkpoint, 15u);
  EXPECT_EQ(r.status.scans_processed, 30u);
}

// Started again without --resume: the earlier run's checkpoint is not
// overwritten, it moves to previous/ (and --resume from there still works).
TEST(AgentRuntime, AFreshStartKeepsTheEarlierCheckpointAside) {
  const fs::path out = fresh_dir("fresh_again");
  auto bus = std::make_shared<protocol::MemoryBus>();
  const AgentStream s = two_robots()[0];
  run_a(*bus, out, s, 20, false);
  run_a(*bus, out, s, 5, false);
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
