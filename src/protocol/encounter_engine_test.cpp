#include "protocol/encounter_engine.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "io/maps/dsmap.hpp"
#include "swarm/map_knowledge.hpp"
#include "protocol/encounter_engine_test_util.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm::protocol {
namespace {

using namespace engine_test;

using End = EncounterOutcome::End;

TEST(EncounterEngine, BothRobotsAcceptTheSameTransformAndMergeWhatTheOtherLacks) {
  Pair p(unconfirmed());
  p.ea.start("b", 1, 0.0);
  p.eb.start("a", 1, 0.0);
  p.pump(0.0);
  const auto oa = p.ea.take_outcomes(), ob = p.eb.take_outcomes();
  ASSERT_EQ(oa.size(), 1u);
  ASSERT_EQ(ob.size(), 1u);
  ASSERT_EQ(oa[0].end, End::accepted) << oa[0].reason;
  ASSERT_EQ(ob[0].end, End::accepted) << ob[0].reason;
  const Pose2 t = oa[0].estimate.b_frame_in_a;
  EXPECT_TRUE(t == ob[0].estimate.b_frame_in_a);  // one decision, computed twice
  const Pose2 truth = kStartA.inverse() * kStartB;
  EXPECT_NEAR(t.x, truth.x, 0.05);
  EXPECT_NEAR(t.y, truth.y, 0.05);
  EXPECT_NEAR(normalize_angle(t.theta - truth.theta), 0.0, 0.01);
  EXPECT_EQ(p.a.merges, 1);
  EXPECT_EQ(p.b.merges, 1);
  EXPECT_TRUE(p.b.last_transform == t.inverse());
  EXPECT_EQ(oa[0].bytes_sent, ob[0].bytes_received);
  EXPECT_EQ(oa[0].bytes_received, ob[0].bytes_sent);
  EXPECT_EQ(oa[0].layers_received, 1u);
  EXPECT_EQ(p.ea.open_encounters() + p.eb.open_encounters(), 0u);

  // Later, with nothing new on either side, nothing but the offers and
  // placements crosses again.
  p.ea.start("b", 2, 20.0);
  p.eb.start("a", 2, 20.0);
  p.pump(20.0);
  const auto again = p.ea.take_outcomes();
  ASSERT_EQ(again.size(), 1u);
  ASSERT_EQ(again[0].end, End::accepted) << again[0].reason;
  EXPECT_EQ(again[0].layers_received, 0u);
  // The first time b's whole map crossed; this time not a byte of it.
  const std::size_t b_map_bytes = encode_dsmap(MapSnapshot{"b", {MapLayer{"b", 11, {}, 0, p.b.own, {}}}}).size();
  EXPECT_EQ(oa[0].snapshot_bytes_received, b_map_bytes);
  EXPECT_EQ(again[0].snapshot_bytes_received, 0u);
  EXPECT_LT(again[0].bytes_received, oa[0].bytes_received - b_map_bytes + 100);
  EXPECT_EQ(p.a.merges, 1);
}

TEST(EncounterEngine, APeerThatMergedHearsWhereLoopClosingMovedTheMapAndNoOneElseDoes) {
  Pair p(unconfirmed());
  p.a.revision = 3;
  p.ea.announce_moves(0.0, true);  // nobody holds a's map yet
  EXPECT_TRUE(p.ea.take_outbox().empty());
  p.ea.start("b", 1, 0.0);
  p.eb.start("a", 1, 0.0);
  p.pump(0.0);
  ASSERT_EQ(p.ea.take_outcomes().at(0).end, End::accepted);
  p.eb.take_outcomes();
  p.ea.tick(1.0);  // b merged a's map at revision 3: it hears of it once
  p.pump(1.0);
  ASSERT_EQ(p.b.followed.size(), 1u);
  EXPECT_EQ(p.b.followed[0].first, "a");
  const MapMoves& m = p.b.followed[0].second;
  EXPECT_EQ(m.revision, 3u);
  ASSERT_EQ(m.ties.size(), 1u);
  EXPECT_EQ(m.ties[0].encounter, 1u);
  EXPECT_TRUE(m.ties[0].then == p.a.view.pose);  // a's scan as it offered it
  p.a.revision = 4;
  p.ea.tick(3.0);  // moved, but b heard too recently (the interval is 5 s)
  p.pump(3.0);
  EXPECT_EQ(p.b.followed.size(), 1u);
  p.ea.tick(6.5);
  p.pump(6.5);
  ASSERT_EQ(p.b.followed.size(), 2u);
  p.ea.tick(30.0);  // nothing moved since
  p.pump(30.0);
  ASSERT_EQ(p.b.followed.size(), 2u);
  EXPECT_EQ(p.b.followed[1].second.revision, 4u);
  EXPECT_TRUE(p.a.followed.empty());  // b's map never moved
  // b restarts (its checkpoint keeps a's layer, not the closures that came
  // with it): a tells it again, though a's map has not moved.
  p.ea.drop_peer("b", "b restarted", 31.0);
  p.ea.tick(31.0);
  const std::vector<Outgoing> again = p.ea.take_outbox();
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].recipient, "b");
}

TEST(EncounterEngine, TheOutcomeDoesNotDependOnWhoHearsOfTheEncounterFirst) {
  Pair both(unconfirmed()), only_b(unconfirmed());
  both.ea.start("b", 7, 0.0);
  both.eb.start("a", 7, 0.0);
  both.pump(0.0);
  only_b.eb.start("a", 7, 0.0);  // a joins when b's offer arrives
  only_b.pump(0.0);
  const auto x = both.ea.take_outcomes(), y = only_b.ea.take_outcomes();
  ASSERT_EQ(x.size(), 1u);
  ASSERT_EQ(y.size(), 1u);
  EXPECT_EQ(x[0].end, y[0].end);
  EXPECT_TRUE(x[0].estimate.b_frame_in_a == y[0].estimate.b_frame_in_a);
  EXPECT_TRUE(x[0].estimate.a_locates_b.best.pose == y[0].estimate.a_locates_b.best.pose);
}

TEST(EncounterEngine, AFirstVerifiedEstimateWaitsForASecondThatAgrees) {
  Pair p{SwarmConfig{}};
  p.ea.start("b", 1, 0.0);
  p.eb.start("a", 1, 0.0);
  p.pump(0.0);
  const auto first_a = p.ea.take_outcomes(), first_b = p.eb.take_outcomes();
  ASSERT_EQ(first_a.size(), 1u);
  EXPECT_EQ(first_a[0].end, End::rejected);
  EXPECT_EQ(first_b[0].end, End::rejected);
  EXPECT_NE(first_a[0].reason.find("unconfirmed: "), std::string::npos);
  EXPECT_EQ(p.a.merges, 0);
  // The same again, neither robot having moved or mapped: a repeat, not a
  // second estimate. Both decline it, and nothing is confirmed.
  p.ea.start("b", 2, 1.0);
  p.eb.start("a", 2, 1.0);
  p.pump(1.0);
  const auto repeat_a = p.ea.take_outcomes(), repeat_b = p.eb.take_outcomes();
  ASSERT_EQ(repeat_a.size(), 1u);
  EXPECT_EQ(repeat_a[0].end, End::declined);
  EXPECT_EQ(repeat_b[0].end, End::declined);
  EXPECT_EQ(repeat_a[0].decline, EncounterOutcome::Decline::unchanged);
  EXPECT_NE(repeat_a[0].reason.find("nothing new since encounter 1"), std::string::npos) << repeat_a[0].reason;
  EXPECT_EQ(p.a.merges, 0);
  EXPECT_EQ(p.ea.open_encounters() + p.eb.open_encounters(), 0u);
  p.b.version = 12;  // b went on mapping: a new situation
  p.ea.start("b", 3, 2.0);
  p.eb.start("a", 3, 2.0);
  p.pump(2.0);
  const auto second_a = p.ea.take_outcomes(), second_b = p.eb.take_outcomes();
  ASSERT_EQ(second_a[0].end, End::accepted) << second_a[0].reason;
  ASSERT_EQ(second_b[0].end, End::accepted) << second_b[0].reason;
  EXPECT_EQ(second_a[0].confirmed_by, "earlier encounter");
  EXPECT_EQ(second_b[0].confirmed_by, "earlier encounter");
  // A third, once they know each other: confirmed by the transform they hold.
  p.b.version = 13;
  p.ea.start("b", 4, 30.0);
  p.eb.start("a", 4, 30.0);
  p.pump(30.0);
  EXPECT_EQ(p.ea.take_outcomes()[0].confirmed_by, "known transform");
}

// A second encounter whose directions each verify but disagree with each
// other (B reports its pose 12 cm off, so its own placement of A and A's of
// its scan part by that much) confirms the pending transform both lie near.
TEST(EncounterEngine, ASecondEncounterWhoseDirectionsDisagreeButEachAgreesConfirmsThePendingTransform) {
  for (const bool by_directions : {true, false}) {
    SCOPED_TRACE(by_directions ? "confirm_by_directions" : "without");
    SwarmConfig config;
    config.confirm_by_directions = by_directions;
    Pair p(config);
    const auto first = p.meet(1, 0.0).first;
    ASSERT_EQ(first.size(), 1u);
    ASSERT_NE(first[0].reason.find("unconfirmed: "), std::string::npos) << first[0].reason;
    p.b.view.pose = p.b.view.pose * Pose2(0.12, 0.0, 0.0);
    p.b.version = 12;
    const auto [second_a, second_b] = p.meet(2, 1.0);
    ASSERT_EQ(second_a.size(), 1u);
    ASSERT_EQ(second_b.size(), 1u);
    EXPECT_GT(second_a[0].estimate.disagreement_xy, config.encounter.agree_xy);
    if (!by_directions) {
      EXPECT_EQ(second_a[0].end, End::rejected);
      EXPECT_NE(second_a[0].reason.find("the two directions disagree"), std::string::npos) << second_a[0].reason;
      EXPECT_EQ(p.a.merges + p.b.merges, 0);
      continue;
    }
    ASSERT_EQ(second_a[0].end, End::accepted) << second_a[0].reason;
    ASSERT_EQ(second_b[0].end, End::accepted) << second_b[0].reason;
    EXPECT_EQ(second_a[0].confirmed_by, "earlier encounter, by each direction of this one");
    EXPECT_EQ(second_b[0].confirmed_by, second_a[0].confirmed_by);
    // Merged on the first, verified transform, by both robots.
    EXPECT_EQ(p.a.merges, 1);
    EXPECT_EQ(p.b.merges, 1);
    EXPECT_TRUE(p.a.last_transform == first[0].estimate.b_frame_in_a);
    EXPECT_TRUE(p.b.last_transform == first[0].estimate.b_frame_in_a.inverse());
  }
}

// What was pending is settled once the pair merges: a later encounter whose
// directions disagree is not merged on a transform held before that merge
// (the maps have moved since; simulated seed 11 merged 0.054 m off so).
TEST(EncounterEngine, AMergeSettlesWhatWasPending) {
  Pair p(SwarmConfig{});
  const auto first = p.meet(1, 0.0).first;
  ASSERT_EQ(first.size(), 1u);
  ASSERT_NE(first[0].reason.find("unconfirmed: "), std::string::npos) << first[0].reason;
  p.b.version = 12;
  const auto second = p.meet(2, 1.0).first;
  ASSERT_EQ(second.size(), 1u);
  ASSERT_EQ(second[0].end, End::accepted) << second[0].reason;
  EXPECT_EQ(second[0].confirmed_by, "earlier encounter");
  ASSERT_EQ(p.a.merges, 1);
  // B reports its pose 12 cm off: each direction lies near the first
  // encounter's transform, and the two disagree.
  p.b.view.pose = p.b.view.pose * Pose2(0.12, 0.0, 0.0);
  p.b.version = 13;
  const auto [third_a, third_b] = p.meet(3, 30.0);
  ASSERT_EQ(third_a.size(), 1u);
  ASSERT_EQ(third_b.size(), 1u);
  EXPECT_GT(third_a[0].estimate.disagreement_xy, SwarmConfig{}.encounter.agree_xy);
  EXPECT_EQ(third_a[0].end, End::rejected) << third_a[0].confirmed_by;
  EXPECT_EQ(third_b[0].end, End::rejected) << third_b[0].confirmed_by;
  EXPECT_NE(third_a[0].reason.find("held until a second encounter agrees"), std::string::npos) << third_a[0].reason;
  EXPECT_EQ(p.a.merges, 1);
  EXPECT_EQ(p.b.merges, 1);
}

// The other order, with loop closure on: the encounter whose directions
// disagree comes first and is held; a verified one that agrees with it is
// confirmed by it. Held, it is not run again on the same scans (a repeat
// could confirm itself). Without loop closure a merge is final and only
// verified transforms are held.
TEST(EncounterEngine, WithLoopClosureAnEncounterWhoseDirectionsNearlyAgreeIsHeldAndConfirmsALaterOne) {
  for (const bool loop_closure : {true, false}) {
    SCOPED_TRACE(loop_closure ? "loop closure on" : "off");
    SwarmConfig config;
    config.slam.loop_closure.enabled = loop_closure;
    Pair p(config);
    const Pose2 true_pose = p.b.view.pose;
    p.b.view.pose = true_pose * Pose2(0.12, 0.0, 0.0);
    const auto first = p.meet(1, 0.0).first;
    ASSERT_EQ(first.size(), 1u);
    EXPECT_EQ(first[0].end, End::rejected);
    EXPECT_EQ(first[0].reason.find("; held until a second encounter agrees") != std::string::npos, loop_closure)
        << first[0].reason;
    const auto repeat = p.meet(2, 1.0).first;  // the same scans and maps again
    ASSERT_EQ(repeat.size(), 1u);
    EXPECT_EQ(repeat[0].end == End::declined, loop_closure);  // turned down, not held: runs again once
    EXPECT_EQ(p.a.merges, 0);
    p.b.view.pose = true_pose;
    p.b.version = 12;
    const auto third = p.meet(3, 2.0).first;
    ASSERT_EQ(third.size(), 1u);
    if (!loop_closure) {
      EXPECT_NE(third[0].reason.find("unconfirmed: "), std::string::npos) << third[0].reason;
      EXPECT_EQ(p.a.merges, 0);
      continue;
    }
    ASSERT_EQ(third[0].end, End::accepted) << third[0].reason;
    EXPECT_EQ(third[0].confirmed_by, "earlier encounter");
    EXPECT_EQ(p.a.merges, 1);
    EXPECT_EQ(p.b.merges, 1);
  }
}

TEST(EncounterEngine, WithinTheRemergeIntervalBothDecline) {
  Pair p(unconfirmed());
  p.ea.start("b", 1, 0.0);
  p.eb.start("a", 1, 0.0);
  p.pump(0.0);
  p.ea.take_outcomes();
  p.ea.start("b", 2, 5.0);
  p.eb.start("a", 2, 5.0);
  p.pump(5.0);
  const auto o = p.ea.take_outcomes();
  ASSERT_EQ(o.size(), 1u);
  EXPECT_EQ(o[0].end, End::declined);
  EXPECT_NE(o[0].reason.find("re-merge interval"), std::string::npos);
  EXPECT_EQ(p.a.merges, 1);
}

TEST(EncounterEngine, APeerThatVanishesMidTransferIsDroppedAndItsPartialSnapshotDiscarded) {
  SwarmConfig config = unconfirmed();
  config.chunk_bytes = 4096;  // many chunks
  Pair p(config);
  p.ea.start("b", 1, 0.0);
  p.eb.start("a", 1, 0.0);
  int chunks_to_a = 0;
  // b's chunks stop arriving after the third: b "died" mid-transfer.
  p.pump(0.0, [&](const Outgoing& out) {
    const Message m = decode(out.bytes);
    if (out.recipient == "a" && std::holds_alternative<Chunk>(m.body)) return ++chunks_to_a <= 3;
    return true;
  });
  ASSERT_GT(chunks_to_a, 3);
  EXPECT_EQ(p.ea.open_encounters(), 1u);
  EXPECT_GT(p.ea.buffered_bytes(), 0u);
  p.ea.tick(config.exchange_timeout - 1.0);
  EXPECT_EQ(p.ea.open_encounters(), 1u);
  p.ea.tick(config.exchange_timeout + 1.0);
  EXPECT_EQ(p.ea.open_encounters(), 0u);
  EXPECT_EQ(p.ea.buffered_bytes(), 0u);
  const auto o = p.ea.take_outcomes();
  ASSERT_EQ(o.size(), 1u);
  EXPECT_EQ(o[0].end, End::abandoned);
  EXPECT_NE(o[0].reason.find("snapshot"), std::string::npos);
  EXPECT_EQ(p.a.merges, 0);  // nothing half-received reached the map
}

// b is killed mid-encounter and restarted: a has ended that encounter
// ("b restarted"); the new b, offering it again, is declined: an encounter
// ends once, encounters.json has one outcome per id.
TEST(EncounterEngine, AnEncounterThatEndedIsNotRunAgainWithARestartedPeer) {
  Pair p(unconfirmed());
  p.ea.start("b", 1, 0.0);
  p.pump(0.0, [](const Outgoing& out) { return out.recipient != "b"; });  // b is gone
  p.ea.drop_peer("b", "b restarted", 1.0);
  ASSERT_EQ(p.ea.take_outcomes().size(), 1u);
  EncounterEngine b_again("b", unconfirmed(), p.b, 2);
  MessageGate gate_b_again("b");
  b_again.start("a", 1, 2.0);
  for (int round = 0; round < 3; ++round) {
    for (const Outgoing& out : b_again.take_outbox())
      if (auto v = p.ga.admit(out.bytes); v.message) p.ea.receive(*v.message, out.bytes.size(), 2.0);
    for (const Outgoing& out : p.ea.take_outbox())
      if (auto v = gate_b_again.admit(out.bytes); v.message) b_again.receive(*v.message, out.bytes.size(), 2.0);
  }
  EXPECT_TRUE(p.ea.take_outcomes().empty());
  EXPECT_EQ(p.ea.open_encounters(), 0u);
  const auto o = b_again.take_outcomes();
  ASSERT_EQ(o.size(), 1u);
  EXPECT_EQ(o[0].end, End::declined);
  EXPECT_NE(o[0].reason.find("has ended"), std::string::npos) << o[0].reason;
  EXPECT_EQ(p.a.merges, 0);
}

TEST(EncounterEngine, TransfersBeyondTheMemoryBoundAreAbandoned) {
  SwarmConfig config = unconfirmed();
  config.max_transfer_bytes = std::size_t{1} << 20;
  Pair p(config);
  p.ea.start("b", 1, 0.0);
  p.eb.start("a", 1, 0.0);
  // b claims a transfer far larger than a may hold: a gives up before buffering it.
  p.pump(0.0, [&](const Outgoing& out) {
    Message m = decode(out.bytes);
    if (out.recipient != "a" || !std::holds_alternative<Chunk>(m.body)) return true;
    return false;
  });
  ASSERT_EQ(p.ea.open_encounters(), 1u);  // waiting for b's snapshot
  Chunk huge{1, 0, 4, std::uint64_t{64} << 20, 0, std::vector<std::uint8_t>(1000, 1)};
  Message m;
  m.header = {"b", "a", 1, 1000};
  m.body = huge;
  p.ea.receive(m, 1100, 0.0);
  EXPECT_EQ(p.ea.open_encounters(), 0u);
  EXPECT_EQ(p.ea.buffered_bytes(), 0u);
  const auto o = p.ea.take_outcomes();
  ASSERT_EQ(o.size(), 1u);
  EXPECT_NE(o[0].reason.find("more than 1 MiB"), std::string::npos) << o[0].reason;
  EXPECT_EQ(p.a.merges, 0);
}

TEST(EncounterEngine, OpenEncountersAreBounded) {
  SwarmConfig config = unconfirmed();
  config.max_open_encounters = 2;
  FakeRobot robot("a", kStartA, {3.0, 2.0, 0.1}, 1);
  EncounterEngine e("a", config, robot);
  for (int i = 0; i < 5; ++i) e.start("peer" + std::to_string(i), 1, 0.0);
  EXPECT_EQ(e.open_encounters(), 2u);
  const auto o = e.take_outcomes();
  ASSERT_EQ(o.size(), 3u);
  for (const auto& x : o) EXPECT_NE(x.reason.find("busy"), std::string::npos);
  e.drop_peer("peer0", "vanished", 1.0);
  EXPECT_EQ(e.open_encounters(), 1u);
  e.abandon_all("stopped", 2.0);
  EXPECT_EQ(e.open_encounters(), 0u);
  const auto ended = e.take_outcomes();
  ASSERT_EQ(ended.size(), 2u);
  EXPECT_EQ(ended[1].reason, "stopped");
}

}  // namespace
}  // namespace dsswarm::protocol
