#pragma once
// A finished swarm run as plain data, however it ran: in one process
// (`dsswarm swarm` / `demo`, from a SwarmSession) or as robot processes
// (`dsswarm launch`, gathered from their output folders). The outputs and the
// evaluation take this, so both paths are written and scored by one code.
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "grid/multires_map.hpp"
#include "io/trajectory/tum.hpp"
#include "protocol/swarm_session.hpp"
#include "swarm/map_snapshot.hpp"

namespace dsswarm {

struct SwarmAgentResult {
  std::string name;
  Trajectory trajectory;  // poses in its own map frame, every scan, play order
  // Its own map's version (scans in it) after each of those scans, when
  // known: a layer of version v that others hold covers the path while ≤ v.
  std::vector<std::size_t> map_versions;
  std::shared_ptr<const MultiResMap> own_map;      // only its own scans
  std::shared_ptr<const MultiResMap> working_map;  // own ⊕ everything received
  std::vector<MapLayer> knows;  // what it holds of others (origin, version, hops, frame)
  nlohmann::json counters;      // scans matched, held, ... as stats.json reports them

  // The layer of `origin`'s map it holds; null if none.
  const MapLayer* held(const std::string& origin) const {
    for (const MapLayer& l : knows)
      if (l.origin == origin) return &l;
    return nullptr;
  }
};

struct SwarmRunResult {
  std::vector<SwarmAgentResult> agents;
  std::vector<EncounterRecord> encounters;
  std::size_t events_skipped = 0;
  SwarmConfig config;
  // Word of where loop closing moved a merged map (protocol/followers.hpp),
  // all robots together (robot processes: as received).
  std::size_t moved_messages = 0, moved_bytes = 0;
};

// Ground truth of a simulated swarm: per agent, the true world pose at each
// scan timestamp. Enables transform errors, coverage and ATE.
struct SwarmTruth {
  std::vector<Trajectory> world_poses;
};

}  // namespace dsswarm
