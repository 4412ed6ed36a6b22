#pragma once
// Several robots on one clock, in one process: each plays its scans through
// its own SwarmAgent, and when an encounter event comes (a proximity sensor
// or a scenario says two robots are near) the two run the encounter protocol
// — the same engine and the same message bytes as robot processes over DDS —
// through memory, to completion, before the next scan plays.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "protocol/encounter_engine.hpp"
#include "sensor/laser_scan.hpp"
#include "swarm/swarm_agent.hpp"
#include "swarm/swarm_config.hpp"

namespace dsswarm {

// One robot's input: its scans in the order it plays them, each with the
// session-clock time (seconds) at which it is played.
struct AgentStream {
  std::string name;
  std::vector<LaserScan> scans;
  std::vector<double> clock;  // non-decreasing, one per scan
};

struct EncounterEvent {
  double time = 0.0;  // session clock
  std::size_t a = 0;  // indices into the streams
  std::size_t b = 0;
};

// One encounter as both robots saw it. `a` is the protocol's robot A (the
// name that sorts first), whatever the event's order.
struct EncounterRecord {
  std::uint64_t id = 0;
  double time = 0.0;  // session clock
  std::string a, b;
  bool accepted = false;
  std::string reason;
  std::string confirmed_by;   // accepted: "earlier encounter" or "known transform"
  Pose2 b_frame_in_a;         // estimate (meaningful when accepted)
  Pose2 b_pose_in_b, a_pose_in_a;  // the robots' own poses at the encounter
  double a_log_time = 0.0, b_log_time = 0.0;  // timestamps of the scans exchanged
  double match_ms = 0.0;      // both placements (each robot's own time)
  double merge_ms = 0.0;      // both robots' merges (0 when rejected)
  std::size_t bytes = 0;           // every message of the encounter, both ways, as sent
  std::size_t snapshot_bytes = 0;  // of which the snapshot transfers (.dsmap)
  EncounterEstimate estimate;
};

// Builds the record from the two robots' outcomes of one encounter.
EncounterRecord make_record(const protocol::EncounterOutcome& a, const protocol::EncounterOutcome& b, double time);

struct AgentTrack {
  std::vector<double> timestamps;  // log timestamps of the scans played, in play order
  std::vector<SlamStep> steps;
  std::vector<std::size_t> map_versions;  // the own map's version (SwarmAgent::own_version) after each scan
};

class SwarmSession {
 public:
  SwarmSession(std::vector<AgentStream> streams, std::vector<EncounterEvent> events, const SwarmConfig& config);
  ~SwarmSession();

  // Plays everything, then finishes each robot's loop closing (its track gets
  // the optimized poses). `progress(done_scans, total_scans)` is called now and then.
  void run(const std::function<void(std::size_t, std::size_t)>& progress = {});

  std::size_t agents() const { return agents_.size(); }
  const SwarmAgent& agent(std::size_t i) const { return *agents_[i]; }
  const AgentTrack& track(std::size_t i) const { return tracks_[i]; }
  const std::vector<EncounterRecord>& encounters() const { return records_; }
  // Events that did not become encounters, and why (one line each, alike
  // events alike: "robot2 had not started").
  std::size_t events_skipped() const { return skipped_.size(); }
  const std::vector<std::string>& skipped() const { return skipped_; }
  const SwarmConfig& config() const { return config_; }
  // Moved messages (protocol/followers.hpp) all robots sent, and their bytes.
  std::size_t moved_messages() const { return moved_messages_; }
  std::size_t moved_bytes() const { return moved_bytes_; }

 private:
  struct Robot;
  void encounter(const EncounterEvent& e, std::uint64_t id);
  void pump(double now);
  void final_exchanges(double end);

  std::vector<AgentStream> streams_;
  std::vector<EncounterEvent> events_;
  SwarmConfig config_;
  std::vector<std::unique_ptr<SwarmAgent>> agents_;
  std::vector<std::unique_ptr<Robot>> robots_;  // protocol side of each agent
  std::vector<AgentTrack> tracks_;
  std::vector<EncounterRecord> records_;
  std::vector<std::string> skipped_;
  std::size_t moved_messages_ = 0, moved_bytes_ = 0;
};

}  // namespace dsswarm
