#pragma once
// A robot's SwarmAgent shared between its threads: the scan loop processes
// scans, the swarm thread answers the encounter engine (protocol::AgentPort),
// and a composer thread builds the merged map off the scan path. One mutex
// guards the agent; nothing slow happens under it except copying the map
// for an encounter view.
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "io/trajectory/tum.hpp"
#include "protocol/encounter_engine.hpp"
#include "swarm/swarm_agent.hpp"

namespace dsswarm::agent {

using SteadyClock = std::chrono::steady_clock;

class SharedAgent : public protocol::AgentPort {
 public:
  SharedAgent(std::unique_ptr<SwarmAgent> agent, const RelativePoseConfig& locate);
  ~SharedAgent() override;

  // Poses of an earlier run of this robot (resumed), kept ahead of the new ones.
  void restore_trajectory(Trajectory earlier);
  // The scan loop. Returns the step; the trajectory keeps every scan's pose.
  SlamStep process(const LaserScan& scan);
  // Before a scan stamped `stamp` (scan loop): installs the newest merged
  // map due by then that the composer has finished (merge_schedule.hpp).
  // +infinity: whatever is finished (the input has ended).
  std::optional<SwarmAgent::Installed> install_due(double stamp);
  // The encounters whose merged map the composer finished since the last
  // call, with when.
  std::vector<std::pair<std::uint64_t, SteadyClock::time_point>> take_composed();
  // Takes the view for encounter (peer, id) now, for a later capture_view.
  void stage_view(const std::string& peer, std::uint64_t encounter);

  // protocol::AgentPort (swarm thread).
  std::optional<protocol::CapturedView> capture_view(const std::string& peer, std::uint64_t encounter) override;
  MapSnapshot snapshot(const protocol::CapturedView& at) override;
  std::vector<LayerVersion> inventory() const override;
  std::optional<Pose2> known_frame(const std::string& origin) const override;
  void merge(MapSnapshot snapshot, const Pose2& sender_in_self, const protocol::CapturedView& at,
             std::uint64_t encounter) override;
  std::uint64_t graph_revision() const override;
  MapMoves map_moves(const std::string& peer, const std::vector<TieScan>& ties,
                     std::size_t max_closures) const override;
  void follow(const std::string& peer, const MapMoves& moves) override;

  // Reads under the lock.
  template <class F>
  auto with_agent(F&& f) const {
    std::lock_guard lock(mutex_);
    return f(*agent_);
  }
  // The same with the trajectory, this run's poses as loop closing last
  // optimized them (a copy: for outputs and checkpoints, not every scan).
  template <class F>
  auto with_trajectory(F&& f) const {
    std::lock_guard lock(mutex_);
    return f(*agent_, optimized_trajectory());
  }
  // Loop closing's last round (at exit): then the outputs reflect every scan.
  void finish();
  bool composing() const;

 private:
  // A view as taken at its scan, with what it takes to bring its map up to
  // the knowledge the robot has when the encounter opens (merges that came
  // in since, from its earlier encounters).
  struct Staged {
    protocol::CapturedView view;       // view.own: the own map at the scan
    std::vector<LayerVersion> layers;  // the foreign layers view.map holds
    bool own_only = false;             // view.map is the own map (loop closure on): nothing to bring up to date
  };
  Staged capture_locked() const;
  protocol::CapturedView up_to_date(Staged staged) const;
  Trajectory optimized_trajectory() const;  // under the lock
  void compose_loop();

  mutable std::mutex mutex_;
  std::unique_ptr<SwarmAgent> agent_;
  RelativePoseConfig locate_;
  Trajectory trajectory_;
  std::map<std::pair<std::string, std::uint64_t>, Staged> staged_;
  std::vector<std::pair<std::uint64_t, SteadyClock::time_point>> composed_;
  bool stop_ = false;
  std::condition_variable wake_composer_;
  std::thread composer_;  // last: starts once everything above exists
};

}  // namespace dsswarm::agent
