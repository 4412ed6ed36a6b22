#include "protocol/confirmation.hpp"

#include <cmath>

namespace dsswarm::protocol {

bool agrees_at_b(const Pose2& t, const Pose2& other, const Pose2& b_pose, const ConfirmTolerance& tol) {
  const Pose2 d = between(other * b_pose, t * b_pose);
  return std::hypot(d.x, d.y) <= tol.xy && std::abs(normalize_angle(d.theta)) <= tol.theta;
}

std::optional<Pose2> pending_confirmed_by_directions(const EncounterEstimate& e, const Pose2& b_pose,
                                                     std::span<const Pose2> a_pending,
                                                     std::span<const Pose2> b_pending, const ConfirmTolerance& tol) {
  if (e.accepted || !e.placements_verified) return std::nullopt;
  auto both_agree = [&](const Pose2& t) {
    return agrees_at_b(t, e.b_frame_by_a, b_pose, tol) && agrees_at_b(t, e.b_frame_by_b, b_pose, tol);
  };
  for (std::span<const Pose2> list : {a_pending, b_pending})
    for (const Pose2& t : list)
      if (both_agree(t)) return t;
  return std::nullopt;
}

std::optional<Pose2> near_agreeing_estimate(const EncounterEstimate& e, const Pose2& b_pose,
                                            const ConfirmTolerance& tol) {
  // disagreement_*: the two directions' placements of B, apart.
  if (e.accepted || !e.placements_verified || e.disagreement_xy > tol.xy || e.disagreement_theta > tol.theta)
    return std::nullopt;
  return interpolate(e.b_frame_by_a * b_pose, e.b_frame_by_b * b_pose, 0.5) * b_pose.inverse();
}

}  // namespace dsswarm::protocol
