#include "apps/swarm_scenario.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "apps/scenario_file.hpp"
#include "common/agent_name.hpp"
#include "common/errors.hpp"
#include "sensor/play_clock.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

using scenario_detail::load_root;
using scenario_detail::ScenarioFile;

// Slack on segment bounds and log times: relation files give scan timestamps
// to 1 ms, and `t0 + fraction * duration` need not round back to a timestamp exactly.
constexpr double kBoundSlack = 1e-6;  // s
constexpr double kLogTimeSlack = 1e-3;  // s
// Beyond this, an encounter's second log time is reported as not where the
// second agent actually is at the encounter.
constexpr double kLogTimeMismatchWarning = 1.0;  // s

// Agent names become folder names in the swarm command's output.
struct AgentSpec {
  YAML::Node node;
  std::string context;  // "agents[i] (name):"
  std::string name;
  fs::path log;
  bool backward = false;
  double start = 0.0;
};

// A bound of the segment, as given: seconds after the first scan or a fraction of the duration.
struct Bound {
  YAML::Node node;
  std::string key;
  double value = 0.0;
  bool is_fraction = false;
};

std::optional<Bound> read_bound(const ScenarioFile& f, const YAML::Node& agent, const std::string& context,
                                const std::string& seconds_key, const std::string& fraction_key) {
  const YAML::Node seconds = agent[seconds_key];
  const YAML::Node fraction = agent[fraction_key];
  if (seconds && fraction) {
    f.fail(fraction, context, fraction_key, fmt::format("give either '{}' or '{}', not both", seconds_key, fraction_key));
  }
  if (seconds) return Bound{seconds, seconds_key, f.non_negative(seconds, context, seconds_key), false};
  if (fraction) return Bound{fraction, fraction_key, f.fraction(fraction, context, fraction_key), true};
  return std::nullopt;
}

struct Segment {
  std::size_t first = 0;  // file indices, inclusive
  std::size_t last = 0;
};

// The contiguous run of the file whose running-maximum timestamps lie in [from, to].
Segment select_segment(const ScenarioFile& f, const AgentSpec& a, const SensorLog& log) {
  std::vector<double> running_max(log.scans.size());
  double m = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < log.scans.size(); ++i) running_max[i] = m = std::max(m, log.scans[i].timestamp);
  const double t0 = log.scans.front().timestamp;
  const double duration = running_max.back() - t0;

  const auto from = read_bound(f, a.node, a.context, "from", "from_fraction");
  const auto to = read_bound(f, a.node, a.context, "to", "to_fraction");
  const auto absolute = [&](const Bound& b) { return t0 + (b.is_fraction ? b.value * duration : b.value); };
  const double lo = from ? absolute(*from) - kBoundSlack : -std::numeric_limits<double>::infinity();
  const double hi = to ? absolute(*to) + kBoundSlack : std::numeric_limits<double>::infinity();
  if (from && to && from->value >= to->value && from->is_fraction == to->is_fraction) {
    f.fail(to->node, a.context, to->key, fmt::format("{} must be greater than {} ({})", to->value, from->key, from->value));
  }
  if (from && to && absolute(*from) >= absolute(*to)) {
    f.fail(to->node, a.context, to->key,
           fmt::format("ends at {:.3f} s after the log's first scan, not after '{}' ({:.3f} s)", absolute(*to) - t0,
                       from->key, absolute(*from) - t0));
  }
  const auto first = std::lower_bound(running_max.begin(), running_max.end(), lo);
  const auto end = std::upper_bound(running_max.begin(), running_max.end(), hi);
  if (first >= end) {
    const Bound& culprit = from ? *from : *to;
    f.fail(culprit.node, a.context, culprit.key,
           fmt::format("the segment holds no scans (the log {} spans {:.3f} s)", a.log.string(), duration));
  }
  return {static_cast<std::size_t>(first - running_max.begin()), static_cast<std::size_t>(end - running_max.begin()) - 1};
}

// Scans in play order and their session clock; counts the scans whose
// timestamp runs backwards in play order (their clock is held).
AgentStream build_stream(const AgentSpec& a, const SensorLog& log, const Segment& s, std::vector<std::string>& warnings) {
  AgentStream stream;
  stream.name = a.name;
  stream.scans.assign(log.scans.begin() + static_cast<std::ptrdiff_t>(s.first),
                      log.scans.begin() + static_cast<std::ptrdiff_t>(s.last) + 1);
  if (a.backward) std::reverse(stream.scans.begin(), stream.scans.end());
  const double t_first = stream.scans.front().timestamp;
  const double sign = a.backward ? -1.0 : 1.0;
  const std::vector<double> elapsed =
      play_clock(stream.scans, a.backward ? PlayDirection::backward : PlayDirection::forward);
  std::size_t held = 0;
  for (std::size_t i = 0; i < elapsed.size(); ++i) {
    held += elapsed[i] > sign * (stream.scans[i].timestamp - t_first) ? 1 : 0;
    stream.clock.push_back(a.start + elapsed[i]);
  }
  if (held > 0) {
    warnings.push_back(fmt::format(
        "agent {}: {} of {} scans have timestamps running {} in play order; their session clock is held at "
        "the latest time reached",
        a.name, held, stream.scans.size(), a.backward ? "forwards (it plays backward)" : "backwards"));
  }
  return stream;
}

struct LoadedAgents {
  std::vector<AgentSpec> specs;
  std::vector<AgentStream> streams;
};

LoadedAgents load_agents(const ScenarioFile& f, const YAML::Node& root, const LogReadOptions& read,
                         std::vector<std::string>& warnings) {
  const YAML::Node list = root["agents"];
  if (!list) f.fail_missing(root, "", "agents", "a list of robots");
  if (!list.IsSequence() || list.size() == 0) f.fail(list, "", "agents", "expected a non-empty list of agents");
  LoadedAgents out;
  std::map<fs::path, SensorLog> logs;  // each log read once, however many agents play it
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node node = list[i];
    AgentSpec a;
    a.node = node;
    a.context = fmt::format("agents[{}]:", i);
    // Name the agent in every message as soon as its name can be read.
    if (node.IsMap() && node["name"] && node["name"].IsScalar()) {
      a.context = fmt::format("agents[{}] ({}):", i, node["name"].Scalar());
    }
    f.check_keys(node, a.context, "an agent",
                 {"name", "log", "from", "from_fraction", "to", "to_fraction", "direction", "start"});
    if (!node["name"]) f.fail_missing(node, a.context, "name");
    a.name = f.text(node["name"], a.context, "name");
    if (!is_valid_agent_name(a.name)) {
      f.fail(node["name"], a.context, "name",
             fmt::format("'{}' is not a valid agent name (letters, digits, '_', '-', '.'; it names an output folder)",
                         a.name));
    }
    a.context = fmt::format("agents[{}] ({}):", i, a.name);
    for (const AgentSpec& other : out.specs) {
      if (other.name == a.name) f.fail(node["name"], a.context, "name", fmt::format("'{}' is already the name of {}", a.name, other.context.substr(0, other.context.size() - 1)));
    }
    if (!node["log"]) f.fail_missing(node, a.context, "log", "the log file this agent plays");
    a.log = f.existing_file(node["log"], a.context, "log", true);
    if (const YAML::Node d = node["direction"]) {
      const std::string dir = f.text(d, a.context, "direction");
      if (dir != "forward" && dir != "backward") {
        f.fail(d, a.context, "direction", fmt::format("'{}' is neither forward nor backward", dir));
      }
      a.backward = dir == "backward";
    }
    if (const YAML::Node s = node["start"]) a.start = f.non_negative(s, a.context, "start");

    auto cached = logs.find(a.log);
    if (cached == logs.end()) {
      SensorLog log;
      try {
        log = read_log(a.log, read);
      } catch (const InputError& e) {
        f.fail(node["log"], a.context, "log", fmt::format("cannot read the log: {}", e.what()));
      }
      if (log.scans.empty()) f.fail(node["log"], a.context, "log", fmt::format("{} has no scans", a.log.string()));
      warnings.insert(warnings.end(), log.warnings.begin(), log.warnings.end());  // they name the file
      cached = logs.emplace(a.log, std::move(log)).first;
    }
    const Segment segment = select_segment(f, a, cached->second);
    out.streams.push_back(build_stream(a, cached->second, segment, warnings));
    out.specs.push_back(std::move(a));
  }
  return out;
}

std::size_t agent_index(const ScenarioFile& f, const YAML::Node& node, const std::string& context,
                        const std::vector<AgentSpec>& agents) {
  const std::string name = f.text(node, context, "agents");
  for (std::size_t i = 0; i < agents.size(); ++i)
    if (agents[i].name == name) return i;
  f.fail(node, context, "agents", fmt::format("no agent is named '{}'", name));
}

// Where a log time falls in an agent's stream: the played scan nearest to it.
std::optional<std::size_t> scan_at_log_time(const AgentStream& s, double t) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const LaserScan& scan : s.scans) {
    lo = std::min(lo, scan.timestamp);
    hi = std::max(hi, scan.timestamp);
  }
  if (t < lo - kLogTimeSlack || t > hi + kLogTimeSlack) return std::nullopt;
  std::size_t best = 0;
  for (std::size_t i = 1; i < s.scans.size(); ++i)
    if (std::abs(s.scans[i].timestamp - t) < std::abs(s.scans[best].timestamp - t)) best = i;
  return best;
}

std::string span_text(const AgentStream& s) {
  const auto [lo, hi] = std::minmax_element(s.scans.begin(), s.scans.end(),
                                            [](const LaserScan& x, const LaserScan& y) { return x.timestamp < y.timestamp; });
  return fmt::format("[{:.6f}, {:.6f}]", lo->timestamp, hi->timestamp);
}

// The log time an agent has reached at session time `t` (its last scan with clock <= t).
std::optional<double> log_time_at(const AgentStream& s, double t) {
  const auto after = std::upper_bound(s.clock.begin(), s.clock.end(), t);
  if (after == s.clock.begin()) return std::nullopt;
  return s.scans[static_cast<std::size_t>(after - s.clock.begin()) - 1].timestamp;
}

// An encounter's session time, from 'time' or from 'log_times' (then
// `b_log_time` is b's, to check against where b is at that time).
double encounter_time(const ScenarioFile& f, const YAML::Node& node, const std::string& context, const AgentStream& a,
                      const AgentStream& b, std::optional<double>& b_log_time) {
  const YAML::Node time = node["time"];
  const YAML::Node log_times = node["log_times"];
  if (time && log_times) f.fail(log_times, context, "log_times", "give either 'time' or 'log_times', not both");
  if (!time && !log_times) f.fail_missing(node, context, "time", "or 'log_times'");
  if (time) return f.non_negative(time, context, "time");
  if (!log_times.IsSequence() || log_times.size() != 2) {
    f.fail(log_times, context, "log_times", "expected two log times: [time of a, time of b]");
  }
  const double ta = f.number(log_times[0], context, "log_times");
  const double tb = f.number(log_times[1], context, "log_times");
  const auto ia = scan_at_log_time(a, ta);
  if (!ia) {
    f.fail(log_times[0], context, "log_times",
           fmt::format("{:.6f} is outside the segment of agent {} (log times {})", ta, a.name, span_text(a)));
  }
  if (!scan_at_log_time(b, tb)) {
    f.fail(log_times[1], context, "log_times",
           fmt::format("{:.6f} is outside the segment of agent {} (log times {})", tb, b.name, span_text(b)));
  }
  b_log_time = tb;
  return a.clock[*ia];
}

// Encounter `k` at a time one of its agents is not running, or (log_times)
// where b is far from the log time given for it: a warning each.
void warn_about_timing(std::size_t k, const EncounterEvent& e, const AgentStream& a, const AgentStream& b,
                       const std::optional<double>& b_log_time, std::vector<std::string>& warnings) {
  for (const AgentStream* s : {&a, &b}) {
    if (e.time < s->clock.front()) {
      warnings.push_back(fmt::format("encounter {} at session time {:.3f} s: agent {} starts only at {:.3f} s, so "
                                     "the encounter will be skipped",
                                     k, e.time, s->name, s->clock.front()));
    } else if (e.time > s->clock.back()) {
      warnings.push_back(fmt::format("encounter {} at session time {:.3f} s: agent {} finished at {:.3f} s and "
                                     "meets with its final state",
                                     k, e.time, s->name, s->clock.back()));
    }
  }
  if (!b_log_time) return;
  const auto reached = log_time_at(b, e.time);
  if (reached && std::abs(*reached - *b_log_time) > kLogTimeMismatchWarning) {
    warnings.push_back(fmt::format("encounter {} at session time {:.3f} s: agent {} is at log time {:.3f}, "
                                   "{:.1f} s from the given {:.3f}",
                                   k, e.time, b.name, *reached, *reached - *b_log_time, *b_log_time));
  }
}

std::vector<EncounterEvent> load_encounters(const ScenarioFile& f, const YAML::Node& root, const LoadedAgents& agents,
                                            std::vector<std::string>& warnings) {
  std::vector<EncounterEvent> events;
  const YAML::Node list = root["encounters"];
  if (!list || list.IsNull()) return events;
  if (!list.IsSequence()) f.fail(list, "", "encounters", "expected a list of encounters");
  for (std::size_t k = 0; k < list.size(); ++k) {
    const YAML::Node node = list[k];
    const std::string context = fmt::format("encounters[{}]:", k);
    f.check_keys(node, context, "an encounter", {"agents", "time", "log_times"});
    const YAML::Node names = node["agents"];
    if (!names) f.fail_missing(node, context, "agents", "the two agents that meet");
    if (!names.IsSequence() || names.size() != 2) f.fail(names, context, "agents", "expected two agent names: [a, b]");
    EncounterEvent e;
    e.a = agent_index(f, names[0], context, agents.specs);
    e.b = agent_index(f, names[1], context, agents.specs);
    if (e.a == e.b) f.fail(names, context, "agents", fmt::format("'{}' cannot meet itself", agents.specs[e.a].name));
    const AgentStream& a = agents.streams[e.a];
    const AgentStream& b = agents.streams[e.b];
    std::optional<double> b_log_time;
    e.time = encounter_time(f, node, context, a, b, b_log_time);
    warn_about_timing(k, e, a, b, b_log_time, warnings);
    events.push_back(e);
  }
  return events;
}

SwarmScenario build_scenario(const YAML::Node& root, const fs::path& yaml, const LogReadOptions& read) {
  const ScenarioFile f(yaml.string());
  f.check_keys(root, "", "a scenario", {"name", "config", "relations", "agents", "encounters"});

  SwarmScenario scenario;
  scenario.name = root["name"] ? f.text(root["name"], "", "name") : yaml.stem().string();
  if (const YAML::Node c = root["config"]) scenario.config = f.existing_file(c, "", "config").string();
  if (const YAML::Node r = root["relations"]) scenario.relations = f.existing_file(r, "", "relations").string();
  LoadedAgents agents = load_agents(f, root, read, scenario.warnings);
  scenario.events = load_encounters(f, root, agents, scenario.warnings);
  scenario.streams = std::move(agents.streams);
  return scenario;
}

}  // namespace

SwarmScenario load_swarm_scenario(const std::filesystem::path& yaml, const LogReadOptions& read) {
  std::error_code ec;
  if (!fs::is_regular_file(yaml, ec)) throw InputError(fmt::format("{}: scenario file not found", yaml.string()));
  return build_scenario(load_root(yaml, [&] { return YAML::LoadFile(yaml.string()); }), yaml, read);
}

SwarmScenario parse_swarm_scenario(const std::string& text, const std::filesystem::path& yaml,
                                   const LogReadOptions& read) {
  return build_scenario(load_root(yaml, [&] { return YAML::Load(text); }), yaml, read);
}

}  // namespace dsswarm
