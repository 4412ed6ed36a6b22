#include "protocol/repeats.hpp"

#include <gtest/gtest.h>

namespace dsswarm::protocol {
namespace {

const Offered kA{{1.0, 2.0, 0.3}, {{"a", 40, 0}, {"b", 30, 1}}};
const Offered kB{{-3.0, 0.5, 2.0}, {{"b", 30, 0}}};

TEST(RepeatGuard, TheSameOffersAsTheLastDecidedEncounterRepeatIt) {
  RepeatGuard guard(0.05, 0.0175);
  EXPECT_FALSE(guard.repeats("b", kA, kB));  // nothing decided yet
  guard.decided("b", 7, kA, kB);
  EXPECT_EQ(guard.repeats("b", kA, kB), 7u);
  Offered nudged = kA;
  nudged.pose = kA.pose * Pose2(0.03, 0.0, 0.01);  // standing where it stood
  EXPECT_EQ(guard.repeats("b", nudged, kB), 7u);
  EXPECT_FALSE(guard.repeats("c", kA, kB));  // another pair
}

TEST(RepeatGuard, AMoveOrAnythingNewOnEitherSideIsNoRepeat) {
  RepeatGuard guard(0.05, 0.0175);
  guard.decided("b", 7, kA, kB);
  Offered moved = kB;
  moved.pose = kB.pose * Pose2(0.2, 0.0, 0.0);
  EXPECT_FALSE(guard.repeats("b", kA, moved));
  Offered turned = kA;
  turned.pose.theta += 0.05;
  EXPECT_FALSE(guard.repeats("b", turned, kB));
  Offered mapped = kA;
  mapped.inventory[0].version = 41;  // a scan went into its map
  EXPECT_FALSE(guard.repeats("b", mapped, kB));
  Offered learnt = kB;
  learnt.inventory.push_back({"c", 12, 1});  // it merged a third robot's map
  EXPECT_FALSE(guard.repeats("b", kA, learnt));
  guard.decided("b", 8, kA, moved);  // the latest decided one counts
  EXPECT_FALSE(guard.repeats("b", kA, kB));
  EXPECT_EQ(guard.repeats("b", kA, moved), 8u);
}

// A random search may miss what a second one finds: a repeat of an
// encounter turned down runs again (here once), one verified never does.
TEST(RepeatGuard, ARepeatOfOneTurnedDownRunsAgainAsOftenAsAllowed) {
  RepeatGuard guard(0.05, 0.0175, 1);
  guard.decided("b", 7, kA, kB, false);
  EXPECT_FALSE(guard.repeats("b", kA, kB));  // turned down once: run it again
  guard.decided("b", 8, kA, kB, false);
  EXPECT_EQ(guard.repeats("b", kA, kB), 8u);  // twice: enough
  guard.decided("c", 3, kA, kB, false);
  guard.decided("c", 4, kA, kB, true);  // the second run verified
  EXPECT_EQ(guard.repeats("c", kA, kB), 4u);
  guard.decided("d", 5, kA, kB, true);
  EXPECT_EQ(guard.repeats("d", kA, kB), 5u);  // verified: a repeat cannot confirm it

  RepeatGuard never(0.05, 0.0175, 0);
  never.decided("b", 7, kA, kB, false);
  EXPECT_EQ(never.repeats("b", kA, kB), 7u);
}

}  // namespace
}  // namespace dsswarm::protocol
