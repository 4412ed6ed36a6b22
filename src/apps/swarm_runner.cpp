#include "apps/swarm_runner.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "apps/stale_outputs.hpp"
#include "apps/swarm_picture.hpp"
#include "common/process_usage.hpp"
#include "config/config_json.hpp"
#include "eval/swarm_truth.hpp"
#include "io/atomic_file.hpp"
#include "io/maps/annotate.hpp"
#include "io/maps/map_server.hpp"
#include "io/maps/render.hpp"

namespace dsswarm {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

nlohmann::json pose_json(const Pose2& p) { return nlohmann::json::array({p.x, p.y, p.theta}); }

// Pose of agent i's map frame in agent 0's frame, when agent 0 knows it.
std::optional<Pose2> frame_in_reference(const SwarmRunResult& run, std::size_t i) {
  if (i == 0) return Pose2{};
  const MapLayer* l = run.agents.front().held(run.agents[i].name);
  return l ? std::optional<Pose2>(l->origin_in_holder) : std::nullopt;
}

// Adds STEM.{yaml,pgm} (nothing for an empty map) and returns the raster.
GridRaster add_map_files(OutputFiles& files, const std::filesystem::path& dir, const std::string& stem,
                         const MultiResMap& map) {
  GridRaster raster = map.finest().to_raster();
  if (raster.width > 0) add_map_server(files, dir / (stem + ".yaml"), raster);
  return raster;
}

void add_agent_files(OutputFiles& files, const std::filesystem::path& adir, const SwarmAgentResult& a, int colour) {
  files.add(adir / "trajectory.tum", format_tum(adir / "trajectory.tum", a.trajectory));
  add_map_files(files, adir, "map", *a.own_map);
  const GridRaster merged = add_map_files(files, adir, "merged_map", *a.working_map);
  if (merged.width == 0) return;
  Image picture = render_map(merged, fitting_scale(merged));
  std::vector<Eigen::Vector2d> pts;
  for (const auto& p : a.trajectory) pts.push_back(p.pose.translation());
  draw_path(picture, merged, pts, agent_colour(colour));
  picture = with_legend(picture, merged.resolution * merged.width / picture.width,
                        {{a.name, agent_colour(colour), LegendEntry::Mark::Line}});
  files.add(adir / "merged_map.png", encode_png(adir / "merged_map.png", picture));
}

nlohmann::json agent_entry(const SwarmAgentResult& a, bool in_joint_frame) {
  nlohmann::json j = a.counters;
  j["name"] = a.name;
  j["scans"] = a.trajectory.size();
  j["knows"] = nlohmann::json::array();
  for (const MapLayer& l : a.knows)
    j["knows"].push_back({{"origin", l.origin}, {"version", l.version}, {"hops", l.hops},
                          {"origin_in_holder", pose_json(l.origin_in_holder)}});
  j["map_bytes"] = a.working_map->memory_bytes() + (a.knows.empty() ? 0 : a.own_map->memory_bytes());
  j["in_joint_frame"] = in_joint_frame;
  return j;
}

nlohmann::json encounter_entry(const EncounterRecord& r) {
  nlohmann::json e;
  e["id"] = r.id;
  e["time"] = r.time;
  e["agents"] = {r.a, r.b};
  e["log_times"] = {r.a_log_time, r.b_log_time};
  e["poses"] = {pose_json(r.a_pose_in_a), pose_json(r.b_pose_in_b)};
  e["transform"] = pose_json(record_transform(r));
  // Before the wide refinement (same as `transform` when it did not apply).
  if (r.estimate.accepted) e["transform_near"] = pose_json(r.estimate.b_frame_in_a_near);
  e["accepted"] = r.accepted;
  e["reason"] = r.reason;
  e["confirmed_by"] = r.confirmed_by;
  e["match_ms"] = r.match_ms;
  e["merge_ms"] = r.merge_ms;
  e["bytes"] = r.bytes;
  e["snapshot_bytes"] = r.snapshot_bytes;
  e["disagreement"] = {r.estimate.disagreement_xy, r.estimate.disagreement_theta * kRadToDeg};
  e["wide_moved"] = {r.estimate.wide_moved_xy, r.estimate.wide_moved_theta * kRadToDeg};
  e["settled_by_wide_fit"] = r.estimate.settled_by_wide_fit;
  // Each side's placement of the other robot in its own map.
  e["placements"] = {pose_json(r.estimate.a_locates_b.best.pose), pose_json(r.estimate.b_locates_a.best.pose)};
  e["scores"] = {r.estimate.a_locates_b.best.score, r.estimate.b_locates_a.best.score};
  e["same_side"] = {r.estimate.a_locates_b.best.same_side_ratio, r.estimate.b_locates_a.best.same_side_ratio};
  // How clearly each placement beat its best alternative (runner-up / best surroundings score).
  auto runner_up = [](const RelativePoseResult& p) {
    return p.runner_up && p.best.surroundings_score > 0.0 ? p.runner_up->surroundings_score / p.best.surroundings_score
                                                          : 0.0;
  };
  e["runner_up_ratio"] = {runner_up(r.estimate.a_locates_b), runner_up(r.estimate.b_locates_a)};
  e["known_fraction"] = {r.estimate.a_locates_b.best.known_fraction, r.estimate.b_locates_a.best.known_fraction};
  return e;
}

// The run's totals; with truth, the worst accepted errors and the wrong merges.
nlohmann::json summary(const SwarmRunResult& run, const std::vector<EncounterTruthScore>& scores, bool scored) {
  nlohmann::json stats;
  std::size_t accepted = 0, wrong = 0;
  double match_ms = 0.0, merge_ms = 0.0, bytes = 0.0;
  ErrorPair worst, worst_causal;
  for (std::size_t k = 0; k < run.encounters.size(); ++k) {
    const EncounterRecord& r = run.encounters[k];
    match_ms += r.match_ms;
    bytes += static_cast<double>(r.bytes);
    if (!r.accepted) continue;
    ++accepted;
    merge_ms += r.merge_ms;
    if (!scored) continue;
    const EncounterTruthScore& s = scores[k];
    worst = {std::max(worst.metres, s.error.metres), std::max(worst.degrees, s.error.degrees)};
    if (s.causal_error)
      worst_causal = {std::max(worst_causal.metres, s.causal_error->metres),
                      std::max(worst_causal.degrees, s.causal_error->degrees)};
    wrong += s.wrong ? 1 : 0;
  }
  stats["encounters"] = run.encounters.size();
  stats["encounters_accepted"] = accepted;
  stats["encounter_events_skipped"] = run.events_skipped;
  const double n = static_cast<double>(std::max<std::size_t>(1, run.encounters.size()));
  stats["mean_match_ms"] = match_ms / n;
  stats["mean_merge_ms"] = accepted > 0 ? merge_ms / static_cast<double>(accepted) : 0.0;
  stats["mean_bytes"] = bytes / n;
  stats["moved_messages"] = run.moved_messages;
  stats["moved_bytes"] = run.moved_bytes;
  if (scored) {
    stats["worst_accepted_error"] = {worst.metres, worst.degrees};
    stats["worst_accepted_causal_error"] = {worst_causal.metres, worst_causal.degrees};
    stats["wrong_merges"] = wrong;
  }
  return stats;
}

// Each robot's files (its own, unless the robot process wrote them; its
// trajectory in the joint frame; the truth) and its entry in stats.json.
nlohmann::json add_agents(OutputFiles& files, const std::filesystem::path& dir, const SwarmRunResult& run,
                          const std::vector<std::optional<Pose2>>& frames, const SwarmTruth* truth,
                          bool agent_files) {
  const std::vector<AgentTruthScore> agent_scores = truth ? score_agents(run, *truth) : std::vector<AgentTruthScore>{};
  nlohmann::json agents = nlohmann::json::array();
  for (std::size_t i = 0; i < run.agents.size(); ++i) {
    const SwarmAgentResult& a = run.agents[i];
    const std::filesystem::path adir = dir / "agents" / a.name;
    if (agent_files) add_agent_files(files, adir, a, static_cast<int>(i));
    if (frames[i]) {
      Trajectory joint = a.trajectory;
      for (auto& p : joint) p.pose = *frames[i] * p.pose;
      const std::filesystem::path path = dir / "joint" / (a.name + ".tum");
      files.add(path, format_tum(path, joint));
    }
    nlohmann::json j = agent_entry(a, frames[i].has_value());
    if (truth && !a.trajectory.empty() && !truth->world_poses[i].empty()) {
      files.add(adir / "ground_truth.tum", format_tum(adir / "ground_truth.tum", truth->world_poses[i]));
      j["ate_rmse"] = agent_scores[i].ate_rmse;
      j["coverage"] = agent_scores[i].coverage;
    }
    agents.push_back(std::move(j));
  }
  return agents;
}

// encounters.json, each scored against the truth when there is one: the scores.
std::vector<EncounterTruthScore> add_encounters(OutputFiles& files, const std::filesystem::path& dir,
                                                const SwarmRunResult& run, const SwarmTruth* truth) {
  std::vector<EncounterTruthScore> scores;
  if (truth) {
    const EncounterScorer scorer(run, *truth);
    for (const EncounterRecord& r : run.encounters) scores.push_back(scorer.score(r));
  }
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t k = 0; k < run.encounters.size(); ++k) {
    nlohmann::json e = encounter_entry(run.encounters[k]);
    if (truth) e.update(to_json(scores[k]));
    list.push_back(std::move(e));
  }
  files.add(dir / "encounters.json", nlohmann::json{{"encounters", list}}.dump(2) + "\n");
  return scores;
}

}  // namespace

double run_swarm_session(SwarmSession& session, const std::string& label) {
  const auto start = Clock::now();
  auto next_report = start + std::chrono::seconds(2);
  session.run([&](std::size_t done, std::size_t total) {
    if (label.empty() || Clock::now() < next_report || done == total) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const double rate = static_cast<double>(done) / elapsed;
    fmt::print(stderr, "[{}] {}/{} scans ({:.0f}%), {} encounters, about {:.0f} s left\n", label, done, total,
               100.0 * static_cast<double>(done) / static_cast<double>(total), session.encounters().size(),
               static_cast<double>(total - done) / rate);
    next_report = Clock::now() + std::chrono::seconds(2);
  });
  return std::chrono::duration<double>(Clock::now() - start).count();
}

SwarmRunResult run_result(const SwarmSession& s) {
  SwarmRunResult run;
  run.encounters = s.encounters();
  run.events_skipped = s.events_skipped();
  run.moved_messages = s.moved_messages();
  run.moved_bytes = s.moved_bytes();
  run.config = s.config();
  auto shared = [](const MultiResMap& m) { return std::shared_ptr<const MultiResMap>(&m, [](const MultiResMap*) {}); };
  for (std::size_t i = 0; i < s.agents(); ++i) {
    const SwarmAgent& a = s.agent(i);
    SwarmAgentResult r;
    r.name = a.name();
    const AgentTrack& t = s.track(i);
    for (std::size_t k = 0; k < t.steps.size(); ++k) r.trajectory.push_back({t.timestamps[k], t.steps[k].pose});
    r.map_versions = t.map_versions;
    r.own_map = shared(a.slam().own_map());
    r.working_map = shared(a.slam().map());
    r.knows = a.knowledge().layers();
    for (const auto& [name, count] : a.slam().scan_counters()) r.counters[name] = count;
    for (const auto& [name, count] : a.loop_counters()) r.counters[name] = count;
    run.agents.push_back(std::move(r));
  }
  return run;
}

nlohmann::json write_swarm_outputs(const std::filesystem::path& dir, const SwarmRunResult& run,
                                   const SwarmOutputOptions& options) {
  const SwarmTruth* truth = options.truth;
  std::vector<std::filesystem::path> previous = previous_swarm_outputs(dir);
  if (!options.agent_files)  // the robots' own files stay
    std::erase_if(previous, [&](const std::filesystem::path& p) {
      return std::any_of(run.agents.begin(), run.agents.end(),
                         [&](const SwarmAgentResult& a) { return p.parent_path() == dir / "agents" / a.name; });
    });
  OutputFiles files;
  std::vector<std::optional<Pose2>> frames;
  for (std::size_t i = 0; i < run.agents.size(); ++i) frames.push_back(frame_in_reference(run, i));
  nlohmann::json agents = add_agents(files, dir, run, frames, truth, options.agent_files);
  std::size_t total_scans = 0;
  for (const SwarmAgentResult& a : run.agents) total_scans += a.trajectory.size();
  const std::vector<EncounterTruthScore> scores = add_encounters(files, dir, run, truth);
  if (!run.agents.empty()) {
    const GridRaster first_merged = run.agents.front().working_map->finest().to_raster();
    if (first_merged.width > 0)
      files.add(dir / "swarm.png", encode_png(dir / "swarm.png", swarm_picture(run, first_merged, frames)));
  }

  nlohmann::json stats = summary(run, scores, truth != nullptr);
  stats["agents"] = agents;
  stats["scans"] = total_scans;
  stats["wall_seconds"] = options.wall_seconds;
  stats["scans_per_second"] =
      options.wall_seconds > 0 ? static_cast<double>(total_scans) / options.wall_seconds : 0.0;
  stats["peak_rss_bytes"] = peak_rss_bytes();
  stats["config"] = to_json(run.config);
  files.add(dir / "stats.json", stats.dump(2) + "\n");
  files.write_all();
  remove_stale_outputs(dir, previous, files);
  return stats;
}

}  // namespace dsswarm
