#pragma once
// Proximity events played on time (`dsswarm proximity`, and `agent --sim`,
// whose simulated proximity sensor raises them): each is handed to `raise`
// `lead` seconds before its time on the session clock (× 1/rate), early
// enough for a robot to arm it before the scan it names. Events whose time
// had passed by more than `lead` when the player started are not raised:
// they are over (a robot restarted in the middle of a run would otherwise
// open every encounter of the run's past at once).
#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <thread>
#include <vector>

#include "protocol/messages.hpp"
#include "protocol/swarm_session.hpp"

namespace dsswarm::agent {

struct TimedProximity {
  double time = 0.0;  // session clock, s
  protocol::Proximity event;
};

// The events of a recorded or simulated swarm as robot processes get them:
// each names, per robot, the stamp of the last scan it has played at the
// event's time, so a robot process joins right after that scan — exactly
// where the in-process swarm (SwarmSession) runs it; ids are the events'
// order, as the session numbers them. A robot that has played nothing by
// then gets a NaN stamp (it declines: no scan yet).
std::vector<TimedProximity> proximity_schedule(const std::vector<AgentStream>& streams,
                                               std::vector<EncounterEvent> events);

class ProximityPlayer {
 public:
  using Raise = std::function<void(const protocol::Proximity&)>;
  ProximityPlayer(std::vector<TimedProximity> events, double rate, double lead,
                  std::optional<std::chrono::system_clock::time_point> start_at, Raise raise);
  ~ProximityPlayer();  // stops early if need be
  bool done() const { return done_.load(); }
  std::size_t skipped() const { return skipped_.load(); }  // events over before the start
  void wait();         // until every event is raised

 private:
  std::atomic<bool> stop_{false}, done_{false};
  std::atomic<std::size_t> skipped_{0};
  std::thread thread_;
};

}  // namespace dsswarm::agent
