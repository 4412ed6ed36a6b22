// decide_encounter on placements made up here: the rules, without the search.
#include "swarm/encounter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace dsswarm::decide_test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const Pose2 kFrame{3.0, -1.0, 0.4};                     // B's frame in A's, the truth
const Pose2 kPoseA{2.0, 1.0, 0.3}, kPoseB{10.0, 4.0, 1.2};  // each robot in its own frame

// A placement that passes this side's checks at `pose`, with its wide fit at `wide`.
PeerPlacement placed(const Pose2& pose, const Pose2& wide) {
  PeerPlacement p;
  p.valid = true;
  p.located.best = {pose, 0.8, 0.8, 0.9, 1.0, 1.0};
  p.wide = wide;
  return p;
}

// A places B at the truth moved by `da` (at B), B places A so that B lands at
// the truth moved by `db`; each wide fit likewise by `wa` / `wb`.
struct Pair {
  PeerPlacement a_locates_b, b_locates_a;
};
Pair pair(const Pose2& da, const Pose2& db, const Pose2& wa, const Pose2& wb) {
  const Pose2 b_in_a = kFrame * kPoseB;
  // B's frame as B's placement of A has it: (A in B's map) = frame⁻¹ · A.
  auto a_in_b = [&](const Pose2& d) { return ((b_in_a * d) * kPoseB.inverse()).inverse() * kPoseA; };
  return {placed(b_in_a * da, b_in_a * wa), placed(a_in_b(db), a_in_b(wb))};
}

double off_at_b(const Pose2& frame) {
  const Pose2 d = between(kFrame * kPoseB, frame * kPoseB);
  return std::hypot(d.x, d.y) + std::abs(d.theta);
}

TEST(DecideEncounter, WithLoopClosureAgreeingWideFitsSettleDirectionsThatDisagree) {
  // 0.16 m / 1.2° apart where the robots met; their wide fits 2 cm / 0.2°.
  const Pair p = pair(Pose2(0.08, 0.0, 0.6 * kDeg), Pose2(-0.08, 0.0, -0.6 * kDeg), Pose2(0.01, 0.0, 0.1 * kDeg),
                      Pose2(-0.01, 0.0, -0.1 * kDeg));
  EncounterConfig config;
  const EncounterEstimate plain = decide_encounter(kPoseA, kPoseB, p.a_locates_b, p.b_locates_a, config);
  EXPECT_FALSE(plain.accepted);  // without loop closure the wide fit only refines an agreement
  EXPECT_NE(plain.reason.find("directions disagree"), std::string::npos) << plain.reason;
  config.wide_fit_settles_only = true;
  const EncounterEstimate e = decide_encounter(kPoseA, kPoseB, p.a_locates_b, p.b_locates_a, config);
  ASSERT_TRUE(e.accepted) << e.reason;
  EXPECT_TRUE(e.settled_by_wide_fit);
  EXPECT_NEAR(e.disagreement_xy, 0.16, 0.01);
  EXPECT_LT(off_at_b(e.b_frame_in_a), 0.005);  // the wide fits' mean
}

TEST(DecideEncounter, WideFitsThatDisagreeTooSettleNothing) {
  const Pair p = pair(Pose2(0.08, 0.0, 0.6 * kDeg), Pose2(-0.08, 0.0, -0.6 * kDeg), Pose2(0.06, 0.0, 0.0),
                      Pose2(-0.06, 0.0, 0.0));
  EncounterConfig config;
  config.wide_fit_settles_only = true;
  const EncounterEstimate e = decide_encounter(kPoseA, kPoseB, p.a_locates_b, p.b_locates_a, config);
  EXPECT_FALSE(e.accepted);
  EXPECT_FALSE(e.settled_by_wide_fit);
  EXPECT_TRUE(e.placements_verified);
  EXPECT_NE(e.reason.find("of both maps, by 0.12 m"), std::string::npos) << e.reason;
}

TEST(DecideEncounter, WithLoopClosureTheWideFitMovesNoAgreedTransform) {
  // The directions agree (2 cm); the wide fits would move the transform 5 cm.
  const Pair p = pair(Pose2(0.01, 0.0, 0.0), Pose2(-0.01, 0.0, 0.0), Pose2(0.05, 0.0, 0.0), Pose2(0.05, 0.0, 0.0));
  EncounterConfig config;
  const EncounterEstimate moved = decide_encounter(kPoseA, kPoseB, p.a_locates_b, p.b_locates_a, config);
  ASSERT_TRUE(moved.accepted) << moved.reason;
  EXPECT_NEAR(off_at_b(moved.b_frame_in_a), 0.05, 0.005);
  config.wide_fit_settles_only = true;
  const EncounterEstimate kept = decide_encounter(kPoseA, kPoseB, p.a_locates_b, p.b_locates_a, config);
  ASSERT_TRUE(kept.accepted) << kept.reason;
  EXPECT_FALSE(kept.settled_by_wide_fit);
  EXPECT_LT(off_at_b(kept.b_frame_in_a), 0.002);
}

TEST(DecideEncounter, APlacementThatFailsItsChecksIsNotSettledByTheWideFit) {
  Pair p = pair(Pose2(0.08, 0.0, 0.0), Pose2(-0.08, 0.0, 0.0), Pose2(), Pose2());
  p.b_locates_a.located.best.inlier_ratio = 0.3;
  EncounterConfig config;
  config.wide_fit_settles_only = true;
  const EncounterEstimate e = decide_encounter(kPoseA, kPoseB, p.a_locates_b, p.b_locates_a, config);
  EXPECT_FALSE(e.accepted);
  EXPECT_NE(e.reason.find("fits its map poorly"), std::string::npos) << e.reason;
}

}  // namespace
}  // namespace dsswarm::decide_test
