#include "apps/launch_gather.hpp"

#include <fmt/format.h>

#include <fstream>

#include "agent/checkpoint.hpp"
#include "agent/outcome_json.hpp"
#include "common/errors.hpp"
#include "swarm/map_merge.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using protocol::EncounterOutcome;

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return nlohmann::json::object();
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not valid JSON ({})", path.string(), e.what()));
  }
}

std::vector<EncounterOutcome> read_outcomes(const fs::path& path) {
  const nlohmann::json j = read_json(path);
  std::vector<EncounterOutcome> out;
  if (!j.contains("encounters")) return out;
  for (const nlohmann::json& e : j.at("encounters")) out.push_back(agent::outcome_from_json(e, path.string()));
  return out;
}

SwarmAgentResult agent_result(const fs::path& dir, const std::string& name, const nlohmann::json& stats) {
  const agent::Checkpoint c = agent::read_checkpoint(dir, name);
  SwarmAgentResult a;
  a.name = name;
  a.trajectory = c.trajectory;
  std::vector<MapLayer> foreign;
  for (const MapLayer& l : c.snapshot.layers) {
    if (l.origin == name)
      a.own_map = l.pieces.empty() ? l.map : std::make_shared<const MultiResMap>(layer_evidence(l));
    else
      foreign.push_back(l);
  }
  if (!a.own_map) throw InputError(fmt::format("{}: the checkpoint holds no map of {}", dir.string(), name));
  a.knows = foreign;
  a.working_map = std::make_shared<const MultiResMap>(compose_working_map(*a.own_map, foreign));
  for (const char* key : {"scans_matched", "scans_held", "matches_rejected", "recovery_searches", "scans_received",
                          "scans_skipped", "cpu_seconds", "wall_seconds", "largest_scan_gap_ms",
                          "largest_scan_gap_during_encounter_ms", "merge_latency_ms", "merge_ready_ms", "merges_late",
                          "messages_rejected"})
    if (stats.contains(key)) a.counters[key] = stats[key];
  return a;
}

// The other robot's side as far as one side knows it (its peer died mid-way).
EncounterOutcome mirrored(const EncounterOutcome& o) {
  EncounterOutcome m;
  m.encounter = o.encounter;
  m.self = o.peer;
  m.peer = o.self;
  m.self_is_a = !o.self_is_a;
  m.end = o.end;
  m.reason = o.reason;
  m.confirmed_by = o.confirmed_by;
  m.estimate = o.estimate;
  m.decided = o.decided;
  m.self_pose = o.peer_pose;
  m.peer_pose = o.self_pose;
  m.self_stamp = o.peer_stamp;
  m.peer_stamp = o.self_stamp;
  m.compute_ms = o.peer_compute_ms;
  m.bytes_sent = o.bytes_received;
  m.bytes_received = o.bytes_sent;
  return m;
}

}  // namespace

GatheredRun gather_launch(const fs::path& out, const std::vector<std::string>& names, const SwarmConfig& config,
                          const std::map<std::uint64_t, double>& event_times) {
  GatheredRun g;
  g.run.config = config;
  // (encounter id, A, B) → A's and B's outcomes.
  std::map<std::tuple<std::uint64_t, std::string, std::string>, std::pair<const EncounterOutcome*, const EncounterOutcome*>>
      pairs;
  std::vector<std::vector<EncounterOutcome>> outcomes;
  for (const std::string& name : names) {
    const fs::path dir = out / "agents" / name;
    nlohmann::json stats = read_json(dir / "stats.json");
    if (!agent::has_checkpoint(dir)) {
      g.problems.push_back(fmt::format("{} left no outputs in {}", name, dir.string()));
      continue;
    }
    g.run.agents.push_back(agent_result(dir, name, stats));
    g.run.moved_messages += stats.value("moved_received", std::size_t{0});
    g.run.moved_bytes += stats.value("moved_bytes_received", std::size_t{0});
    g.agent_stats.push_back(std::move(stats));
    outcomes.push_back(read_outcomes(dir / "encounters.json"));
  }
  std::size_t declined = 0;
  for (const auto& list : outcomes)
    for (const EncounterOutcome& o : list) {
      if (o.end == EncounterOutcome::End::declined) {
        declined += o.self_is_a ? 1 : 0;  // counted once per event
        continue;
      }
      auto& slot = pairs[{o.encounter, o.self_is_a ? o.self : o.peer, o.self_is_a ? o.peer : o.self}];
      (o.self_is_a ? slot.first : slot.second) = &o;
    }
  for (const auto& [key, sides] : pairs) {
    const auto time = event_times.find(std::get<0>(key));
    const double t = time == event_times.end() ? 0.0 : time->second;
    if (sides.first && sides.second) {
      g.run.encounters.push_back(make_record(*sides.first, *sides.second, t));
      continue;
    }
    const EncounterOutcome& one = sides.first ? *sides.first : *sides.second;
    g.problems.push_back(fmt::format("encounter {} of {} and {}: only {}'s side was written", one.encounter, one.self,
                                     one.peer, one.self));
    const EncounterOutcome other = mirrored(one);
    g.run.encounters.push_back(one.self_is_a ? make_record(one, other, t) : make_record(other, one, t));
  }
  std::sort(g.run.encounters.begin(), g.run.encounters.end(),
            [](const EncounterRecord& x, const EncounterRecord& y) { return x.time < y.time || (x.time == y.time && x.id < y.id); });
  g.run.events_skipped = declined;
  return g;
}

}  // namespace dsswarm
