#include "agent/outcome_json.hpp"

#include "common/errors.hpp"

namespace dsswarm::agent {
namespace {

using nlohmann::json;
using OutcomeEnd = protocol::EncounterOutcome::End;

json pose(const Pose2& p) { return json::array({p.x, p.y, p.theta}); }
Pose2 pose(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

json hypothesis(const PoseHypothesis& h) {
  return {{"pose", pose(h.pose)},          {"score", h.score},
          {"surroundings_score", h.surroundings_score}, {"inlier_ratio", h.inlier_ratio},
          {"known_fraction", h.known_fraction}, {"same_side_ratio", h.same_side_ratio}};
}
PoseHypothesis hypothesis(const json& j) {
  return {pose(j.at("pose")), j.at("score").get<double>(), j.at("surroundings_score").get<double>(),
          j.at("inlier_ratio").get<double>(), j.at("known_fraction").get<double>(),
          j.at("same_side_ratio").get<double>()};
}

json located(const RelativePoseResult& r) {
  json j{{"best", hypothesis(r.best)}, {"evaluations", r.evaluations}};
  if (r.runner_up) j["runner_up"] = hypothesis(*r.runner_up);
  return j;
}
RelativePoseResult located(const json& j) {
  RelativePoseResult r;
  r.best = hypothesis(j.at("best"));
  r.evaluations = j.at("evaluations").get<int>();
  if (j.contains("runner_up")) r.runner_up = hypothesis(j.at("runner_up"));
  return r;
}

constexpr std::pair<OutcomeEnd, const char*> kEnds[] = {
    {OutcomeEnd::accepted, "accepted"}, {OutcomeEnd::rejected, "rejected"}, {OutcomeEnd::declined, "declined"}, {OutcomeEnd::abandoned, "abandoned"}};

}  // namespace

json to_json(const protocol::EncounterOutcome& o) {
  const char* end = "abandoned";
  for (const auto& [e, name] : kEnds)
    if (e == o.end) end = name;
  const EncounterEstimate& e = o.estimate;
  return {{"encounter", o.encounter},
          {"self", o.self},
          {"peer", o.peer},
          {"self_is_a", o.self_is_a},
          {"end", end},
          {"reason", o.reason},
          {"confirmed_by", o.confirmed_by},
          {"decided", o.decided},
          {"estimate",
           {{"accepted", e.accepted},
            {"reason", e.reason},
            {"b_frame_in_a", pose(e.b_frame_in_a)},
            {"b_frame_in_a_near", pose(e.b_frame_in_a_near)},
            {"a_locates_b", located(e.a_locates_b)},
            {"b_locates_a", located(e.b_locates_a)},
            {"disagreement", {e.disagreement_xy, e.disagreement_theta}},
            {"wide_moved", {e.wide_moved_xy, e.wide_moved_theta}},
            {"settled_by_wide_fit", e.settled_by_wide_fit}}},
          {"self_pose", pose(o.self_pose)},
          {"peer_pose", pose(o.peer_pose)},
          {"self_stamp", o.self_stamp},
          {"peer_stamp", o.peer_stamp},
          {"started", o.started},
          {"ended", o.ended},
          {"compute_ms", o.compute_ms},
          {"peer_compute_ms", o.peer_compute_ms},
          {"merge_ms", o.merge_ms},
          {"bytes_sent", o.bytes_sent},
          {"bytes_received", o.bytes_received},
          {"snapshot_bytes_sent", o.snapshot_bytes_sent},
          {"snapshot_bytes_received", o.snapshot_bytes_received},
          {"layers_received", o.layers_received}};
}

protocol::EncounterOutcome outcome_from_json(const json& j, const std::string& source) {
  try {
    protocol::EncounterOutcome o;
    o.encounter = j.at("encounter").get<std::uint64_t>();
    o.self = j.at("self").get<std::string>();
    o.peer = j.at("peer").get<std::string>();
    o.self_is_a = j.at("self_is_a").get<bool>();
    const std::string end = j.at("end").get<std::string>();
    bool known = false;
    for (const auto& [e, name] : kEnds)
      if (end == name) {
        o.end = e;
        known = true;
      }
    if (!known) throw InputError(source + ": unknown encounter end '" + end + "'");
    o.reason = j.at("reason").get<std::string>();
    o.confirmed_by = j.at("confirmed_by").get<std::string>();
    o.decided = j.at("decided").get<bool>();
    const json& e = j.at("estimate");
    o.estimate.accepted = e.at("accepted").get<bool>();
    o.estimate.reason = e.at("reason").get<std::string>();
    o.estimate.b_frame_in_a = pose(e.at("b_frame_in_a"));
    o.estimate.b_frame_in_a_near = pose(e.at("b_frame_in_a_near"));
    o.estimate.a_locates_b = located(e.at("a_locates_b"));
    o.estimate.b_locates_a = located(e.at("b_locates_a"));
    o.estimate.disagreement_xy = e.at("disagreement").at(0).get<double>();
    o.estimate.disagreement_theta = e.at("disagreement").at(1).get<double>();
    o.estimate.wide_moved_xy = e.at("wide_moved").at(0).get<double>();
    o.estimate.wide_moved_theta = e.at("wide_moved").at(1).get<double>();
    o.estimate.settled_by_wide_fit = e.value("settled_by_wide_fit", false);  // absent before 2026-12
    o.self_pose = pose(j.at("self_pose"));
    o.peer_pose = pose(j.at("peer_pose"));
    o.self_stamp = j.at("self_stamp").get<double>();
    o.peer_stamp = j.at("peer_stamp").get<double>();
    o.started = j.at("started").get<double>();
    o.ended = j.at("ended").get<double>();
    o.compute_ms = j.at("compute_ms").get<double>();
    o.peer_compute_ms = j.at("peer_compute_ms").get<double>();
    o.merge_ms = j.at("merge_ms").get<double>();
    o.bytes_sent = j.at("bytes_sent").get<std::size_t>();
    o.bytes_received = j.at("bytes_received").get<std::size_t>();
    o.snapshot_bytes_sent = j.at("snapshot_bytes_sent").get<std::size_t>();
    o.snapshot_bytes_received = j.at("snapshot_bytes_received").get<std::size_t>();
    o.layers_received = j.at("layers_received").get<std::size_t>();
    return o;
  } catch (const json::exception& e) {
    throw InputError(source + ": " + e.what());
  }
}

}  // namespace dsswarm::agent
