#pragma once
// What `dsswarm swarm` wrote, read back for scoring: DIR/agents/<name>/trajectory.tum,
// DIR/joint/<name>.tum and DIR/encounters.json.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "geometry/pose2.hpp"
#include "io/trajectory/tum.hpp"

namespace dsswarm {

// One entry of encounters.json.
struct SwarmEncounterEntry {
  double time = 0.0;           // session clock, s
  std::string a, b;            // agent names
  double a_log_time = 0.0;     // timestamps of the scans exchanged
  double b_log_time = 0.0;
  Pose2 a_pose;                // a's pose in a's frame at the encounter
  Pose2 b_pose;                // b's pose in b's frame
  std::optional<Pose2> transform;  // b's frame in a's frame (a candidate only, when rejected)
  bool accepted = false;
  std::string reason;
  std::optional<double> match_ms, merge_ms, bytes;
};

// Reads {"encounters": [...]}. Required per entry: time, agents, log_times,
// poses, accepted; transform when accepted (may be null otherwise); reason,
// match_ms, merge_ms, bytes optional; other keys are ignored (simulation adds
// its own). Throws InputError naming the file, the entry and the field.
std::vector<SwarmEncounterEntry> read_swarm_encounters(const std::filesystem::path& path);

struct SwarmAgentOutput {
  std::string name;
  Trajectory own;                  // agents/<name>/trajectory.tum
  std::optional<Trajectory> joint; // joint/<name>.tum, when its transform was known
};

struct SwarmOutput {
  std::vector<SwarmAgentOutput> agents;  // sorted by name
  std::vector<SwarmEncounterEntry> encounters;
};

// Reads a swarm output folder. encounters.json may be absent (no encounters);
// agents/ must hold at least one agent with a trajectory.tum.
SwarmOutput read_swarm_output(const std::filesystem::path& dir);

}  // namespace dsswarm
