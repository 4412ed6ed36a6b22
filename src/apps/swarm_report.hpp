#pragma once
// Console lines of `dsswarm swarm` and `dsswarm demo` that need more than one
// format call.
#include <string>
#include <vector>

#include "swarm/swarm_session.hpp"

namespace dsswarm {

// What became of the encounter events the session was given, e.g.
// "3 scripted encounters: 2 run, 1 skipped (robot2 had not started)".
// `what` names the events ("scripted encounters", "proximity events");
// `names` and `first_clock` (session time of each agent's first scan, inf
// for none) are per agent, `records` are the session's encounters.
std::string describe_encounter_events(const std::string& what, const std::vector<EncounterEvent>& events,
                                      const std::vector<std::string>& names, const std::vector<double>& first_clock,
                                      const std::vector<EncounterRecord>& records, const SwarmConfig& config);

}  // namespace dsswarm
