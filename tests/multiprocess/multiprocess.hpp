#pragma once
// What the multi-process tests share: a scratch directory per test (removed
// when the test ends), `dsswarm` child processes started and stopped through
// a ProcessGroup (every one of them killed and reaped when the test ends,
// whatever happened), DDS domains of the test's own, and readers of what a
// robot process leaves behind.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/process_group.hpp"
#include "io/trajectory/tum.hpp"
#include "net/swarm_link.hpp"
#include "protocol/gate.hpp"

namespace dsswarm::mp {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// The running test's own DDS domains: `k` = 0, 1, ... for a second swarm or
// the ROS 2 side (ctest -j runs the tests side by side).
int test_domain(int k = 0);

// A test's processes and files. The destructor stops every process still
// running (SIGTERM, then SIGKILL) and removes the directory.
class Rig {
 public:
  Rig();
  ~Rig();
  Rig(const Rig&) = delete;
  Rig& operator=(const Rig&) = delete;

  const fs::path& dir() const { return dir_; }
  // Starts `dsswarm args...`, its output in dir()/logs/<log>.log.
  std::size_t start(const std::string& log, const std::vector<std::string>& args);
  // Starts `argv` as it is (argv[0] a path), e.g. `ip netns exec NS dsswarm ...`.
  std::size_t start_raw(const std::string& log, const std::vector<std::string>& argv);
  ProcessGroup& group() { return group_; }
  // The exit status, or a test failure (with the log's tail) after `timeout`.
  int wait(std::size_t process, std::chrono::milliseconds timeout);
  // The last lines of a process's log, for failure messages.
  std::string log_tail(const std::string& log, std::size_t lines = 30) const;
  // Every log's tail: printed when the test fails.
  std::string all_logs() const;

 private:
  fs::path dir_;
  ProcessGroup group_;
  std::vector<std::string> logs_;
};

// `agent` options of one simulated robot of seed 1's swarm on loopback,
// unsecured on `domain` unless `keys` is given, no ROS 2 outputs.
struct SimAgent {
  std::string name;
  int robot = 1, robots = 3;
  double rate = 8.0;
  double start_at = 0.0;  // unix time of clock 0
  int domain = 0;
  std::string interface = "lo";
  fs::path out;
  fs::path keys;                // secured swarm: the keys directory
  std::vector<std::string> extra;
};
std::vector<std::string> agent_args(const SimAgent& a);

// Unix time `seconds` from now (the robots' common clock 0).
double unix_in(double seconds);

// A plain DDS participant of the test on the swarm topics of a partition
// (net::swarm_partition(id); "" for a secured swarm's domain), loopback,
// unsecured: `name`'s inbox and the heartbeats, as a robot would hear them
// (DDS hands every matched reader its own copy), and sends to any robot.
struct SwarmTap {
  SwarmTap(int domain, const std::string& partition, const std::string& name);
  net::Participant participant;
  net::DdsSwarmLink link;
};
// Malformed, truncated, oversized, wrong-version, non-finite, corrupt,
// misdirected and replayed messages for `victim` (and one valid one), each
// with the reason its gate files it under ("" for the valid one). Sequences
// continue `sender`'s: call again for another round.
std::vector<std::pair<std::string, std::vector<std::uint8_t>>> bad_messages(protocol::MessageStamper& sender,
                                                                            const std::string& victim);

// Waits until a heartbeat from `robot` arrives on `tap`.
bool wait_for_heartbeat(SwarmTap& tap, const std::string& robot, std::chrono::milliseconds timeout);

nlohmann::json read_json(const fs::path& path);
// Names of the origins of the layers a robot's stats.json says it holds.
std::vector<std::string> known_origins(const nlohmann::json& stats);
// The outcomes in a robot's encounters.json, by encounter id.
std::map<std::uint64_t, nlohmann::json> outcomes_by_id(const fs::path& encounters_json);
// Whether a robot's stats.json says it holds `origin`'s map.
bool holds(const nlohmann::json& stats, const std::string& origin);
// Encounters that both robots (their output folders) ended as accepted.
std::size_t accepted_by_both(const fs::path& a, const fs::path& b);

// Polls `done` every 50 ms for up to `timeout`.
bool wait_until(const std::function<bool()>& done, std::chrono::milliseconds timeout);

// A robot's outputs are complete: maps, checkpoint, encounters.json and
// stats.json readable, a pose in time order for every scan processed, and
// each of the run's `scans` processed or counted as skipped.
void expect_complete_outputs(const fs::path& dir, std::size_t scans);

}  // namespace dsswarm::mp
