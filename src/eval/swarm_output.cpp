#include "eval/swarm_output.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class EntryReader {
 public:
  EntryReader(const json& entry, std::string where) : entry_(entry), where_(std::move(where)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw InputError(fmt::format("{}: field '{}': {}", where_, field, what));
  }

  const json& require(const std::string& field) const {
    const auto it = entry_.find(field);
    if (it == entry_.end()) fail(field, "missing");
    return *it;
  }

  bool has(const std::string& field) const {
    const auto it = entry_.find(field);
    return it != entry_.end() && !it->is_null();
  }

  double number(const json& j, const std::string& field) const {
    if (!j.is_number()) fail(field, fmt::format("expected a number, got {}", j.dump()));
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(field, "not a finite number");
    return v;
  }

  double number(const std::string& field) const { return number(require(field), field); }

  const json& array(const json& j, const std::string& field, std::size_t size, const std::string& what) const {
    if (!j.is_array() || j.size() != size) fail(field, fmt::format("expected {}, got {}", what, j.dump()));
    return j;
  }

  Pose2 pose(const json& j, const std::string& field) const {
    array(j, field, 3, "[x, y, theta]");
    return {number(j[0], field), number(j[1], field), number(j[2], field)};
  }

  std::string text(const json& j, const std::string& field) const {
    if (!j.is_string()) fail(field, fmt::format("expected a string, got {}", j.dump()));
    return j.get<std::string>();
  }

 private:
  const json& entry_;
  std::string where_;
};

SwarmEncounterEntry parse_entry(const json& entry, const std::string& where) {
  if (!entry.is_object()) throw InputError(fmt::format("{}: expected an object", where));
  const EntryReader r(entry, where);
  SwarmEncounterEntry e;
  e.time = r.number("time");
  const json& agents = r.array(r.require("agents"), "agents", 2, "two agent names");
  e.a = r.text(agents[0], "agents");
  e.b = r.text(agents[1], "agents");
  const json& times = r.array(r.require("log_times"), "log_times", 2, "two log times");
  e.a_log_time = r.number(times[0], "log_times");
  e.b_log_time = r.number(times[1], "log_times");
  const json& poses = r.array(r.require("poses"), "poses", 2, "two poses [[x, y, theta], [x, y, theta]]");
  e.a_pose = r.pose(poses[0], "poses");
  e.b_pose = r.pose(poses[1], "poses");
  const json& accepted = r.require("accepted");
  if (!accepted.is_boolean()) r.fail("accepted", fmt::format("expected true or false, got {}", accepted.dump()));
  e.accepted = accepted.get<bool>();
  if (r.has("transform")) {
    e.transform = r.pose(entry.at("transform"), "transform");
  } else if (e.accepted) {
    r.fail("transform", "missing (an accepted encounter must have one)");
  }
  if (r.has("reason")) e.reason = r.text(entry.at("reason"), "reason");
  if (r.has("match_ms")) e.match_ms = r.number("match_ms");
  if (r.has("merge_ms")) e.merge_ms = r.number("merge_ms");
  if (r.has("bytes")) e.bytes = r.number("bytes");
  return e;
}

}  // namespace

std::vector<SwarmEncounterEntry> read_swarm_encounters(const fs::path& path) {
  std::ifstream in(path);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec) || !in) {
    throw InputError(fmt::format("{}: cannot open encounters file", path.string()));
  }
  json root;
  try {
    root = json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(fmt::format("{}: invalid JSON: {}", path.string(), e.what()));
  }
  if (!root.is_object() || !root.contains("encounters") || !root.at("encounters").is_array()) {
    throw InputError(fmt::format("{}: field 'encounters': expected {{\"encounters\": [...]}}", path.string()));
  }
  std::vector<SwarmEncounterEntry> out;
  const json& list = root.at("encounters");
  for (std::size_t k = 0; k < list.size(); ++k) {
    out.push_back(parse_entry(list[k], fmt::format("{}: encounters[{}]", path.string(), k)));
  }
  return out;
}

SwarmOutput read_swarm_output(const fs::path& dir) {
  std::error_code ec;
  const fs::path agents_dir = dir / "agents";
  if (!fs::is_directory(agents_dir, ec)) {
    throw InputError(fmt::format("{}: not a swarm output folder (no agents/ folder)", dir.string()));
  }
  SwarmOutput out;
  for (const auto& item : fs::directory_iterator(agents_dir)) {
    if (!item.is_directory()) continue;
    SwarmAgentOutput agent;
    agent.name = item.path().filename().string();
    const fs::path own = item.path() / "trajectory.tum";
    if (!fs::is_regular_file(own, ec)) {
      throw InputError(fmt::format("{}: agent folder without trajectory.tum", item.path().string()));
    }
    agent.own = read_tum(own);
    const fs::path joint = dir / "joint" / (agent.name + ".tum");
    if (fs::is_regular_file(joint, ec)) agent.joint = read_tum(joint);
    out.agents.push_back(std::move(agent));
  }
  if (out.agents.empty()) throw InputError(fmt::format("{}: no agents", agents_dir.string()));
  std::sort(out.agents.begin(), out.agents.end(),
            [](const SwarmAgentOutput& x, const SwarmAgentOutput& y) { return x.name < y.name; });
  const fs::path encounters = dir / "encounters.json";
  if (fs::exists(encounters, ec)) {
    out.encounters = read_swarm_encounters(encounters);
    for (std::size_t k = 0; k < out.encounters.size(); ++k) {
      for (const std::string& name : {out.encounters[k].a, out.encounters[k].b}) {
        const bool known = std::any_of(out.agents.begin(), out.agents.end(),
                                       [&](const SwarmAgentOutput& a) { return a.name == name; });
        if (!known) {
          throw InputError(fmt::format("{}: encounters[{}]: field 'agents': no agent '{}' in {}", encounters.string(),
                                       k, name, agents_dir.string()));
        }
      }
    }
  }
  return out;
}

}  // namespace dsswarm
