#include "protocol/confirmation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace dsswarm::protocol {
namespace {

const ConfirmTolerance kConfirmTol{0.25, 0.035};
const Pose2 kTrueFrame{3.0, -1.0, 0.4};  // B's frame in A's, the truth
const Pose2 kRobotB{10.0, 4.0, 1.2};      // robot B in its own frame, 10 m from the origin

// An encounter turned down because its directions disagree: each placement
// verified, one direction `da`, the other `db` off the true frame (at B).
EncounterEstimate disagreeing(const Pose2& da, const Pose2& db) {
  EncounterEstimate e;
  e.placements_verified = true;
  e.b_frame_by_a = kTrueFrame * kRobotB * da * kRobotB.inverse();
  e.b_frame_by_b = kTrueFrame * kRobotB * db * kRobotB.inverse();
  const Pose2 apart = between(e.b_frame_by_b * kRobotB, e.b_frame_by_a * kRobotB);  // as decide_encounter has it
  e.disagreement_xy = std::hypot(apart.x, apart.y);
  e.disagreement_theta = std::abs(normalize_angle(apart.theta));
  e.reason = "the two directions disagree";
  return e;
}

TEST(Confirmation, AgreementIsMeasuredAtRobotBNotAtTheFramesOrigin) {
  EXPECT_TRUE(agrees_at_b(kTrueFrame, kTrueFrame * kRobotB * Pose2(0.2, 0.0, 0.0) * kRobotB.inverse(), kRobotB, kConfirmTol));
  EXPECT_FALSE(agrees_at_b(kTrueFrame, kTrueFrame * kRobotB * Pose2(0.3, 0.0, 0.0) * kRobotB.inverse(), kRobotB, kConfirmTol));
  // 1° about B's frame origin moves B, 10.8 m away, by 0.19 m: agrees; 1.5°
  // (under the 2° allowed) moves it 0.28 m: does not.
  EXPECT_TRUE(agrees_at_b(kTrueFrame, kTrueFrame * Pose2(0.0, 0.0, 0.0175), kRobotB, kConfirmTol));
  EXPECT_FALSE(agrees_at_b(kTrueFrame, kTrueFrame * Pose2(0.0, 0.0, 0.0262), kRobotB, kConfirmTol));
}

TEST(Confirmation, BothDirectionsNearAPendingTransformConfirmIt) {
  // 0.10 m / 1.1° apart: too far apart to be verified themselves (8 cm / 1°).
  const EncounterEstimate e = disagreeing(Pose2(0.05, 0.0, 0.0096), Pose2(-0.05, 0.0, -0.0096));
  const std::vector<Pose2> pending{kTrueFrame * kRobotB * Pose2(0.0, 0.02, 0.002) * kRobotB.inverse()};
  const std::optional<Pose2> t = pending_confirmed_by_directions(e, kRobotB, pending, {}, kConfirmTol);
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->x, pending[0].x, 1e-12);
  EXPECT_NEAR(t->theta, pending[0].theta, 1e-12);
  EXPECT_TRUE(pending_confirmed_by_directions(e, kRobotB, {}, pending, kConfirmTol));  // B's list counts as much
}

TEST(Confirmation, OneDirectionFarFromThePendingTransformConfirmsNothing) {
  const std::vector<Pose2> pending{kTrueFrame};
  // One direction a mirror image of the other (180°), as in a symmetric corridor.
  EXPECT_FALSE(pending_confirmed_by_directions(disagreeing(Pose2(), Pose2(0.0, 0.0, 3.1)), kRobotB, pending, {}, kConfirmTol));
  EXPECT_FALSE(pending_confirmed_by_directions(disagreeing(Pose2(0.4, 0.0, 0.0), Pose2()), kRobotB, pending, {}, kConfirmTol));
  EXPECT_FALSE(pending_confirmed_by_directions(disagreeing(Pose2(), Pose2()), kRobotB, {}, {}, kConfirmTol));  // none pending
}

TEST(Confirmation, OnlyAnEncounterTurnedDownForDisagreementAlone) {
  const std::vector<Pose2> pending{kTrueFrame};
  EncounterEstimate poor = disagreeing(Pose2(0.05, 0.0, 0.0), Pose2(-0.05, 0.0, 0.0));
  poor.placements_verified = false;  // e.g. a placement fits its map poorly
  EXPECT_FALSE(pending_confirmed_by_directions(poor, kRobotB, pending, {}, kConfirmTol));
  EncounterEstimate verified = disagreeing(Pose2(), Pose2());
  verified.accepted = true;  // confirmed the usual way (confirm())
  EXPECT_FALSE(pending_confirmed_by_directions(verified, kRobotB, pending, {}, kConfirmTol));
}

TEST(Confirmation, TheFirstAgreeingTransformOfASListWinsOnBothSides) {
  const EncounterEstimate e = disagreeing(Pose2(0.05, 0.0, 0.0), Pose2(-0.05, 0.0, 0.0));
  const Pose2 far = kTrueFrame * Pose2(5.0, 0.0, 0.0);
  const Pose2 near_a = kTrueFrame * kRobotB * Pose2(0.01, 0.0, 0.0) * kRobotB.inverse();
  const Pose2 near_b = kTrueFrame * kRobotB * Pose2(-0.01, 0.0, 0.0) * kRobotB.inverse();
  const std::vector<Pose2> a_list{far, near_a}, b_list{near_b};
  const std::optional<Pose2> t = pending_confirmed_by_directions(e, kRobotB, a_list, b_list, kConfirmTol);
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->x, near_a.x, 1e-12);
  EXPECT_NEAR(t->y, near_a.y, 1e-12);
}

TEST(Confirmation, DirectionsWithinTheToleranceAreHeldAsTheirMean) {
  const std::optional<Pose2> held =
      near_agreeing_estimate(disagreeing(Pose2(0.06, 0.0, 0.01), Pose2(-0.04, 0.0, -0.006)), kRobotB, kConfirmTol);
  ASSERT_TRUE(held);
  const Pose2 d = between(kTrueFrame * kRobotB, *held * kRobotB);  // at B: halfway between the two
  EXPECT_NEAR(d.x, 0.01, 1e-3);
  EXPECT_NEAR(d.y, 0.0, 1e-3);
  EXPECT_NEAR(d.theta, 0.002, 1e-9);
  // Too far apart (0.3 m), one placement unverified, or accepted anyway: nothing held.
  EXPECT_FALSE(near_agreeing_estimate(disagreeing(Pose2(0.15, 0.0, 0.0), Pose2(-0.15, 0.0, 0.0)), kRobotB,
                                      kConfirmTol));
  EncounterEstimate poor = disagreeing(Pose2(0.05, 0.0, 0.0), Pose2(-0.05, 0.0, 0.0));
  poor.placements_verified = false;
  EXPECT_FALSE(near_agreeing_estimate(poor, kRobotB, kConfirmTol));
  EncounterEstimate accepted = disagreeing(Pose2(), Pose2());
  accepted.accepted = true;
  EXPECT_FALSE(near_agreeing_estimate(accepted, kRobotB, kConfirmTol));
}

}  // namespace
}  // namespace dsswarm::protocol
