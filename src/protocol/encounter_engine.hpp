#pragma once
// One robot's side of every encounter it takes part in (messages.hpp has
// the exchange step by step). The engine is synchronous and clock-free: the
// caller hands it messages and the time, and sends what it puts in its
// outbox. In `dsswarm swarm` / `demo` a session pumps several engines through
// memory; in `dsswarm agent` a thread feeds one from DDS. Everything a robot
// keeps per peer (re-merge timer, transforms awaiting confirmation) lives
// here, and every random seed derives from the pair and the encounter id,
// so two processes compute exactly what one process would.
// A robot runs its encounters in id order (the order of the events): one
// that comes while an earlier one is still open waits for it to end, so it
// starts from the map and knowledge that earlier merge left, as it would in
// one process where every encounter ends before the next begins.
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "protocol/confirmation.hpp"
#include "protocol/followers.hpp"
#include "protocol/gate.hpp"
#include "protocol/messages.hpp"
#include "protocol/repeats.hpp"
#include "protocol/transfer.hpp"
#include "swarm/encounter.hpp"
#include "swarm/map_snapshot.hpp"
#include "swarm/swarm_config.hpp"

namespace dsswarm::protocol {

// A robot's state for one encounter, taken when it joins.
struct CapturedView {
  EncounterView view;  // view.map stays valid while keep_alive lives
  double stamp = 0.0;  // log time of the scan in view
  std::shared_ptr<const void> keep_alive;
  // The own map as at that scan and its version, when the robot goes on
  // mapping meanwhile (a robot process): what the snapshot sends of it.
  std::shared_ptr<const MultiResMap> own;
  std::uint64_t own_version = 0;
  // With loop closure on, that own map as the snapshot sends it (pieces apart).
  std::shared_ptr<const MapLayer> own_layer;
};

// What the engine needs of its robot.
class AgentPort {
 public:
  virtual ~AgentPort() = default;
  // The robot's view for encounter `encounter` with `peer`; nullopt before its first scan.
  virtual std::optional<CapturedView> capture_view(const std::string& peer, std::uint64_t encounter) = 0;
  // Own map (layer 0: `at`'s own map if it holds one, else the current one) and everything known.
  virtual MapSnapshot snapshot(const CapturedView& at) = 0;
  virtual std::vector<LayerVersion> inventory() const = 0;  // what snapshot() would hold, without copying
  // The pose of `origin`'s map frame in this robot's frame, if it holds that robot's map.
  virtual std::optional<Pose2> known_frame(const std::string& origin) const = 0;
  // Takes in the peer's layers (the sender's frame at `sender_in_self`) from
  // encounter `encounter`, whose view of this robot was `at`. Called for
  // every accepted encounter (snapshot.sender: the peer), with no layers
  // when the peer had nothing new:
  // the encounter itself ties the two frames (SwarmAgent::tie).
  virtual void merge(MapSnapshot snapshot, const Pose2& sender_in_self, const CapturedView& at,
                     std::uint64_t encounter) = 0;
  // Loop closing (followers.hpp): a number that grows whenever it moves this
  // robot's map; where the map lies now for a peer that follows it (its
  // scans at `ties`); and a peer's word that its map moved. The defaults
  // are a robot whose map never moves.
  virtual std::uint64_t graph_revision() const { return 0; }
  virtual MapMoves map_moves(const std::string& /*peer*/, const std::vector<TieScan>& /*ties*/,
                             std::size_t /*max_closures*/) const {
    return {};
  }
  virtual void follow(const std::string& /*peer*/, const MapMoves& /*moves*/) {}
};

struct EncounterOutcome {
  enum class End { accepted, rejected, declined, abandoned };
  // Why this robot declined to take part (declined by itself; a peer's decline is `by_peer`).
  enum class Decline { none, merging_off, merged_recently, busy, no_scan, unchanged, by_peer };
  std::uint64_t encounter = 0;
  std::string self, peer;
  bool self_is_a = true;  // A: the robot whose name sorts first
  End end = End::abandoned;
  std::string reason;        // why not accepted
  Decline decline = Decline::none;
  std::string confirmed_by;  // accepted: "known transform" or "earlier encounter[, by each direction of this one]"
  EncounterEstimate estimate;  // set once decided
  bool decided = false;
  Pose2 self_pose, peer_pose;  // each robot's pose in its own frame at the scans exchanged
  double self_stamp = 0.0, peer_stamp = 0.0;
  double started = 0.0, ended = 0.0;  // the caller's clock, s
  double compute_ms = 0.0, peer_compute_ms = 0.0, merge_ms = 0.0;
  std::size_t bytes_sent = 0, bytes_received = 0;  // every message of the encounter, as on the wire
  std::size_t snapshot_bytes_sent = 0, snapshot_bytes_received = 0;  // the .dsmap transfers alone
  std::size_t layers_received = 0;
};

struct Outgoing {
  std::string recipient;
  std::vector<std::uint8_t> bytes;
};

class EncounterEngine {
 public:
  EncounterEngine(std::string self, const SwarmConfig& config, AgentPort& port, std::uint64_t incarnation = 1);
  ~EncounterEngine();

  // A proximity event: this robot and `peer` are near.
  void start(const std::string& peer, std::uint64_t encounter, double now);
  // A message the gate admitted, `wire_bytes` long.
  void receive(const Message& message, std::size_t wire_bytes, double now);
  // The peer restarted or vanished: its open encounters are abandoned.
  void drop_peer(const std::string& peer, const std::string& why, double now);
  // Abandons every open encounter (this robot stops).
  void abandon_all(const std::string& why, double now);
  // Abandons encounters older than the exchange timeout; announce_moves().
  void tick(double now);
  // Tells the peers that merged this robot's map where it lies now, if loop
  // closing moved it and they are due word (followers.hpp; all of them when
  // `force`).
  void announce_moves(double now, bool force = false);

  std::vector<Outgoing> take_outbox() { return std::exchange(outbox_, {}); }
  std::vector<EncounterOutcome> take_outcomes() { return std::exchange(outcomes_, {}); }
  // Encounters open or waiting for an earlier one to end.
  std::size_t open_encounters() const { return open_.size() + waiting_.size(); }
  const std::string& self() const { return self_; }
  // Bytes held by incoming transfers in progress (bounded by the open-encounter cap).
  std::size_t buffered_bytes() const;

 private:
  struct Exchange;
  using Key = std::pair<std::string, std::uint64_t>;  // peer, encounter id
  struct PeerState {
    double last_merge = -1e300;
    std::vector<Pose2> pending;  // verified (or nearly: near_agreeing_estimate), unconfirmed: B's frame in A's
  };
  // An encounter waiting for an earlier one of this robot to end.
  struct Waiting {
    double since = 0.0;  // when it would have started
    std::optional<Offer> offer;  // the peer's, if it came meanwhile
    std::size_t offer_bytes = 0;
  };

  Exchange* join(const std::string& peer, std::uint64_t encounter, double now);
  Exchange* open(const std::string& peer, std::uint64_t encounter, double since, double now);
  bool blocked(std::uint64_t encounter) const;
  void resume_waiting(double now);
  void end_waiting(const Key& key, EncounterOutcome::End end, EncounterOutcome::Decline decline, std::string reason,
                   double now);
  void on_offer(const std::string& peer, const Offer& offer, std::size_t bytes, double now);
  void take_offer(Exchange& x, const Offer& offer, std::size_t bytes, double now);
  void on_placement(const std::string& peer, const Placement& placement, std::size_t bytes, double now);
  void on_chunk(const std::string& peer, const Chunk& chunk, std::size_t bytes, double now);
  void on_decline(const std::string& peer, const Decline& decline, std::size_t bytes, double now);
  void decide(Exchange& x, double now);
  void confirm(Exchange& x);
  bool confirm_by_directions(Exchange& x);
  void hold_pending(const std::string& peer, const Pose2& t);
  ConfirmTolerance confirm_tolerance() const { return {config_.confirm_xy, config_.confirm_theta}; }
  void send_transfer(Exchange& x);
  void absorb_transfer(Exchange& x, double now);
  void send(Exchange* x, const std::string& recipient, Body body);
  void decline(const std::string& peer, std::uint64_t encounter, EncounterOutcome::Decline why,
               const std::string& reason, double now);
  void finish(const Key& key, EncounterOutcome::End end, std::string reason, double now);
  std::uint64_t seed_for(const Exchange& x) const;
  void remember_ended(const Key& key);

  std::string self_;
  SwarmConfig config_;
  AgentPort& port_;
  MessageStamper stamper_;
  std::map<Key, std::unique_ptr<Exchange>> open_;
  std::map<Key, Waiting> waiting_;
  std::map<std::string, PeerState> peers_;
  std::set<Key> ended_;           // bounded by config_.remembered_encounters,
  std::deque<Key> ended_order_;   // the oldest forgotten first
  std::vector<Outgoing> outbox_;
  std::vector<EncounterOutcome> outcomes_;
  Followers followers_;
  RepeatGuard repeats_;
};

}  // namespace dsswarm::protocol
