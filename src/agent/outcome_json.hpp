#pragma once
// A robot's encounter outcomes as JSON (its encounters.json), complete enough
// that `dsswarm launch` can pair both robots' sides into the same records the
// in-process swarm writes (protocol/swarm_session.hpp make_record).
#include <nlohmann/json.hpp>

#include "protocol/encounter_engine.hpp"

namespace dsswarm::agent {

nlohmann::json to_json(const protocol::EncounterOutcome& o);
// Throws InputError naming `source` when a field is missing or malformed.
protocol::EncounterOutcome outcome_from_json(const nlohmann::json& j, const std::string& source);

}  // namespace dsswarm::agent
