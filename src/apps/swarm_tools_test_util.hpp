#pragma once
// For the tests of the swarm tools (proximity, trigger, status, replay
// --scenario): the real `dsswarm` process started on loopback in the test's
// own DDS domain and swarm, a tiny CARMEN log and a scenario playing it.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "apps/process_group.hpp"
#include "common/test_files.hpp"
#include "io/logs/carmen_writer.hpp"
#include "net/net_test_util.hpp"

namespace dsswarm::test {

namespace fs = std::filesystem;

inline constexpr double kLogStart = 966647577.25;  // epoch-sized stamps: they cross ROS time bit for bit
inline constexpr double kScanPeriod = 0.1;
inline constexpr int kLogScans = 40;

// Scan i at kLogStart + i · kScanPeriod, ranges and odometry distinct per scan.
inline fs::path write_tiny_log(const fs::path& dir) {
  std::vector<LaserScan> scans;
  for (int i = 0; i < kLogScans; ++i) {
    LaserScan s;
    s.timestamp = kLogStart + kScanPeriod * i;
    s.angle_min = -std::numbers::pi / 2;
    s.angle_increment = std::numbers::pi / 179;
    s.range_max = 80.0;
    for (int b = 0; b < 180; ++b) s.ranges.push_back(b == 9 ? 81.91f : 0.5f + 0.017f * static_cast<float>(b + 3 * i));
    s.odometry = Pose2(0.05 * i, -0.02 * i, 0.01 * i);
    s.laser_offset = Pose2(0.1, 0.0, 0.0);
    scans.push_back(std::move(s));
  }
  const fs::path log = dir / "tiny.log";
  write_carmen(log, scans);
  return log;
}

// robot1 plays [0, 2.5] s of the log forward from session time 0.5; robot2
// plays [1.5 s, end] backward from 0. Encounters at 0.23 (robot1 has not
// started), 1.03 and 2.07 s.
inline fs::path write_tiny_scenario(const fs::path& dir) {
  write_tiny_log(dir);
  return write_text(dir / "tiny.yaml", R"(name: tiny
agents:
  - name: robot1
    log: tiny.log
    to: 2.5
    start: 0.5
  - name: robot2
    log: tiny.log
    from: 1.5
    direction: backward
encounters:
  - agents: [robot1, robot2]
    time: 0.23
  - agents: [robot2, robot1]
    time: 1.03
  - agents: [robot1, robot2]
    time: 2.07
)");
}

inline std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The test's own swarm: a swarm id and domain no other test shares.
inline std::string test_swarm() { return "t" + std::to_string(getpid()); }

inline std::vector<std::string> swarm_net_args() {
  return {"--swarm", test_swarm(), "--swarm-domain", std::to_string(net::test::test_domain()), "--interface", "lo"};
}

// `dsswarm ARGS...` with its output in `log`.
inline std::size_t start_cli(ProcessGroup& group, std::vector<std::string> args, const fs::path& log) {
  args.insert(args.begin(), DSSWARM_CLI);
  return group.start(args, log);
}

}  // namespace dsswarm::test
