#include "apps/swarm_runner.hpp"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <unordered_set>

#include "apps/slam_runner.hpp"
#include "common/errors.hpp"
#include "config/config_json.hpp"
#include "eval/ate.hpp"
#include "io/atomic_file.hpp"
#include "io/maps/dsmap.hpp"
#include "io/maps/map_server.hpp"
#include "io/maps/render.hpp"

namespace dsswarm {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

nlohmann::json pose_json(const Pose2& p) { return nlohmann::json::array({p.x, p.y, p.theta}); }

Trajectory own_trajectory(const AgentTrack& t) {
  Trajectory out;
  out.reserve(t.steps.size());
  for (std::size_t i = 0; i < t.steps.size(); ++i) out.push_back({t.timestamps[i], t.steps[i].pose});
  return out;
}

// Pose of agent i's map frame in agent 0's frame, when agent 0 knows it.
std::optional<Pose2> frame_in_reference(const SwarmSession& s, std::size_t i) {
  if (i == 0) return Pose2{};
  const MapLayer* layer = s.agent(0).knowledge().find(s.agent(i).name());
  if (!layer) return std::nullopt;
  return layer->origin_in_holder;
}

// True pose at timestamp t (nearest scan) of a simulated agent.
Pose2 truth_at(const Trajectory& truth, double t) {
  const StampedPose* best = &truth.front();
  for (const StampedPose& p : truth)
    if (std::abs(p.timestamp - t) < std::abs(best->timestamp - t)) best = &p;
  return best->pose;
}

// How agent `track`'s map frame sat in the world at log time `until`: the
// least-squares alignment of its poses up to then (what its map held then;
// later drift cannot be held against an earlier encounter). Nullopt with
// fewer than 2 poses.
std::optional<Pose2> alignment_until(const AgentTrack& track, const Trajectory& truth, double until) {
  Trajectory so_far;
  for (std::size_t i = 0; i < track.steps.size() && track.timestamps[i] <= until; ++i)
    so_far.push_back({track.timestamps[i], track.steps[i].pose});
  if (so_far.size() < 2) return std::nullopt;
  return evaluate_ate(so_far, truth).alignment;
}

// Cells (on a 0.1 m world lattice) where `grid` holds evidence, placed in the
// world through `frame_in_world`.
std::unordered_set<std::int64_t> known_world_cells(const DsGrid& grid, const Pose2& frame_in_world) {
  constexpr double kCell = 0.1;
  constexpr float kKnown = 0.1f;
  std::unordered_set<std::int64_t> out;
  grid.for_each_tile([&](CellIndex origin, const DsMass* cells) {
    for (int i = 0; i < DsGrid::kTileCells; ++i) {
      if (cells[i].occupied + cells[i].free < kKnown) continue;
      const CellIndex c = DsGrid::tile_cell(origin, i);
      const Eigen::Vector2d w = frame_in_world * grid.cell_center(c);
      const auto x = static_cast<std::int64_t>(std::floor(w.x() / kCell));
      const auto y = static_cast<std::int64_t>(std::floor(w.y() / kCell));
      out.insert((x << 32) ^ (y & 0xffffffff));
    }
  });
  return out;
}

// Writes STEM.{yaml,pgm} (nothing for an empty map) and returns the raster.
GridRaster write_map_files(const std::filesystem::path& dir, const std::string& stem, const MultiResMap& map) {
  GridRaster raster = map.finest().to_raster();
  if (raster.width > 0) write_map_server(dir / (stem + ".yaml"), raster);
  return raster;
}

// `raster`: the first agent's merged map.
void draw_swarm_picture(const std::filesystem::path& path, const SwarmSession& s, const GridRaster& raster,
                        const std::vector<std::optional<Pose2>>& frames) {
  if (raster.width == 0) return;
  Image picture = render_map(raster, fitting_scale(raster));
  for (std::size_t i = 0; i < s.agents(); ++i) {
    if (!frames[i]) continue;
    std::vector<Eigen::Vector2d> pts;
    for (const SlamStep& step : s.track(i).steps) pts.push_back(*frames[i] * step.pose.translation());
    draw_polyline(picture, raster, pts, agent_colour(static_cast<int>(i)), 1);
    if (!pts.empty()) draw_marker(picture, raster, pts.front(), agent_colour(static_cast<int>(i)), 3);
  }
  // Encounters where agent 0's frame can place robot a: filled black when
  // accepted, red ring when rejected.
  for (const EncounterRecord& r : s.encounters()) {
    for (std::size_t i = 0; i < s.agents(); ++i) {
      if (s.agent(i).name() != r.a || !frames[i]) continue;
      const Eigen::Vector2d at = *frames[i] * r.a_pose_in_a.translation();
      if (r.accepted) {
        draw_marker(picture, raster, at, Rgb{0, 0, 0}, 5);
      } else {
        draw_marker(picture, raster, at, Rgb{220, 30, 30}, 5);
        draw_marker(picture, raster, at, Rgb{255, 255, 255}, 3);
      }
    }
  }
  write_png(path, picture);
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

nlohmann::json write_swarm_outputs(const std::filesystem::path& dir, const SwarmSession& s, double wall_seconds,
                                   const SwarmTruth* truth) {
  if (truth && truth->world_poses.size() != s.agents())
    throw ConfigError("swarm outputs: ground truth for " + std::to_string(truth->world_poses.size()) +
                      " agents, but the session has " + std::to_string(s.agents()));
  std::filesystem::create_directories(dir);
  std::vector<std::optional<Pose2>> frames;
  for (std::size_t i = 0; i < s.agents(); ++i) frames.push_back(frame_in_reference(s, i));

  // Per agent: trajectory, own and merged maps, and (simulated) accuracy.
  nlohmann::json agents = nlohmann::json::array();
  std::size_t total_scans = 0;
  std::unordered_set<std::int64_t> explored;  // by the whole swarm (simulation only)
  std::vector<std::unordered_set<std::int64_t>> known(s.agents());
  GridRaster first_merged;  // the first agent's merged map: swarm.png's background  // per agent, by its working map
  for (std::size_t i = 0; i < s.agents(); ++i) {
    const SwarmAgent& a = s.agent(i);
    const std::filesystem::path adir = dir / "agents" / a.name();
    std::filesystem::create_directories(adir);
    const Trajectory own = own_trajectory(s.track(i));
    write_tum(adir / "trajectory.tum", own);
    write_map_files(adir, "map", a.slam().own_map());
    GridRaster merged = write_map_files(adir, "merged_map", a.slam().map());
    if (merged.width > 0) {
      Image picture = render_map(merged, fitting_scale(merged));
      std::vector<Eigen::Vector2d> pts;
      for (const auto& p : own) pts.push_back(p.pose.translation());
      draw_polyline(picture, merged, pts, agent_colour(static_cast<int>(i)), 1);
      write_png(adir / "merged_map.png", picture);
    }
    if (i == 0) first_merged = std::move(merged);
    if (frames[i]) {
      Trajectory joint = own;
      for (auto& p : joint) p.pose = *frames[i] * p.pose;
      std::filesystem::create_directories(dir / "joint");
      write_tum(dir / "joint" / (a.name() + ".tum"), joint);
    }
    nlohmann::json j;
    j["name"] = a.name();
    j["scans"] = own.size();
    j["scans_matched"] = a.slam().scans_matched();
    j["scans_held"] = a.slam().scans_held();
    j["matches_rejected"] = a.slam().matches_rejected();
    j["recovery_searches"] = a.slam().recoveries();
    j["knows"] = nlohmann::json::array();
    for (const MapLayer& l : a.knowledge().layers())
      j["knows"].push_back({{"origin", l.origin}, {"version", l.version}, {"hops", l.hops},
                            {"origin_in_holder", pose_json(l.origin_in_holder)}});
    j["map_bytes"] = a.slam().map().memory_bytes() + (a.knowledge().size() > 0 ? a.slam().own_map().memory_bytes() : 0);
    j["in_joint_frame"] = frames[i].has_value();
    if (truth && !own.empty() && !truth->world_poses[i].empty()) {
      const Trajectory& t = truth->world_poses[i];
      write_tum(adir / "ground_truth.tum", t);
      j["ate_rmse"] = evaluate_ate(own, t).rmse;
      const Pose2 frame_in_world = truth_at(t, own.front().timestamp) * own.front().pose.inverse();
      auto own_cells = known_world_cells(a.slam().own_map().finest(), frame_in_world);
      explored.insert(own_cells.begin(), own_cells.end());
      known[i] = known_world_cells(a.slam().map().finest(), frame_in_world);
    }
    total_scans += own.size();
    agents.push_back(std::move(j));
  }
  if (truth) {
    for (std::size_t i = 0; i < s.agents(); ++i) {
      std::size_t covered = 0;
      for (std::int64_t c : explored) covered += known[i].count(c);
      agents[i]["coverage"] = explored.empty() ? 0.0 : static_cast<double>(covered) / static_cast<double>(explored.size());
    }
  }

  // Encounters.
  std::vector<Pose2> alignments;  // per agent: own map frame -> world, best fit of the whole trajectory
  if (truth)
    for (std::size_t i = 0; i < s.agents(); ++i)
      alignments.push_back(evaluate_ate(own_trajectory(s.track(i)), truth->world_poses[i]).alignment);
  nlohmann::json list = nlohmann::json::array();
  std::size_t accepted = 0;
  double match_ms = 0.0, merge_ms = 0.0, bytes = 0.0, worst_xy = 0.0, worst_theta = 0.0;
  double worst_causal_xy = 0.0, worst_causal_theta = 0.0;
  std::size_t wrong = 0;
  for (const EncounterRecord& r : s.encounters()) {
    nlohmann::json e;
    e["id"] = r.id;
    e["time"] = r.time;
    e["agents"] = {r.a, r.b};
    e["log_times"] = {r.a_log_time, r.b_log_time};
    e["poses"] = {pose_json(r.a_pose_in_a), pose_json(r.b_pose_in_b)};
    e["transform"] = pose_json(r.accepted ? r.b_frame_in_a : r.estimate.a_locates_b.best.pose * r.b_pose_in_b.inverse());
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
    if (truth) {
      std::size_t ia = 0, ib = 0;
      for (std::size_t i = 0; i < s.agents(); ++i) {
        if (s.agent(i).name() == r.a) ia = i;
        if (s.agent(i).name() == r.b) ib = i;
      }
      const Trajectory& ta = truth->world_poses[ia];
      const Trajectory& tb = truth->world_poses[ib];
      // Frames: each agent's map frame in the world, from its first pose.
      const Pose2 fa = truth_at(ta, s.track(ia).timestamps.front()) * s.track(ia).steps.front().pose.inverse();
      const Pose2 fb = truth_at(tb, s.track(ib).timestamps.front()) * s.track(ib).steps.front().pose.inverse();
      const Pose2 true_transform = fa.inverse() * fb;
      e["true_transform"] = pose_json(true_transform);
      const Pose2 est = r.accepted ? r.b_frame_in_a : r.estimate.a_locates_b.best.pose * r.b_pose_in_b.inverse();
      // Error of the transform where it is applied: B's map placed in A's
      // frame, compared at B's position. Three references for "true":
      //  frame_error:   the frames as they were at each robot's start;
      //  aligned_error: each map frame as its whole trajectory best fits the
      //                 truth (the ATE alignment) — drift averaged out;
      //  causal_error:  the same with each trajectory only up to the
      //                 encounter — the maps as they were when merged;
      //  error:         as each robot's current pose says (local truth).
      auto transform_error = [&](const Pose2& truth_transform) {
        const Pose2 d = between(truth_transform * r.b_pose_in_b, est * r.b_pose_in_b);
        return nlohmann::json::array({std::hypot(d.x, d.y), std::abs(normalize_angle(d.theta)) * kRadToDeg});
      };
      e["frame_error"] = transform_error(true_transform);
      e["aligned_error"] = transform_error(alignments[ia].inverse() * alignments[ib]);
      const auto ca = alignment_until(s.track(ia), ta, r.a_log_time);
      const auto cb = alignment_until(s.track(ib), tb, r.b_log_time);
      if (ca && cb) e["causal_error"] = transform_error(ca->inverse() * *cb);
      // Where the transform was measured: the relative pose of the two robots.
      const Pose2 true_rel = between(truth_at(ta, r.a_log_time), truth_at(tb, r.b_log_time));
      const Pose2 est_rel = r.a_pose_in_a.inverse() * est * r.b_pose_in_b;
      const Pose2 dr = between(true_rel, est_rel);
      const double exy = std::hypot(dr.x, dr.y), eth = std::abs(normalize_angle(dr.theta)) * kRadToDeg;
      e["error"] = {exy, eth};
      // The same split by direction: where each robot placed the other, against
      // the truth relative to its own pose estimate.
      const Pose2 pa = between(r.a_pose_in_a * true_rel, r.estimate.a_locates_b.best.pose);
      const Pose2 pb = between(r.b_pose_in_b * true_rel.inverse(), r.estimate.b_locates_a.best.pose);
      e["placement_errors"] = {{std::hypot(pa.x, pa.y), std::abs(normalize_angle(pa.theta)) * kRadToDeg},
                               {std::hypot(pb.x, pb.y), std::abs(normalize_angle(pb.theta)) * kRadToDeg}};
      if (r.accepted) {
        worst_xy = std::max(worst_xy, exy);
        worst_theta = std::max(worst_theta, eth);
        if (e.contains("causal_error")) {
          worst_causal_xy = std::max(worst_causal_xy, e["causal_error"][0].get<double>());
          worst_causal_theta = std::max(worst_causal_theta, e["causal_error"][1].get<double>());
        }
        // Wrong under every reference: a robot whose own SLAM slipped makes
        // one reference disagree even with a well-placed map, never both.
        const auto& al = e["aligned_error"];
        if ((exy > 0.3 || eth > 3.0) && (al[0].get<double>() > 0.3 || al[1].get<double>() > 3.0)) ++wrong;
      }
    }
    if (r.accepted) {
      ++accepted;
      merge_ms += r.merge_ms;
    }
    match_ms += r.match_ms;
    bytes += static_cast<double>(r.bytes);
    list.push_back(std::move(e));
  }
  write_file_atomically(dir / "encounters.json", nlohmann::json{{"encounters", list}}.dump(2) + "\n");
  draw_swarm_picture(dir / "swarm.png", s, first_merged, frames);

  nlohmann::json stats;
  stats["agents"] = agents;
  stats["scans"] = total_scans;
  stats["wall_seconds"] = wall_seconds;
  stats["scans_per_second"] = wall_seconds > 0 ? static_cast<double>(total_scans) / wall_seconds : 0.0;
  stats["encounters"] = s.encounters().size();
  stats["encounters_accepted"] = accepted;
  stats["encounter_events_skipped"] = s.events_skipped();
  const double n = static_cast<double>(std::max<std::size_t>(1, s.encounters().size()));
  stats["mean_match_ms"] = match_ms / n;
  stats["mean_merge_ms"] = accepted > 0 ? merge_ms / static_cast<double>(accepted) : 0.0;
  stats["mean_bytes"] = bytes / n;
  stats["peak_rss_bytes"] = peak_rss_bytes();
  stats["config"] = to_json(s.config());
  if (truth) {
    stats["worst_accepted_error"] = {worst_xy, worst_theta};
    stats["worst_accepted_causal_error"] = {worst_causal_xy, worst_causal_theta};
    stats["wrong_merges"] = wrong;
  }
  write_file_atomically(dir / "stats.json", stats.dump(2) + "\n");
  return stats;
}

}  // namespace dsswarm
