#pragma once
// Scenario files for `dsswarm swarm`: which robots play which part of which
// log, from when, in which direction, and when they meet.
//
//   name: intel-split                  # optional; default: the file's stem
//   config: slam.json                  # optional SLAM JSON config, relative to this file
//   relations: ../../shared/data/relations/intel.relations   # optional, relative to this file
//   agents:                            # at least one
//     - name: robot1                   # letters, digits, '_', '-', '.'; unique
//       log: ../../shared/data/carmen/intel.log.gz            # relative to this file
//       from: 0            # s after the log's first scan   (or from_fraction: 0.0); default: the start
//       to: 600            # s after the log's first scan   (or to_fraction: 0.6);   default: the end
//       direction: forward # or backward: the segment's scans played last to first
//       start: 0           # session time (s) at which the agent plays its first scan; default 0
//   encounters:                        # optional
//     - agents: [robot1, robot2]
//       time: 312.5                    # session clock, s
//     - agents: [robot1, robot2]
//       log_times: [1234.5, 2210.0]    # instead of time: when robot1 plays its scan at log time
//                                      # 1234.5; the second is informational (must be in robot2's segment)
//
// Segments. Fractions are of the log's duration (first scan to latest
// timestamp). A scan belongs to [from, to] by the running maximum of the
// timestamps in file order, so a segment is always a contiguous run of the
// file even where timestamps run backwards (intel): file order is the true order.
//
// Session clock. An agent plays its scan i at
//   start + max over j <= i of (t_j − t_first)   (forward)
//   start + max over j <= i of (t_first − t_j)   (backward)
// where t_first is the timestamp of its first played scan (for a backward
// agent, the segment's last): the play clock (sensor/play_clock.hpp) plus the
// start. The running maximum keeps the clock non-decreasing where timestamps
// run backwards; such scans are counted in a warning.
//
// Encounters by log_times. The session time is the clock of the first agent's
// scan nearest to the given log time (within 1 ms of the segment's span), so
// that scan is the last one the agent has played when the encounter happens
// (SwarmSession fires an event only once every scan up to its time has played).
//
// Every mistake (missing or unknown key, bad value, unreadable log, empty
// segment...) is an InputError naming the file, the line, the agent (index and
// name) or encounter, and the key. Unknown keys are errors so typos cannot pass silently.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/logs/log_reader.hpp"
#include "protocol/swarm_session.hpp"

namespace dsswarm {

struct SwarmScenario {
  std::string name;                    // from the file, or the file stem
  std::vector<AgentStream> streams;    // ready to play, in file order of `agents`
  std::vector<EncounterEvent> events;  // scripted encounters, in file order (may be empty)
  std::optional<std::string> config;   // SLAM JSON config path, resolved against the YAML's folder
  std::string relations;               // relations file for evaluation, resolved ("" if none)
  std::vector<std::string> warnings;   // log quirks and scenario oddities, one line each
};

// Reads the scenario and every log it names (each distinct log once).
SwarmScenario load_swarm_scenario(const std::filesystem::path& yaml, const LogReadOptions& read = {});

// The same for the scenario's text in memory; `yaml` stands for its path:
// errors name it and relative paths are resolved against its folder.
SwarmScenario parse_swarm_scenario(const std::string& text, const std::filesystem::path& yaml,
                                   const LogReadOptions& read = {});

}  // namespace dsswarm
