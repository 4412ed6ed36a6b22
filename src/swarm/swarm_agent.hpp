#pragma once
// One robot of the swarm: single-robot SLAM in its own frame, plus what it
// has learnt from the others (per origin, see map_knowledge.hpp). It knows
// nothing of the others until told one is near; then it offers its map and
// current scan, and merges what the other offers once the encounter is
// verified (encounter.hpp). Alone, or if every encounter fails, it is just a
// single robot doing SLAM.
#include <memory>
#include <optional>
#include <string>

#include "slam/slam.hpp"
#include "swarm/encounter.hpp"
#include "swarm/map_knowledge.hpp"

namespace dsswarm {

// A robot's SLAM settings: the swarm's, with its own random stream derived
// from its name (so a robot process and the in-process swarm agree).
SlamConfig agent_slam_config(const SlamConfig& swarm, const std::string& name);

class SwarmAgent {
 public:
  SwarmAgent(std::string name, const SlamConfig& config);

  SlamStep process(const LaserScan& scan);

  // What this robot puts on the table at an encounter.
  // Working map, current scan, pose and surroundings (as `config` asks).
  EncounterView view(const RelativePoseConfig& config) const;
  MapSnapshot snapshot() const;      // own map (layer 0) + everything known of others

  // Takes in another robot's snapshot, whose sender's frame has pose
  // `sender_in_self` here, and rebuilds the working map if anything is new.
  // Returns whether anything was new.
  bool merge(const MapSnapshot& snapshot, const Pose2& sender_in_self);

  // The layers snapshot() would hold (origin, version, hops), without copying maps.
  std::vector<LayerVersion> inventory() const;
  const std::optional<LaserScan>& last_scan() const { return last_scan_; }

  const std::string& name() const { return name_; }
  const Slam& slam() const { return slam_; }
  const MapKnowledge& knowledge() const { return knowledge_; }

 private:
  std::string name_;
  Slam slam_;
  MapKnowledge knowledge_;
  std::optional<LaserScan> last_scan_;
  // Frozen copy of the own map for snapshots, refreshed when the map grew.
  mutable std::shared_ptr<const MultiResMap> own_copy_;
  mutable std::size_t own_copy_version_ = 0;
};

}  // namespace dsswarm
