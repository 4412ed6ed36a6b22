#pragma once
// What the agent runtime tests share: robots driving through the L-shaped
// office, a fresh output folder, runtime options, and a swarm of runtimes on
// threads over one in-memory bus.
#include <atomic>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "agent/agent_runtime.hpp"
#include "agent/paced_feed.hpp"
#include "agent/paced_feed_test_util.hpp"
#include "protocol/memory_link.hpp"
#include "protocol/swarm_session.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm::agent::runtime_test {

namespace fs = std::filesystem;

// A robot driving a straight line through the L-shaped office at 10 Hz, odometry exact.
inline AgentStream drive(const std::string& name, const Pose2& from, const Pose2& to, int scans, std::uint64_t seed) {
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

inline std::vector<AgentStream> two_robots() {
  return {drive("a", {1.5, 1.5, 0.4}, {3.0, 2.0, 0.1}, 30, 1), drive("b", {8.5, 2.0, -2.5}, {5.0, 2.5, 2.9}, 30, 2)};
}

inline fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(DSSWARM_TEST_TMP) / "agent" / name;
  fs::remove_all(dir);
  return dir;
}

inline AgentOptions options_for(const std::string& name, const fs::path& out) {
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

}  // namespace dsswarm::agent::runtime_test
