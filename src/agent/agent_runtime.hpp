#pragma once
// One robot as its own program (`dsswarm agent`): SLAM on scans as they
// arrive, the encounter protocol with whichever peers a proximity event
// names, the merged map composed off the scan path, live outputs, periodic
// checkpoints. Where the scans come from (ScanFeed), how bytes reach the
// peers (protocol::SwarmLink) and where the live map goes (RobotOutputs) are
// the caller's: DDS in a robot process, memory in tests.
//
// Threads: the caller's (scan loop: process, install merged maps, fire
// stamped triggers, publish, checkpoint), a swarm thread (messages, the
// encounter engine, heartbeats, time-outs) and SharedAgent's composer.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "agent/scan_feed.hpp"
#include "agent/live_map_output.hpp"
#include "agent/robot_outputs.hpp"
#include "agent/send_queue.hpp"
#include "agent/shared_agent.hpp"
#include "agent/triggers.hpp"
#include "common/warning_throttle.hpp"
#include "grid/grid_raster.hpp"
#include "protocol/gate.hpp"
#include "protocol/link.hpp"
#include "runtime/worker_thread.hpp"

namespace dsswarm::agent {

struct AgentOptions {
  std::string name;
  SwarmConfig swarm;                 // the swarm's settings (this robot's seed derives from its name)
  std::filesystem::path out;         // outputs and checkpoints
  double heartbeat_period = 1.0;     // s
  double peer_timeout = 6.0;         // s without a heartbeat: the peer is gone, its encounters dropped
  double checkpoint_period = 30.0;   // s (0: only at exit)
  double trigger_patience = 10.0;    // s a stamped proximity event waits for its scan
  double linger = 0.0;               // s to go on answering peers once the feed has run out
  bool resume = false;               // continue from the checkpoint in `out`
  // Recorded input played × rate: the swarm's clocks (re-merge interval,
  // exchange time-out) run on the play clock, so a run at rate X decides as
  // the in-process swarm does at its own session clock. 1 for live robots.
  double time_scale = 1.0;
  std::uint64_t incarnation = 0;     // 0: the start time (ns); tests pin it
  protocol::WireLimits limits;
};

// What stats.json and `dsswarm status` report.
struct AgentReport {
  protocol::AgentStatus status;
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;  // the whole process, every thread
  double largest_gap_ms = 0.0;                 // between two processed scans, any time
  double largest_gap_during_encounter_ms = 0.0;
  std::vector<double> merge_latencies_ms;      // proximity event → merged map in use
  std::vector<double> merge_ready_ms;          // proximity event → merged map composed
  std::uint64_t merges_late = 0;               // not ready by their scan (swarm.merge_delay)
  std::map<std::string, std::uint64_t> rejected_by_reason;
  std::uint64_t triggers_late = 0;
  std::uint64_t scans_in_checkpoint = 0;  // resumed: scans received again that the checkpoint holds
  std::uint64_t moved_received = 0, moved_bytes_received = 0;  // peers' word that their maps moved
  std::uint64_t messages_deferred = 0;  // to a peer whose inbox was full: sent later, in order
  std::vector<protocol::EncounterOutcome> outcomes;
};

class AgentRuntime {
 public:
  AgentRuntime(AgentOptions options, ScanFeed& feed, protocol::SwarmLink& link, RobotOutputs* outputs = nullptr);
  ~AgentRuntime();
  AgentRuntime(const AgentRuntime&) = delete;
  AgentRuntime& operator=(const AgentRuntime&) = delete;

  // Runs until `stop` is set, or the feed is exhausted and `linger` has
  // passed; then writes the outputs and a last checkpoint.
  void run(const std::atomic<bool>& stop);
  AgentReport report() const;
  const SharedAgent& agent() const { return *shared_; }
  // A proximity sensor on this robot says a peer is near (as a received
  // Proximity message would); from any thread.
  void raise_proximity(const protocol::Proximity& event);

 private:
  void swarm_loop();
  void install_due(double stamp);
  void heartbeat_loop();
  protocol::AgentStatus status(double now) const;
  void handle(const protocol::Message& m, std::size_t bytes, double now);
  void on_proximity(const protocol::Proximity& p, double now);
  // Arms a stamped event's trigger; false when the event means "now" for this robot.
  bool arm_unless_now(const protocol::Proximity& p);
  void start_encounter(const std::string& peer, std::uint64_t id, double now);
  void after_scan(const LaserScan& scan, const SlamStep& step);
  void fire(std::vector<Trigger> due);
  void flush_engine();
  void drop_silent_peers(double now);
  void checkpoint(bool wait);  // wait: until written (at exit)
  void write_outputs();
  double now() const;        // s of wall time since start
  double swarm_now() const;  // the same on the play clock (× time_scale)

  AgentOptions options_;
  ScanFeed& feed_;
  protocol::SwarmLink& link_;
  RobotOutputs* outputs_;
  SteadyClock::time_point started_;
  WorkerThread loop_closing_;  // the robot's loop-closing rounds, off the scan path (outlives shared_)
  std::unique_ptr<SharedAgent> shared_;
  std::unique_ptr<LiveMapOutput> live_map_;  // /map, when there are outputs (before shared_ goes)
  std::uint64_t scans_before_ = 0;  // processed in earlier runs (resumed)
  std::optional<double> resumed_at_;  // stamp of the checkpoint's last pose (resumed)

  // Swarm thread state (engine_mutex_).
  mutable std::mutex engine_mutex_;
  std::unique_ptr<protocol::EncounterEngine> engine_;
  protocol::MessageGate gate_;
  struct Peer {
    protocol::AgentStatus status;
    double last_heard = 0.0;
    bool lost = false;
  };
  std::map<std::string, Peer> peers_;
  std::map<std::pair<std::string, std::uint64_t>, std::vector<std::pair<protocol::Message, std::size_t>>> held_;
  SendQueue sends_{options_.swarm.exchange_timeout};  // a busy peer's messages wait; after that long it is dropped
  std::map<std::uint64_t, double> event_time_;  // encounter → when its proximity event took effect
  std::vector<protocol::EncounterOutcome> outcomes_;
  WarningThrottle warnings_{"swarm messages", std::chrono::seconds(5)};

  // Scan loop → swarm thread (trigger_mutex_).
  std::vector<Trigger> fired_;
  std::uint64_t triggers_late_ = 0;

  // Scan loop state.
  mutable std::mutex trigger_mutex_;
  TriggerBook triggers_;
  mutable std::mutex report_mutex_;
  AgentReport report_;
  // Read by the heartbeat thread: a robot busy placing a peer still says it is alive.
  std::atomic<std::size_t> open_encounters_{0};
  std::atomic<std::uint32_t> decided_{0}, accepted_{0};
  std::atomic<std::uint64_t> messages_rejected_{0};
  std::uint64_t moved_received_ = 0, moved_bytes_received_ = 0;  // under engine_mutex_
  std::atomic<double> last_merge_{-1.0};  // s since start, -1: never
  std::atomic<double> rate_{0.0};         // scans processed per second over the last heartbeat period
  protocol::MessageStamper heartbeats_;
  std::atomic<bool> stop_swarm_{false};
  std::optional<SteadyClock::time_point> last_scan_at_;
  double last_checkpoint_ = 0.0;
  std::atomic<std::uint64_t> processed_{0};
  std::atomic<std::uint64_t> scans_in_checkpoint_{0};
  std::thread swarm_thread_;
  std::thread heartbeat_thread_;
  std::thread checkpoint_writer_;
  std::atomic<bool> checkpoint_written_{true};
};

}  // namespace dsswarm::agent
