#pragma once
// Settings of a robot in a swarm: its SLAM, how it judges an encounter, and
// how it talks to the others (the same for every robot of a swarm).
#include <cstddef>

#include "slam/slam.hpp"
#include "swarm/encounter.hpp"

namespace dsswarm {

// SLAM as a robot of a swarm runs it by default: loop closure on as in
// `run`, with a round of it every 20 nodes instead of run's 40. An encounter
// places the other robot's scan in, and merges into, the map as the latest
// round left it; the staler that is, the further a transform found on it lies
// from the maps as they end up (docs/loop_closure.md).
SlamConfig swarm_slam_config();

struct SwarmConfig {
  // Loop closure is on: robots send their submaps apart, an accepted
  // encounter is a constraint in each robot's own pose graph, and closures
  // into the other robots' submaps keep the joint frame in place
  // (docs/loop_closure.md, "In the swarm"). {"loop_closure": {"enabled":
  // false}} turns it off: one map per robot, about two thirds of the CPU.
  SlamConfig slam = swarm_slam_config();
  EncounterConfig encounter;
  // Robots that met with an accepted merge skip further encounters for this
  // long (their maps have not changed much); rejected ones retry at once.
  double remerge_interval = 10.0;  // s
  // A merge takes effect in the map a robot localizes in this long (log
  // time) after the scan of its encounter (merge_schedule.hpp): in one
  // process and in robot processes alike, so both localize the same scans in
  // the same maps and decide the same. A robot process whose merge is not
  // composed by then uses it when it is (counted as late). 0: at once.
  double merge_delay = 2.0;  // s
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
  // An encounter whose two placements each verify but disagree with each
  // other (beyond encounter.agree_xy / agree_theta, within confirm_xy /
  // confirm_theta) still counts as a second estimate: it confirms a pending
  // transform that each direction agrees with, or, with loop closure on, is
  // held pending itself (protocol/confirmation.hpp). Robots that meet while
  // their maps are still bent (loops not yet closed) seldom agree to 8 cm twice.
  bool confirm_by_directions = true;
  // An encounter is declined as a repeat when both robots stand within this
  // of where they stood at the pair's last decided encounter, on the same
  // maps (protocol/repeats.hpp): parked robots are not placed again and again.
  double repeat_xy = 0.05;      // m
  double repeat_theta = 0.0175; // rad (1°)
  // A repeat of an encounter turned down (not verified) is run again this
  // many times: each run is a new random search, which may find what the
  // last one missed. A verified one is never repeated (a transform cannot
  // confirm itself).
  int repeat_retries = 1;
  // The exchange itself (protocol/): an encounter not finished in this long
  // after both robots joined is abandoned, its partial transfer discarded (a
  // peer vanished). A peer joins (sends its offer) only once its earlier
  // encounters have ended: when many robots meet at once that can take a
  // while, so the wait for its offer has its own, longer limit (a peer that
  // dies meanwhile is dropped sooner, when its heartbeats stop).
  double exchange_timeout = 30.0;       // s
  double offer_timeout = 90.0;          // s
  std::size_t chunk_bytes = 60000;      // snapshot bytes per message
  std::size_t max_open_encounters = 16; // at once, with any peers (bounds memory)
  std::size_t max_pending_confirmations = 16;  // per peer, oldest dropped
  // Encounters that ended (any way) are remembered, the oldest forgotten
  // beyond this: an encounter ends once, even when a restarted peer offers
  // the same one again.
  std::size_t remembered_encounters = 4096;
  // Snapshot bytes held by all incoming transfers together; a transfer that
  // would go beyond is abandoned (many peers at once must not exhaust a
  // small robot's memory). A 100 m × 100 m map travels in ~3 MB.
  std::size_t max_transfer_bytes = std::size_t{256} << 20;
  // With loop closure on, peers that merged a robot's map hear where its
  // loop closures moved it (followers.hpp) at most this often, about each
  // of their last `max_followed_encounters` encounters with it.
  double moves_interval = 5.0;  // s
  std::size_t max_followed_encounters = 32;
  // With them go the robot's loop closures into the peer's map, the most
  // recent this many (52 bytes each), for the peer's graph to weigh too.
  std::size_t max_moved_closures = 4096;
  // `dsswarm swarm` (robots in one process): after the logs end, rounds in
  // which the robots take turns, each closing its loops on what the others
  // last told it and telling them where that left its map. Turn by turn,
  // not all at once: two robots each bending towards the other's last shape
  // at the same moment would trade their shapes rather than agree.
  int final_exchanges = 2;

  void validate() const;  // throws ConfigError naming the field
};

}  // namespace dsswarm
