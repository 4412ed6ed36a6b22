#pragma once
// Several robots on one clock: each plays its scans through its own
// SwarmAgent, and when an encounter event comes (a proximity sensor or a
// scenario says two robots are near) the two exchange snapshots and scans,
// estimate the transform between their frames, and merge if it verifies.
//
// This is the offline stand-in for what the robots do on their own over the
// network: the session only orders events in time. The exchange itself goes
// through `transport`, so a caller can serialize snapshots exactly as they
// would go over the wire (and count the bytes) without the core doing I/O.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sensor/laser_scan.hpp"
#include "swarm/swarm_agent.hpp"

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

struct EncounterRecord {
  double time = 0.0;  // session clock
  std::string a, b;
  bool accepted = false;
  std::string reason;
  std::string confirmed_by;   // accepted: "earlier encounter" or "known transform" ("" when not confirming)
  Pose2 b_frame_in_a;         // estimate (meaningful when accepted)
  Pose2 b_pose_in_b, a_pose_in_a;  // the robots' own poses at the encounter
  double a_log_time = 0.0, b_log_time = 0.0;  // timestamps of the scans exchanged
  double match_ms = 0.0;      // both placements and the verification
  double merge_ms = 0.0;      // both robots' merges (0 when rejected)
  std::size_t bytes = 0;      // both snapshots + both scans as sent
  EncounterEstimate estimate;
};

// What crosses the network: the transport returns the snapshot as the other
// side receives it, and adds to `bytes` what it cost. The default passes the
// snapshot through in memory and counts nothing.
using SnapshotTransport = std::function<MapSnapshot(const MapSnapshot&, std::size_t& bytes)>;

struct SwarmConfig {
  SlamConfig slam;
  EncounterConfig encounter;
  // Robots that met with an accepted merge skip further encounters for this
  // long (their maps have not changed much); rejected ones retry at once.
  double remerge_interval = 10.0;  // s of session clock
  // false: encounters are ignored and every robot maps alone (the baseline
  // merging is measured against).
  bool merge = true;
  // A verified transform is merged on only once a second, independent
  // estimate of the same transform agrees with it: an earlier encounter of
  // the pair, or the transform already known (directly or through a third
  // robot). Two robots facing each other in a symmetric corridor can agree on
  // a wrong placement, both ways, at one moment; they almost never do twice,
  // from other places. Agreement is measured at robot B's position.
  bool confirm = true;
  double confirm_xy = 0.25;      // m
  double confirm_theta = 0.035;  // rad (2°)

  void validate() const;
};

struct AgentTrack {
  std::vector<double> timestamps;  // log timestamps of the scans played, in play order
  std::vector<SlamStep> steps;
};

class SwarmSession {
 public:
  SwarmSession(std::vector<AgentStream> streams, std::vector<EncounterEvent> events, const SwarmConfig& config,
               SnapshotTransport transport = {});

  // Plays everything. `progress(done_scans, total_scans)` is called now and then.
  void run(const std::function<void(std::size_t, std::size_t)>& progress = {});

  std::size_t agents() const { return agents_.size(); }
  const SwarmAgent& agent(std::size_t i) const { return *agents_[i]; }
  const AgentTrack& track(std::size_t i) const { return tracks_[i]; }
  const std::vector<EncounterRecord>& encounters() const { return records_; }
  std::size_t events_skipped() const { return skipped_; }
  const SwarmConfig& config() const { return config_; }

 private:
  void encounter(const EncounterEvent& e);

  std::vector<AgentStream> streams_;
  std::vector<EncounterEvent> events_;
  SwarmConfig config_;
  SnapshotTransport transport_;
  std::vector<std::unique_ptr<SwarmAgent>> agents_;
  std::vector<AgentTrack> tracks_;
  std::vector<EncounterRecord> records_;
  std::vector<std::vector<double>> last_merge_;  // [a][b] session time of the last accepted merge
  // [a][b] (a < b): verified transforms (b's frame in a's) awaiting confirmation.
  std::vector<std::vector<std::vector<Pose2>>> unconfirmed_;
  std::size_t skipped_ = 0;
};

}  // namespace dsswarm
