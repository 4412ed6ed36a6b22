#include "eval/swarm_eval.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "common/errors.hpp"
#include "eval/metrics_json.hpp"
#include "eval/trajectory_lookup.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

// ------------------------------------------------------------ encounters.json

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

// ------------------------------------------------------------ scoring helpers

// The relation metric, or none when no relation has poses at both ends (the
// metric itself refuses that case with an error meant for a whole run).
std::optional<RelationMetrics> score(const Trajectory& trajectory, const std::vector<Relation>& relations,
                                     double max_time_diff) {
  if (relations.empty() || trajectory.empty()) return std::nullopt;
  const TimestampIndex index(trajectory, "swarm");
  const bool any = std::any_of(relations.begin(), relations.end(), [&](const Relation& r) {
    return index.nearest(r.t1, max_time_diff) && index.nearest(r.t2, max_time_diff);
  });
  if (!any) return std::nullopt;
  return evaluate_relations(trajectory, relations, max_time_diff);
}

Trajectory concatenate(const Trajectory& a, const Trajectory& b) {
  Trajectory out = a;
  out.insert(out.end(), b.begin(), b.end());
  return out;
}

std::string fixed(const std::optional<double>& v, int digits) {
  return v ? fmt::format("{:.{}f}", *v, digits) : std::string("-");
}

std::string metric_columns(const std::optional<RelationMetrics>& m) {
  if (!m) return fmt::format("{:>22} {:>22}", "-", "-");
  return fmt::format("{:>22} {:>22}", fmt::format("{:.4f} ± {:.4f}", m->trans_mean, m->trans_std),
                     fmt::format("{:.3f} ± {:.3f}", m->rot_mean_deg, m->rot_std_deg));
}

json pose_json(const Pose2& p) { return json::array({p.x, p.y, p.theta}); }

json optional_metrics(const std::optional<RelationMetrics>& m) { return m ? to_json(*m) : json(nullptr); }

std::string truth_text(const EncounterScore& e) {
  if (!e.truth) return "no relation";
  if (e.truth->hops == 0) return "same scan";
  if (e.truth->hops == 1) return "relation";
  return fmt::format("chain of {}", e.truth->hops);
}

struct EncounterSummary {
  std::size_t accepted = 0, scored = 0;
  double trans_mean = 0.0, trans_max = 0.0, rot_mean_deg = 0.0, rot_max_deg = 0.0;
};

EncounterSummary summarize(const std::vector<EncounterScore>& encounters) {
  EncounterSummary s;
  for (const EncounterScore& e : encounters) {
    if (!e.entry.accepted) continue;
    ++s.accepted;
    if (!e.scored()) continue;
    ++s.scored;
    s.trans_mean += e.trans_error;
    s.rot_mean_deg += e.rot_error_deg;
    s.trans_max = std::max(s.trans_max, e.trans_error);
    s.rot_max_deg = std::max(s.rot_max_deg, e.rot_error_deg);
  }
  if (s.scored > 0) {
    s.trans_mean /= static_cast<double>(s.scored);
    s.rot_mean_deg /= static_cast<double>(s.scored);
  }
  return s;
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

// ------------------------------------------------------------ relation graph

RelationGraph::RelationGraph(const std::vector<Relation>& relations, double max_time_diff)
    : relations_(relations), max_time_diff_(max_time_diff) {
  require_valid_max_time_diff(max_time_diff);
  std::vector<double> times;
  for (const Relation& r : relations_) {
    if (!std::isfinite(r.t1) || !std::isfinite(r.t2)) continue;
    times.push_back(r.t1);
    times.push_back(r.t2);
  }
  std::sort(times.begin(), times.end());
  // Endpoints within max_time_diff of the node's first time are the same scan.
  for (const double t : times)
    if (node_times_.empty() || t - node_times_.back() > max_time_diff_) node_times_.push_back(t);
  edges_.resize(node_times_.size());
  for (std::size_t i = 0; i < relations_.size(); ++i) {
    const auto n1 = node_at(relations_[i].t1);
    const auto n2 = node_at(relations_[i].t2);
    if (!n1 || !n2 || *n1 == *n2) continue;
    edges_[*n1].push_back({*n2, i, true});
    edges_[*n2].push_back({*n1, i, false});
  }
}

std::optional<std::size_t> RelationGraph::node_at(double t) const {
  if (node_times_.empty() || !std::isfinite(t)) return std::nullopt;
  // Nodes are the first time of their cluster, so a time belongs to the node at or just before it.
  const auto after = std::upper_bound(node_times_.begin(), node_times_.end(), t);
  std::optional<std::size_t> best;
  double best_diff = std::numeric_limits<double>::infinity();
  for (auto it : {after, after == node_times_.begin() ? after : std::prev(after)}) {
    if (it == node_times_.end()) continue;
    const double diff = std::abs(*it - t);
    if (diff <= max_time_diff_ && diff < best_diff) {
      best = static_cast<std::size_t>(it - node_times_.begin());
      best_diff = diff;
    }
  }
  return best;
}

std::optional<RelationGraph::Truth> RelationGraph::motion(double ta, double tb, std::size_t max_hops) const {
  if (!std::isfinite(ta) || !std::isfinite(tb)) return std::nullopt;
  if (std::abs(ta - tb) <= max_time_diff_) return Truth{Pose2(), 0};
  const auto from = node_at(ta);
  const auto to = node_at(tb);
  if (!from || !to || max_hops == 0) return std::nullopt;
  if (*from == *to) return Truth{Pose2(), 0};
  // Breadth-first: fewest relations; edges in file order keep the choice reproducible.
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> depth(node_times_.size(), kNone);
  std::vector<const Edge*> via(node_times_.size(), nullptr);
  std::vector<std::size_t> parent(node_times_.size(), kNone);
  std::deque<std::size_t> queue{*from};
  depth[*from] = 0;
  while (!queue.empty() && depth[*to] == kNone) {
    const std::size_t n = queue.front();
    queue.pop_front();
    if (depth[n] >= max_hops) continue;
    for (const Edge& e : edges_[n]) {
      if (depth[e.to] != kNone) continue;
      depth[e.to] = depth[n] + 1;
      via[e.to] = &e;
      parent[e.to] = n;
      queue.push_back(e.to);
    }
  }
  if (depth[*to] == kNone) return std::nullopt;
  std::vector<const Edge*> path;
  for (std::size_t n = *to; n != *from; n = parent[n]) path.push_back(via[n]);
  Pose2 m;
  for (auto it = path.rbegin(); it != path.rend(); ++it) {
    const Pose2& r = relations_[(*it)->relation].motion;
    m = m * ((*it)->forward ? r : r.inverse());
  }
  return Truth{m, path.size()};
}

std::vector<double> RelationGraph::endpoints_near(double t, double window) const {
  std::vector<double> out;
  if (!std::isfinite(t) || !(window >= 0.0)) return out;
  const auto lo = std::lower_bound(node_times_.begin(), node_times_.end(), t - window);
  const auto hi = std::upper_bound(node_times_.begin(), node_times_.end(), t + window);
  out.assign(lo, hi);
  std::stable_sort(out.begin(), out.end(), [t](double x, double y) { return std::abs(x - t) < std::abs(y - t); });
  return out;
}

// ------------------------------------------------------------ evaluation

namespace {

// The agent's own pose at the relation timestamp nearest to t (within the
// bridge) that the agent covers.
std::optional<StampedPose> bridge_pose(const RelationGraph& graph, const Trajectory& own, const TimestampIndex& index,
                                       double t, const SwarmEvalOptions& o) {
  for (const double candidate : graph.endpoints_near(t, o.bridge)) {
    if (const auto i = index.nearest(candidate, o.max_time_diff)) return StampedPose{candidate, own[*i].pose};
  }
  return std::nullopt;
}

std::size_t agent_named(const SwarmOutput& output, const std::string& name) {
  for (std::size_t i = 0; i < output.agents.size(); ++i)
    if (output.agents[i].name == name) return i;
  throw InputError(fmt::format("encounters: no agent named '{}' among the trajectories", name));
}

}  // namespace

SwarmEvaluation evaluate_swarm(const SwarmOutput& output, const std::vector<Relation>& relations,
                               const SwarmEvalOptions& options) {
  require_valid_max_time_diff(options.max_time_diff);
  if (!std::isfinite(options.bridge) || options.bridge < 0.0) {
    throw ConfigError(fmt::format("bridge must be a finite number of seconds >= 0, got {}", options.bridge));
  }
  const double dt = options.max_time_diff;
  SwarmEvaluation ev;
  ev.options = options;
  ev.relations_total = relations.size();
  const std::size_t n = output.agents.size();

  std::vector<TimestampIndex> own;
  own.reserve(n);
  for (const SwarmAgentOutput& a : output.agents) own.emplace_back(a.own, a.name);
  for (const SwarmAgentOutput& a : output.agents) {
    if (!a.joint) continue;
    [[maybe_unused]] const TimestampIndex check(*a.joint, a.name + " joint");  // refuses non-finite poses
  }

  // Who covers each end of each relation.
  std::vector<std::vector<Relation>> per_agent(n);
  std::map<std::pair<std::size_t, std::size_t>, std::vector<Relation>> cross;  // (x, y) with x < y
  for (const Relation& r : relations) {
    std::vector<std::size_t> at1, at2;
    for (std::size_t i = 0; i < n; ++i) {
      const bool c1 = own[i].nearest(r.t1, dt).has_value();
      const bool c2 = own[i].nearest(r.t2, dt).has_value();
      if (c1) at1.push_back(i);
      if (c2) at2.push_back(i);
      if (c1 && c2) per_agent[i].push_back(r);
    }
    if (at1.size() == 1 && at2.size() == 1 && at1[0] != at2[0]) {
      cross[{std::min(at1[0], at2[0]), std::max(at1[0], at2[0])}].push_back(r);
    }
  }

  for (std::size_t i = 0; i < n; ++i) {
    const SwarmAgentOutput& a = output.agents[i];
    AgentRelationScore s;
    s.name = a.name;
    s.poses = a.own.size();
    s.joint = a.joint.has_value();
    s.relations_covered = per_agent[i].size();
    s.metrics = score(a.own, per_agent[i], dt);
    ev.agents.push_back(std::move(s));
  }

  Trajectory all_joint;
  std::vector<Relation> all_cross;
  for (const auto& [pair, rels] : cross) {
    const SwarmAgentOutput& x = output.agents[pair.first];
    const SwarmAgentOutput& y = output.agents[pair.second];
    CrossAgentScore c;
    c.x = x.name;
    c.y = y.name;
    c.relations = rels.size();
    ev.cross_relations += rels.size();
    if (x.joint && y.joint) {
      c.metrics = score(concatenate(*x.joint, *y.joint), rels, dt);
      all_cross.insert(all_cross.end(), rels.begin(), rels.end());
    } else {
      c.without_joint = rels.size();
      ev.cross_without_joint += rels.size();
    }
    ev.pairs.push_back(std::move(c));
  }
  for (const SwarmAgentOutput& a : output.agents)
    if (a.joint) all_joint.insert(all_joint.end(), a.joint->begin(), a.joint->end());
  ev.cross = score(all_joint, all_cross, dt);

  const RelationGraph graph(relations, dt);
  for (std::size_t k = 0; k < output.encounters.size(); ++k) {
    EncounterScore s;
    s.index = k;
    s.entry = output.encounters[k];
    s.a_time = s.entry.a_log_time;
    s.b_time = s.entry.b_log_time;
    if (s.entry.transform) s.estimated_motion = s.entry.a_pose.inverse() * *s.entry.transform * s.entry.b_pose;
    s.truth = graph.motion(s.a_time, s.b_time, options.max_hops);
    if (!s.truth && options.bridge > 0.0) {
      const std::size_t ia = agent_named(output, s.entry.a), ib = agent_named(output, s.entry.b);
      const auto pa = bridge_pose(graph, output.agents[ia].own, own[ia], s.entry.a_log_time, options);
      const auto pb = bridge_pose(graph, output.agents[ib].own, own[ib], s.entry.b_log_time, options);
      if (pa && pb) {
        if (const auto truth = graph.motion(pa->timestamp, pb->timestamp, options.max_hops)) {
          s.truth = truth;
          s.a_time = pa->timestamp;
          s.b_time = pb->timestamp;
          if (s.entry.transform) s.estimated_motion = pa->pose.inverse() * *s.entry.transform * pb->pose;
        }
      }
    }
    if (s.scored()) {
      const Pose2 error = between(s.truth->motion, *s.estimated_motion);
      s.trans_error = std::hypot(error.x, error.y);
      s.rot_error_deg = std::abs(error.theta) * kRadToDeg;
    }
    ev.encounters.push_back(std::move(s));
  }
  return ev;
}

std::string format_swarm_evaluation(const SwarmEvaluation& ev) {
  std::string out = fmt::format(
      "swarm evaluation: {} agents, {} relations (relation metric of Kümmerle et al. 2009; max time difference "
      "{} s)\n\n",
      ev.agents.size(), ev.relations_total, ev.options.max_time_diff);

  out += "per agent, own frame (relations whose two timestamps the agent covers)\n";
  out += fmt::format("  {:<14} {:>7} {:>5} {:>9} {:>22} {:>22}\n", "agent", "poses", "joint", "relations",
                     "trans mean ± std (m)", "rot mean ± std (deg)");
  for (const AgentRelationScore& a : ev.agents) {
    out += fmt::format("  {:<14} {:>7} {:>5} {:>9} {}\n", a.name, a.poses, a.joint ? "yes" : "no",
                       a.relations_covered, metric_columns(a.metrics));
  }

  out += "\ncross-agent, joint frame (t1 covered by one agent only, t2 by another only)\n";
  out += fmt::format("  {:<24} {:>9} {:>9} {}\n", "agents", "relations", "no joint",
                     fmt::format("{:>22} {:>22}", "trans mean ± std (m)", "rot mean ± std (deg)"));
  for (const CrossAgentScore& c : ev.pairs) {
    out += fmt::format("  {:<24} {:>9} {:>9} {}\n", c.x + " ↔ " + c.y, c.relations, c.without_joint,
                       metric_columns(c.metrics));
  }
  out += fmt::format("  {:<24} {:>9} {:>9} {}\n", "all", ev.cross_relations, ev.cross_without_joint,
                     metric_columns(ev.cross));

  out += fmt::format(
      "\nencounters: relative pose of b w.r.t. a (pose_a⁻¹ ⊕ transform ⊕ pose_b) against relation truth "
      "(same scan, one relation, or a chain of at most {}; checked up to {} s from the exchanged scans when they "
      "are no relation's timestamps: 'shift')\n",
      ev.options.max_hops, ev.options.bridge);
  out += fmt::format("  {:>3} {:>9} {:<20} {:<31} {:<8} {:<12} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}  {}\n", "#",
                     "time (s)", "agents", "log times a, b", "accepted", "truth", "shift (s)", "err (m)", "err (deg)",
                     "match ms", "merge ms", "bytes", "reason");
  for (const EncounterScore& e : ev.encounters) {
    const double shift = std::max(std::abs(e.a_time - e.entry.a_log_time), std::abs(e.b_time - e.entry.b_log_time));
    out += fmt::format("  {:>3} {:>9.2f} {:<20} {:<31} {:<8} {:<12} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}  {}\n",
                       e.index, e.entry.time, e.entry.a + " → " + e.entry.b,
                       fmt::format("{:.3f}, {:.3f}", e.entry.a_log_time, e.entry.b_log_time),
                       e.entry.accepted ? "yes" : "no", truth_text(e),
                       fixed(e.truth && e.bridged() ? std::optional(shift) : std::nullopt, 2),
                       fixed(e.scored() ? std::optional(e.trans_error) : std::nullopt, 4),
                       fixed(e.scored() ? std::optional(e.rot_error_deg) : std::nullopt, 3),
                       fixed(e.entry.match_ms, 1), fixed(e.entry.merge_ms, 1), fixed(e.entry.bytes, 0),
                       e.entry.reason);
  }
  const EncounterSummary s = summarize(ev.encounters);
  out += fmt::format("  accepted {} of {}; scored against truth {}", s.accepted, ev.encounters.size(), s.scored);
  if (s.scored > 0) {
    out += fmt::format(": error mean {:.4f} m / {:.3f}°, worst {:.4f} m / {:.3f}°", s.trans_mean, s.rot_mean_deg,
                       s.trans_max, s.rot_max_deg);
  }
  out += "\n  (errors of rejected encounters are those of the candidate they turned down)\n";
  return out;
}

json to_json(const SwarmEvaluation& ev) {
  json agents = json::array();
  for (const AgentRelationScore& a : ev.agents) {
    agents.push_back({{"name", a.name},
                      {"poses", a.poses},
                      {"joint", a.joint},
                      {"relations_covered", a.relations_covered},
                      {"relations", optional_metrics(a.metrics)}});
  }
  json pairs = json::array();
  for (const CrossAgentScore& c : ev.pairs) {
    pairs.push_back({{"agents", {c.x, c.y}},
                     {"relations", c.relations},
                     {"without_joint", c.without_joint},
                     {"metrics", optional_metrics(c.metrics)}});
  }
  json encounters = json::array();
  for (const EncounterScore& e : ev.encounters) {
    json j = {{"index", e.index},
              {"time", e.entry.time},
              {"agents", {e.entry.a, e.entry.b}},
              {"log_times", {e.entry.a_log_time, e.entry.b_log_time}},
              {"accepted", e.entry.accepted},
              {"reason", e.entry.reason},
              {"truth", truth_text(e)},
              {"checked_at", {e.a_time, e.b_time}},
              {"bridged", e.truth && e.bridged()},
              {"hops", e.truth ? json(e.truth->hops) : json(nullptr)},
              {"true_motion", e.truth ? pose_json(e.truth->motion) : json(nullptr)},
              {"estimated_motion", e.estimated_motion ? pose_json(*e.estimated_motion) : json(nullptr)},
              {"trans_error", e.scored() ? json(e.trans_error) : json(nullptr)},
              {"rot_error_deg", e.scored() ? json(e.rot_error_deg) : json(nullptr)}};
    encounters.push_back(std::move(j));
  }
  const EncounterSummary s = summarize(ev.encounters);
  json summary = {{"total", ev.encounters.size()}, {"accepted", s.accepted}, {"scored", s.scored}};
  if (s.scored > 0) {
    summary["trans_mean"] = s.trans_mean;
    summary["trans_max"] = s.trans_max;
    summary["rot_mean_deg"] = s.rot_mean_deg;
    summary["rot_max_deg"] = s.rot_max_deg;
  }
  return {{"relations", ev.relations_total},
          {"max_time_diff", ev.options.max_time_diff},
          {"max_hops", ev.options.max_hops},
          {"bridge", ev.options.bridge},
          {"agents", agents},
          {"cross", {{"relations", ev.cross_relations},
                     {"without_joint", ev.cross_without_joint},
                     {"metrics", optional_metrics(ev.cross)},
                     {"pairs", pairs}}},
          {"encounters", encounters},
          {"encounter_summary", summary}};
}

}  // namespace dsswarm
