#pragma once
// Confirmation (swarm.confirm): a verified transform between two robots' maps
// is merged on only when a second, independent estimate agrees with it
// (docs/design.md, "Confirmation"). Pure functions of what both robots hold,
// so the two sides of an encounter come to the same answer.
#include <optional>
#include <span>

#include "geometry/pose2.hpp"
#include "swarm/encounter.hpp"

namespace dsswarm::protocol {

struct ConfirmTolerance {
  double xy = 0.0;     // m, at robot B
  double theta = 0.0;  // rad
};

// `other` (B's frame in A's) puts robot B, at `b_pose` in its own frame,
// within `tol` of where `t` puts it. Measured at B: the frames' origins may
// be far away, where a small angle error looks like a large offset.
bool agrees_at_b(const Pose2& t, const Pose2& other, const Pose2& b_pose, const ConfirmTolerance& tol);

// An encounter turned down only because its two directions disagree (each
// placement verified on its own) still holds two independent estimates. A
// pending verified transform that each of them agrees with is confirmed by
// them: returned (the first such in A's list, then B's), else nothing.
std::optional<Pose2> pending_confirmed_by_directions(const EncounterEstimate& e, const Pose2& b_pose,
                                                     std::span<const Pose2> a_pending,
                                                     std::span<const Pose2> b_pending, const ConfirmTolerance& tol);

// The same kind of encounter, when its two directions lie within `tol` of
// each other: the mean of the two, held pending like a verified transform
// (a later encounter that agrees confirms it, whichever came first).
// Otherwise nothing.
std::optional<Pose2> near_agreeing_estimate(const EncounterEstimate& e, const Pose2& b_pose,
                                            const ConfirmTolerance& tol);

}  // namespace dsswarm::protocol
