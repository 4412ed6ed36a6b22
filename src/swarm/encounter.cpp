#include "swarm/encounter.hpp"

#include <cmath>
#include <numbers>
#include <fmt/format.h>

#include "common/errors.hpp"

namespace dsswarm {

void EncounterConfig::validate() const {
  locate.validate();
  auto unit = [](double v) { return v >= 0.0 && v <= 1.0; };
  if (!unit(min_known_fraction)) throw ConfigError("encounter.min_known_fraction must be in [0, 1]");
  if (!unit(min_inlier_ratio)) throw ConfigError("encounter.min_inlier_ratio must be in [0, 1]");
  if (!unit(min_same_side)) throw ConfigError("encounter.min_same_side must be in [0, 1]");
  if (!unit(max_runner_up_ratio)) throw ConfigError("encounter.max_runner_up_ratio must be in [0, 1]");
  if (!(agree_xy > 0.0) || !(agree_theta > 0.0)) throw ConfigError("encounter.agree_xy and agree_theta must be > 0");
}

namespace {

// Why a placement cannot be trusted, or "" when it can. `who` sees `whom`.
std::string placement_problem(const RelativePoseResult& r, const EncounterConfig& config, const char* who,
                              const char* whom) {
  const PoseHypothesis& best = r.best;
  if (best.known_fraction < config.min_known_fraction)
    return fmt::format("{}: too little of {}'s scan falls on its map (known {:.2f} < {:.2f})", who, whom,
                       best.known_fraction, config.min_known_fraction);
  if (best.inlier_ratio < config.min_inlier_ratio)
    return fmt::format("{}: {}'s scan fits its map poorly (inliers {:.2f} < {:.2f})", who, whom, best.inlier_ratio,
                       config.min_inlier_ratio);
  if (best.same_side_ratio < config.min_same_side)
    return fmt::format("{}: {}'s scan meets its walls from the other side ({:.2f} < {:.2f} seen from the same side)",
                       who, whom, best.same_side_ratio, config.min_same_side);
  if (r.runner_up && r.runner_up->surroundings_score > config.max_runner_up_ratio * best.surroundings_score) {
    const Pose2 d = between(best.pose, r.runner_up->pose);
    return fmt::format("{}: ambiguous: another placement of {} {:.2f} m / {:.0f}° away scores {:.2f} of the best",
                       who, whom, std::hypot(d.x, d.y), std::abs(d.theta) * 180.0 / std::numbers::pi,
                       r.runner_up->surroundings_score / std::max(best.surroundings_score, 1e-9));
  }
  return "";
}

// How far apart two estimates of B's pose are, and whether that is beyond
// what the two directions may disagree by.
struct Apart {
  double xy = 0.0, theta = 0.0;  // m, rad
};
Apart apart(const Pose2& x, const Pose2& y) {
  return {std::hypot(x.x - y.x, x.y - y.y), std::abs(normalize_angle(x.theta - y.theta))};
}
bool beyond(const Apart& d, const EncounterConfig& config) {
  return d.xy > config.agree_xy || d.theta > config.agree_theta;
}

}  // namespace

PeerPlacement locate_peer(const EncounterView& self, const EncounterView& peer, const EncounterConfig& config,
                          std::uint64_t seed) {
  config.validate();
  if (!self.map) throw ConfigError("locate_peer: this robot's view needs its map");
  PeerPlacement p;
  p.located = locate_scan(*self.map, peer.points, self.pose.translation(), config.locate, seed, peer.surroundings);
  if (self.recent_map) {
    // Kept when this side trusts it and the peer's surroundings fit it
    // better: the recent submaps hold less, so they win only where the
    // composed map disagrees with itself.
    RelativePoseResult recent = locate_scan(*self.recent_map, peer.points, self.pose.translation(), config.locate,
                                            seed + 3, peer.surroundings);
    const bool trusted = placement_problem(recent, config, "", "").empty();
    if (trusted && (!placement_problem(p.located, config, "", "").empty() ||
                    recent.best.surroundings_score > p.located.best.surroundings_score))
      p.located = std::move(recent);
  }
  p.valid = !peer.points.empty();
  // The merge lines up whole maps, not one scan: a placement this side
  // trusts is refined with the peer's obstacles out to
  // merge_surroundings_radius (the decision weighs the result).
  if (p.valid && !peer.wide_surroundings.empty() && placement_problem(p.located, config, "", "").empty())
    p.wide = refine_placement(*self.map, peer.points, peer.wide_surroundings, p.located.best.pose, config.locate,
                              seed + 2)
                 .pose;
  return p;
}

EncounterEstimate decide_encounter(const Pose2& a_pose, const Pose2& b_pose, const PeerPlacement& a_locates_b,
                                   const PeerPlacement& b_locates_a, const EncounterConfig& config) {
  config.validate();
  EncounterEstimate e;
  e.a_locates_b = a_locates_b.located;
  e.b_locates_a = b_locates_a.located;
  if (!a_locates_b.valid || !b_locates_a.valid) {
    e.reason = "a robot has no valid scan points";
    return e;
  }
  // Both directions as estimates of B's frame in A's frame.
  e.b_frame_by_a = e.a_locates_b.best.pose * b_pose.inverse();
  e.b_frame_by_b = (e.b_locates_a.best.pose * a_pose.inverse()).inverse();
  // Compare where each puts robot B: the frames' origins may be far away,
  // where a small angle error looks like a large offset.
  const Pose2 b_by_a = e.b_frame_by_a * b_pose, b_by_b = e.b_frame_by_b * b_pose;
  const Apart directions = apart(b_by_a, b_by_b);
  e.disagreement_xy = directions.xy;
  e.disagreement_theta = directions.theta;

  std::string problem = placement_problem(e.a_locates_b, config, "A", "B");
  if (problem.empty()) problem = placement_problem(e.b_locates_a, config, "B", "A");
  e.placements_verified = problem.empty();
  const bool wide = a_locates_b.wide && b_locates_a.wide;
  const Pose2 wide_a = wide ? *a_locates_b.wide : Pose2{};  // B's pose by each direction's wide fit
  const Pose2 wide_b = wide ? (*b_locates_a.wide * a_pose.inverse()).inverse() * b_pose : Pose2{};
  const Apart wide_fits = apart(wide_a, wide_b);
  if (problem.empty() && beyond(directions, config)) {
    if (wide && config.wide_fit_settles_only && !beyond(wide_fits, config)) {
      e.b_frame_in_a = e.b_frame_in_a_near = interpolate(wide_a, wide_b, 0.5) * b_pose.inverse();
      e.accepted = e.settled_by_wide_fit = true;
      return e;
    }
    problem = fmt::format("the two directions disagree by {:.2f} m / {:.1f}°", e.disagreement_xy,
                          e.disagreement_theta * 180.0 / std::numbers::pi);
    if (wide && config.wide_fit_settles_only)
      problem += fmt::format(" (fitting {:.0f} m of both maps, by {:.2f} m / {:.1f}°)",
                             config.locate.merge_surroundings_radius, wide_fits.xy,
                             wide_fits.theta * 180.0 / std::numbers::pi);
  }
  if (!problem.empty()) {
    e.reason = problem;
    return e;
  }
  // Accepted: the mean of the two estimates of B's pose, expressed as a frame transform.
  e.b_frame_in_a = e.b_frame_in_a_near = interpolate(b_by_a, b_by_b, 0.5) * b_pose.inverse();
  e.accepted = true;
  if (!wide || config.wide_fit_settles_only) return e;
  // Verification above judged the near placements; the wide fit moves them
  // by centimetres. A larger move means the maps disagree with each other
  // (bent between here and their far parts, or the wide fit latched onto the
  // wrong part): the near estimate, right where the robots are, stands.
  const Pose2 wide_frame = interpolate(wide_a, wide_b, 0.5) * b_pose.inverse();
  const Pose2 moved = between(e.b_frame_in_a * b_pose, wide_frame * b_pose);
  e.wide_moved_xy = std::hypot(moved.x, moved.y);
  e.wide_moved_theta = std::abs(normalize_angle(moved.theta));
  if (beyond({e.wide_moved_xy, e.wide_moved_theta}, config)) {
    if (config.reject_bent_maps) {
      e.accepted = false;
      e.reason = fmt::format(
          "the maps disagree with each other: fitting {:.0f} m of both maps moves the transform {:.2f} m / {:.1f}° "
          "from the fit where the robots met",
          config.locate.merge_surroundings_radius, e.wide_moved_xy, e.wide_moved_theta * 180.0 / std::numbers::pi);
    }
    return e;
  }
  e.b_frame_in_a = wide_frame;
  return e;
}

EncounterEstimate estimate_encounter(const EncounterView& a, const EncounterView& b, const EncounterConfig& config,
                                     std::uint64_t seed) {
  if (!a.map || !b.map) throw ConfigError("estimate_encounter: both views need a map");
  const PeerPlacement a_locates_b = locate_peer(a, b, config, seed);
  const PeerPlacement b_locates_a = locate_peer(b, a, config, seed + 1);
  return decide_encounter(a.pose, b.pose, a_locates_b, b_locates_a, config);
}

}  // namespace dsswarm
