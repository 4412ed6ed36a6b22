#pragma once
// What robots of a swarm say to each other. Every message is one of these
// bodies behind a common header; wire.hpp turns them into bytes and back
// (versioned, checksummed, validated). The same bytes travel over DDS between
// robot processes and through the in-memory transport of `dsswarm swarm` /
// `demo`, so both run one code path and count the same bytes.
//
// An encounter between robots A and B (A's name sorts first), both told by a
// Proximity event with the same id:
//   1. each sends an Offer: its current scan, pose, surroundings, and which
//      map layers (origin, version) it holds;
//   2. each places the other's scan in its own map and sends its Placement;
//   3. both run the same decision on the two placements (decide_encounter),
//      so both accept or neither does;
//   4. if accepted, each sends in Chunks only the snapshot layers the other
//      lacks (a .dsmap, zstd-compressed, checksummed), and merges what it
//      receives.
// A robot that cannot take part (no scan yet, merged with that peer moments
// ago, merging off) answers with a Decline.
//
// After an accepted encounter, a robot with loop closure on tells the peer
// (a Moved, at most every `moves_interval` s) whenever its loop closures
// moved its submaps or its scan of that encounter: the peer's copy of its
// map and the tie between the two graphs follow, and its closures into the
// peer's map join the peer's graph (swarm/map_snapshot.hpp, MapMoves).
// Older agents refuse this kind and count it; nothing else changes. A Moved
// without closures (agents before 2026-12-07) is read as having none.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "geometry/pose2.hpp"
#include "sensor/scan_points.hpp"
#include "swarm/encounter.hpp"
#include "swarm/map_snapshot.hpp"

namespace dsswarm::protocol {

inline constexpr std::uint16_t kProtocolVersion = 1;

enum class Kind : std::uint8_t {
  heartbeat = 1,
  proximity = 2,
  offer = 3,
  decline = 4,
  placement = 5,
  chunk = 6,
  moved = 7,
};
const char* kind_name(Kind kind);

struct Header {
  std::string sender;     // agent name (or the tool that sent it, e.g. "proximity")
  std::string recipient;  // agent name, or "" for everyone
  // The sender's start (ns since the epoch): a restarted sender has a larger
  // one, so messages of an earlier run can be told apart from a new run's.
  std::uint64_t incarnation = 0;
  std::uint64_t sequence = 0;  // per sender and incarnation, from 1: replays are refused
};

// What `dsswarm status` shows of an agent.
struct AgentStatus {
  double uptime = 0.0;                  // s since the agent started
  std::uint64_t scans_received = 0;
  std::uint64_t scans_processed = 0;
  std::uint64_t scans_skipped = 0;      // arrived while the agent was behind
  double scans_per_second = 0.0;        // processed, over the last heartbeat interval
  std::uint32_t peers_known = 0;        // robots whose maps it holds
  std::uint32_t encounters = 0;         // decided (accepted or rejected)
  std::uint32_t encounters_accepted = 0;
  double last_merge_age = -1.0;         // s since its last merge, -1: never
  std::uint64_t map_version = 0;        // scans in its own map
  std::uint64_t messages_rejected = 0;  // malformed, unauthorized, replayed
};

struct Heartbeat {
  AgentStatus status;
};

// Robots `a` and `b` are near each other. On a live robot the event means
// "now" (stamps NaN); for replayed logs it names, per robot, the log time of
// the scan after which to take part, so runs repeat exactly.
struct Proximity {
  std::string a, b;
  std::uint64_t event = 0;  // encounter id, the same for both robots
  double a_stamp = std::numeric_limits<double>::quiet_NaN();
  double b_stamp = std::numeric_limits<double>::quiet_NaN();
};

struct Offer {
  std::uint64_t encounter = 0;
  double stamp = 0.0;  // log time of the scan offered
  Pose2 pose;          // the sender's pose in its own map frame
  std::vector<ScanPoint> points;
  std::vector<ScanPoint> surroundings;
  std::vector<ScanPoint> wide_surroundings;
  std::vector<LayerVersion> inventory;  // every layer it holds, its own first
};

struct Decline {
  std::uint64_t encounter = 0;
  std::string reason;
};

struct Placement {
  std::uint64_t encounter = 0;
  PeerPlacement placement;  // the recipient's robot placed in the sender's map
  // Earlier estimates of the pair's transform the sender holds, as B's frame
  // in A's: from its layer of the other robot (directly or through a third),
  // and verified estimates of this pair still waiting for confirmation. Both
  // robots confirm against what either holds.
  std::optional<Pose2> known_transform;
  std::vector<Pose2> pending;
  double compute_ms = 0.0;  // the sender's time for its placement
};

// One piece of a snapshot transfer (an encoded .dsmap of the layers the
// recipient lacks). count = 0 means "nothing you lack".
struct Chunk {
  std::uint64_t encounter = 0;
  std::uint32_t index = 0;
  std::uint32_t count = 0;
  std::uint64_t total_bytes = 0;
  std::uint32_t total_crc = 0;  // CRC-32 of the whole transfer
  std::vector<std::uint8_t> data;
};

// The sender's map moved since the recipient took a copy (see above).
struct Moved {
  MapMoves moves;
};

using Body = std::variant<Heartbeat, Proximity, Offer, Decline, Placement, Chunk, Moved>;

struct Message {
  Header header;
  Body body;
};

// The kind that goes with a body.
Kind kind_of(const Body& body);

}  // namespace dsswarm::protocol
