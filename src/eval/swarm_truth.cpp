#include "eval/swarm_truth.hpp"

#include <cmath>
#include <numbers>
#include <unordered_set>

#include "common/errors.hpp"
#include "eval/ate.hpp"

namespace dsswarm {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
// A merge off by more than this under every reference is wrong.
constexpr double kWrongMetres = 0.3, kWrongDegrees = 3.0;
// Coverage counts cells of a 10 cm world lattice where a map holds evidence.
constexpr double kCoverageCell = 0.1;
constexpr float kKnownMass = 0.1f;

// True pose at timestamp t (nearest scan) of a simulated agent.
Pose2 truth_at(const Trajectory& truth, double t) {
  const StampedPose* best = &truth.front();
  for (const StampedPose& p : truth)
    if (std::abs(p.timestamp - t) < std::abs(best->timestamp - t)) best = &p;
  return best->pose;
}

// How a trajectory's map frame sat in the world at log time `until`: the
// least-squares alignment of its poses up to then (later drift cannot be held
// against an earlier encounter). Nullopt with fewer than 2 poses.
std::optional<Pose2> alignment_until(const Trajectory& own, const Trajectory& truth, double until) {
  Trajectory so_far;
  for (const StampedPose& p : own) {
    if (p.timestamp > until) break;
    so_far.push_back(p);
  }
  if (so_far.size() < 2) return std::nullopt;
  return evaluate_ate(so_far, truth).alignment;
}

// Cells of the world lattice where `grid` holds evidence, placed through `frame_in_world`.
std::unordered_set<std::int64_t> known_world_cells(const DsGrid& grid, const Pose2& frame_in_world) {
  std::unordered_set<std::int64_t> out;
  grid.for_each_tile([&](CellIndex origin, const PackedMass* cells) {
    for (int i = 0; i < DsGrid::kTileCells; ++i) {
      const DsMass m = cells[i].mass();
      if (m.occupied + m.free < kKnownMass) continue;
      const Eigen::Vector2d w = frame_in_world * grid.cell_center(DsGrid::tile_cell(origin, i));
      const auto x = static_cast<std::int64_t>(std::floor(w.x() / kCoverageCell));
      const auto y = static_cast<std::int64_t>(std::floor(w.y() / kCoverageCell));
      out.insert((x << 32) ^ (y & 0xffffffff));
    }
  });
  return out;
}

ErrorPair error_of(const Pose2& truth, const Pose2& estimate) {
  const Pose2 d = between(truth, estimate);
  return {std::hypot(d.x, d.y), std::abs(normalize_angle(d.theta)) * kRadToDeg};
}

bool beyond(const ErrorPair& e) { return e.metres > kWrongMetres || e.degrees > kWrongDegrees; }

void check(const SwarmRunResult& run, const SwarmTruth& truth) {
  if (truth.world_poses.size() != run.agents.size())
    throw ConfigError("swarm evaluation: ground truth for " + std::to_string(truth.world_poses.size()) +
                      " agents, but the run has " + std::to_string(run.agents.size()));
}

}  // namespace

Pose2 record_transform(const EncounterRecord& r) {
  return r.accepted ? r.b_frame_in_a : r.estimate.a_locates_b.best.pose * r.b_pose_in_b.inverse();
}

std::vector<AgentTruthScore> score_agents(const SwarmRunResult& run, const SwarmTruth& truth) {
  check(run, truth);
  std::vector<AgentTruthScore> scores(run.agents.size());
  std::unordered_set<std::int64_t> explored;  // by the whole swarm
  std::vector<std::unordered_set<std::int64_t>> known(run.agents.size());
  for (std::size_t i = 0; i < run.agents.size(); ++i) {
    const SwarmAgentResult& a = run.agents[i];
    const Trajectory& t = truth.world_poses[i];
    if (a.trajectory.empty() || t.empty()) continue;
    scores[i].ate_rmse = evaluate_ate(a.trajectory, t).rmse;
    const Pose2 frame_in_world = truth_at(t, a.trajectory.front().timestamp) * a.trajectory.front().pose.inverse();
    if (a.own_map) {
      const auto own = known_world_cells(a.own_map->finest(), frame_in_world);
      explored.insert(own.begin(), own.end());
    }
    if (a.working_map) known[i] = known_world_cells(a.working_map->finest(), frame_in_world);
  }
  for (std::size_t i = 0; i < run.agents.size(); ++i) {
    std::size_t covered = 0;
    for (std::int64_t c : explored) covered += known[i].count(c);
    scores[i].coverage = explored.empty() ? 0.0 : static_cast<double>(covered) / static_cast<double>(explored.size());
  }
  return scores;
}

EncounterScorer::EncounterScorer(const SwarmRunResult& run, const SwarmTruth& truth) : run_(run), truth_(truth) {
  check(run, truth);
  for (std::size_t i = 0; i < run.agents.size(); ++i)
    alignments_.push_back(evaluate_ate(run.agents[i].trajectory, truth.world_poses[i]).alignment);
}

std::size_t EncounterScorer::index_of(const std::string& name) const {
  for (std::size_t i = 0; i < run_.agents.size(); ++i)
    if (run_.agents[i].name == name) return i;
  throw ConfigError("swarm evaluation: an encounter names agent " + name + ", which the run does not have");
}

EncounterTruthScore EncounterScorer::score(const EncounterRecord& r) const {
  const std::size_t ia = index_of(r.a), ib = index_of(r.b);
  const Trajectory& ta = truth_.world_poses[ia];
  const Trajectory& tb = truth_.world_poses[ib];
  const Trajectory& own_a = run_.agents[ia].trajectory;
  const Trajectory& own_b = run_.agents[ib].trajectory;
  EncounterTruthScore s;
  // Each map frame in the world, from its robot's first pose.
  const Pose2 fa = truth_at(ta, own_a.front().timestamp) * own_a.front().pose.inverse();
  const Pose2 fb = truth_at(tb, own_b.front().timestamp) * own_b.front().pose.inverse();
  s.true_transform = fa.inverse() * fb;
  const Pose2 est = record_transform(r);
  // B's map placed in A's frame, compared at B's position.
  auto transform_error = [&](const Pose2& truth) { return error_of(truth * r.b_pose_in_b, est * r.b_pose_in_b); };
  s.frame_error = transform_error(s.true_transform);
  s.aligned_error = transform_error(alignments_[ia].inverse() * alignments_[ib]);
  const auto ca = alignment_until(own_a, ta, r.a_log_time);
  const auto cb = alignment_until(own_b, tb, r.b_log_time);
  if (ca && cb) s.causal_error = transform_error(ca->inverse() * *cb);
  // Where the transform was measured: the relative pose of the two robots.
  const Pose2 true_rel = between(truth_at(ta, r.a_log_time), truth_at(tb, r.b_log_time));
  s.error = error_of(true_rel, r.a_pose_in_a.inverse() * est * r.b_pose_in_b);
  s.placement_a = error_of(r.a_pose_in_a * true_rel, r.estimate.a_locates_b.best.pose);
  s.placement_b = error_of(r.b_pose_in_b * true_rel.inverse(), r.estimate.b_locates_a.best.pose);
  // Wrong under every reference: a robot whose own SLAM slipped makes one
  // reference disagree even with a well-placed map, never both.
  s.wrong = r.accepted && beyond(s.error) && beyond(s.aligned_error);
  return s;
}

nlohmann::json to_json(const EncounterTruthScore& s) {
  auto pair = [](const ErrorPair& e) { return nlohmann::json::array({e.metres, e.degrees}); };
  nlohmann::json j;
  j["true_transform"] = {s.true_transform.x, s.true_transform.y, s.true_transform.theta};
  j["frame_error"] = pair(s.frame_error);
  j["aligned_error"] = pair(s.aligned_error);
  if (s.causal_error) j["causal_error"] = pair(*s.causal_error);
  j["error"] = pair(s.error);
  j["placement_errors"] = {pair(s.placement_a), pair(s.placement_b)};
  return j;
}

}  // namespace dsswarm
