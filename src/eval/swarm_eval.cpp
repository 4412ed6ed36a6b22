#include "eval/swarm_eval.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "common/errors.hpp"
#include "eval/cross_frame.hpp"
#include "eval/metrics_json.hpp"
#include "eval/trajectory_lookup.hpp"

namespace dsswarm {
namespace {

using nlohmann::json;

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

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

// ------------------------------------------------------------ evaluation

namespace {

// The agent's pose at the relation timestamp nearest to t (within the
// bridge) that it covers, as its map stood at the encounter: `then`, its pose
// at t then, moved by its final trajectory's motion from t to that timestamp.
// Its final pose there would carry every later loop closure's correction,
// against a transform found before them. When t itself is not in the
// trajectory, its final pose there.
std::optional<StampedPose> bridge_pose(const RelationGraph& graph, const Trajectory& own, const TimestampIndex& index,
                                       double t, const Pose2& then, const SwarmEvalOptions& o) {
  const std::optional<std::size_t> at_t = index.nearest(t, o.max_time_diff);
  for (const double candidate : graph.endpoints_near(t, o.bridge)) {
    if (const auto i = index.nearest(candidate, o.max_time_diff))
      return StampedPose{candidate, at_t ? then * between(own[*at_t].pose, own[*i].pose) : own[*i].pose};
  }
  return std::nullopt;
}

std::size_t agent_named(const SwarmOutput& output, const std::string& name) {
  for (std::size_t i = 0; i < output.agents.size(); ++i)
    if (output.agents[i].name == name) return i;
  throw InputError(fmt::format("encounters: no agent named '{}' among the trajectories", name));
}

// Which relations each agent covers at both ends, and which link two agents
// (t1 covered by one only, t2 by another only), by pair (x, y) with x < y.
struct Coverage {
  std::vector<std::vector<Relation>> per_agent;
  std::map<std::pair<std::size_t, std::size_t>, std::vector<Relation>> cross;
};

Coverage cover(const std::vector<TimestampIndex>& own, const std::vector<Relation>& relations, double dt) {
  Coverage c;
  c.per_agent.resize(own.size());
  for (const Relation& r : relations) {
    std::vector<std::size_t> at1, at2;
    for (std::size_t i = 0; i < own.size(); ++i) {
      const bool c1 = own[i].nearest(r.t1, dt).has_value();
      const bool c2 = own[i].nearest(r.t2, dt).has_value();
      if (c1) at1.push_back(i);
      if (c2) at2.push_back(i);
      if (c1 && c2) c.per_agent[i].push_back(r);
    }
    if (at1.size() == 1 && at2.size() == 1 && at1[0] != at2[0])
      c.cross[{std::min(at1[0], at2[0]), std::max(at1[0], at2[0])}].push_back(r);
  }
  return c;
}

CrossAgentScore score_pair(const SwarmAgentOutput& x, const SwarmAgentOutput& y, const std::vector<Relation>& rels,
                           double dt) {
  CrossAgentScore c;
  c.x = x.name;
  c.y = y.name;
  c.relations = rels.size();
  if (x.joint && y.joint) {
    c.metrics = score(concatenate(*x.joint, *y.joint), rels, dt);
  } else {
    c.without_joint = rels.size();
  }
  if ((c.hindsight_frame = fit_cross_frame(x.own, y.own, rels, dt))) {
    Trajectory placed = y.own;
    for (StampedPose& p : placed) p.pose = *c.hindsight_frame * p.pose;
    c.hindsight = score(concatenate(x.own, placed), rels, dt);
  }
  return c;
}

void score_cross(const SwarmOutput& output, const Coverage& coverage, double dt, SwarmEvaluation& ev) {
  Trajectory all_joint;
  std::vector<Relation> all_cross;
  for (const auto& [pair, rels] : coverage.cross) {
    CrossAgentScore c = score_pair(output.agents[pair.first], output.agents[pair.second], rels, dt);
    ev.cross_relations += c.relations;
    ev.cross_without_joint += c.without_joint;
    if (c.without_joint == 0) all_cross.insert(all_cross.end(), rels.begin(), rels.end());
    ev.pairs.push_back(std::move(c));
  }
  for (const SwarmAgentOutput& a : output.agents)
    if (a.joint) all_joint.insert(all_joint.end(), a.joint->begin(), a.joint->end());
  ev.cross = score(all_joint, all_cross, dt);
}

EncounterScore score_encounter(const SwarmOutput& output, std::size_t k, const RelationGraph& graph,
                               const std::vector<TimestampIndex>& own, const SwarmEvalOptions& options) {
  EncounterScore s;
  s.index = k;
  s.entry = output.encounters[k];
  s.a_time = s.entry.a_log_time;
  s.b_time = s.entry.b_log_time;
  if (s.entry.transform) s.estimated_motion = s.entry.a_pose.inverse() * *s.entry.transform * s.entry.b_pose;
  s.truth = graph.motion(s.a_time, s.b_time, options.max_hops);
  if (!s.truth && options.bridge > 0.0) {
    const std::size_t ia = agent_named(output, s.entry.a), ib = agent_named(output, s.entry.b);
    const auto pa = bridge_pose(graph, output.agents[ia].own, own[ia], s.entry.a_log_time, s.entry.a_pose, options);
    const auto pb = bridge_pose(graph, output.agents[ib].own, own[ib], s.entry.b_log_time, s.entry.b_pose, options);
    const auto truth = pa && pb ? graph.motion(pa->timestamp, pb->timestamp, options.max_hops) : std::nullopt;
    if (truth) {
      s.truth = truth;
      s.a_time = pa->timestamp;
      s.b_time = pb->timestamp;
      if (s.entry.transform) s.estimated_motion = pa->pose.inverse() * *s.entry.transform * pb->pose;
    }
  }
  if (s.scored()) {
    const Pose2 error = between(s.truth->motion, *s.estimated_motion);
    s.trans_error = std::hypot(error.x, error.y);
    s.rot_error_deg = std::abs(error.theta) * kRadToDeg;
  }
  return s;
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

  std::vector<TimestampIndex> own;
  own.reserve(output.agents.size());
  for (const SwarmAgentOutput& a : output.agents) own.emplace_back(a.own, a.name);
  for (const SwarmAgentOutput& a : output.agents) {
    if (!a.joint) continue;
    [[maybe_unused]] const TimestampIndex check(*a.joint, a.name + " joint");  // refuses non-finite poses
  }

  const Coverage coverage = cover(own, relations, dt);
  for (std::size_t i = 0; i < output.agents.size(); ++i) {
    const SwarmAgentOutput& a = output.agents[i];
    ev.agents.push_back({a.name, a.own.size(), a.joint.has_value(), coverage.per_agent[i].size(),
                         score(a.own, coverage.per_agent[i], dt)});
  }
  score_cross(output, coverage, dt, ev);

  const RelationGraph graph(relations, dt);
  for (std::size_t k = 0; k < output.encounters.size(); ++k)
    ev.encounters.push_back(score_encounter(output, k, graph, own, options));
  return ev;
}

namespace {

std::string agents_table(const SwarmEvaluation& ev) {
  std::string out = "per agent, own frame (relations whose two timestamps the agent covers)\n";
  out += fmt::format("  {:<14} {:>7} {:>5} {:>9} {:>22} {:>22}\n", "agent", "poses", "joint", "relations",
                     "trans mean ± std (m)", "rot mean ± std (deg)");
  for (const AgentRelationScore& a : ev.agents) {
    out += fmt::format("  {:<14} {:>7} {:>5} {:>9} {}\n", a.name, a.poses, a.joint ? "yes" : "no",
                       a.relations_covered, metric_columns(a.metrics));
  }
  return out;
}

std::string cross_table(const SwarmEvaluation& ev) {
  std::string out = "\ncross-agent, joint frame (t1 covered by one agent only, t2 by another only)\n";
  out += fmt::format("  {:<24} {:>9} {:>9} {}  {:>22}\n", "agents", "relations", "no joint",
                     fmt::format("{:>22} {:>22}", "trans mean ± std (m)", "rot mean ± std (deg)"),
                     "best frame: trans (m)");
  for (const CrossAgentScore& c : ev.pairs) {
    out += fmt::format("  {:<24} {:>9} {:>9} {}  {:>22}\n", c.x + " ↔ " + c.y, c.relations, c.without_joint,
                       metric_columns(c.metrics),
                       c.hindsight ? fmt::format("{:.4f} ± {:.4f}", c.hindsight->trans_mean, c.hindsight->trans_std)
                                   : std::string("-"));
  }
  out += fmt::format("  {:<24} {:>9} {:>9} {}\n", "all", ev.cross_relations, ev.cross_without_joint,
                     metric_columns(ev.cross));
  out += "  (best frame: each pair's frame fitted to its cross relations in hindsight; what remains there comes from\n"
         "   the agents' own trajectories, their own error and their maps' disagreement, which no frame removes)\n";
  return out;
}

std::string encounters_table(const SwarmEvaluation& ev) {
  std::string out = fmt::format(
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

}  // namespace

std::string format_swarm_evaluation(const SwarmEvaluation& ev) {
  return fmt::format(
             "swarm evaluation: {} agents, {} relations (relation metric of Kümmerle et al. 2009; max time "
             "difference {} s)\n\n",
             ev.agents.size(), ev.relations_total, ev.options.max_time_diff) +
         agents_table(ev) + cross_table(ev) + encounters_table(ev);
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
                     {"metrics", optional_metrics(c.metrics)},
                     {"hindsight_frame", c.hindsight_frame ? pose_json(*c.hindsight_frame) : json(nullptr)},
                     {"hindsight_metrics", optional_metrics(c.hindsight)}});
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
