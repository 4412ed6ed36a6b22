// The encounter engine with three robots: encounters of one robot run one
// after another, as in one process.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "protocol/encounter_engine.hpp"
#include "protocol/encounter_engine_test_util.hpp"

namespace dsswarm::protocol {
namespace {

using namespace engine_test;
using End = EncounterOutcome::End;

// Three robots: a meets b (encounter 1), then c (encounter 2) while 1 is
// still open. a takes its view for 2 only once 1 has ended and merged, as in
// one process, where every encounter ends before the next begins.
struct Trio {
  Trio()
      : a("a", kStartA, {3.0, 2.0, 0.1}, 1),
        b("b", kStartB, {5.0, 2.5, 2.9}, 2),
        c("c", kStartB, {5.0, 2.5, 2.9}, 3) {
    for (FakeRobot* r : {&a, &b, &c}) engines.emplace(r->knowledge.self(), std::make_unique<Side>(unconfirmed(), *r));
  }
  struct Side {
    Side(const SwarmConfig& config, FakeRobot& robot)
        : engine(robot.knowledge.self(), config, robot), gate(robot.knowledge.self()) {}
    EncounterEngine engine;
    MessageGate gate;
  };
  // Delivers everything in flight; what goes to the robots in `hold` waits
  // for a later pump without them.
  void pump(double now, const std::set<std::string>& hold = {}) {
    std::vector<Outgoing> later;
    for (bool moved = true; moved;) {
      moved = false;
      std::vector<Outgoing> all = std::exchange(held, {});
      for (auto& [name, side] : engines)
        for (Outgoing& out : side->engine.take_outbox()) all.push_back(std::move(out));
      for (Outgoing& out : all) {
        moved = true;
        if (hold.contains(out.recipient)) {
          later.push_back(std::move(out));
          continue;
        }
        Side& to = *engines.at(out.recipient);
        if (auto v = to.gate.admit(out.bytes); v.message) to.engine.receive(*v.message, out.bytes.size(), now);
      }
    }
    held = std::move(later);
  }
  EncounterEngine& e(const std::string& name) { return engines.at(name)->engine; }
  FakeRobot a, b, c;
  std::map<std::string, std::unique_ptr<Side>> engines;
  std::vector<Outgoing> held;
};

TEST(EncounterEngine, ALaterEncounterWaitsForTheEarlierOneAndSeesItsMerge) {
  Trio t;
  t.e("a").start("b", 1, 0.0);
  t.e("a").start("c", 2, 0.5);
  t.e("c").start("a", 2, 0.5);
  t.pump(0.5, {"b"});  // b is slow: nothing has reached it yet
  EXPECT_EQ(t.e("a").open_encounters(), 2u);  // 1 open, 2 waiting
  ASSERT_EQ(t.a.captured.size(), 1u);         // a has taken its view for 1 only
  EXPECT_TRUE(t.e("a").take_outcomes().empty());
  EXPECT_TRUE(t.e("c").take_outcomes().empty());  // c waits for a's offer

  t.e("b").start("a", 1, 0.0);
  t.pump(1.0);
  const auto oa = t.e("a").take_outcomes();
  ASSERT_EQ(oa.size(), 2u);
  EXPECT_EQ(oa[0].encounter, 1u);
  EXPECT_EQ(oa[0].end, End::accepted) << oa[0].reason;
  EXPECT_EQ(oa[1].encounter, 2u);
  EXPECT_EQ(oa[1].end, End::accepted) << oa[1].reason;
  EXPECT_EQ(oa[1].started, 0.5);  // its own event time, not when it could begin
  ASSERT_EQ(t.a.captured.size(), 2u);
  EXPECT_EQ(t.a.captured[1], (std::pair<std::uint64_t, int>{2, 1}));  // taken after b's map was merged
  const auto oc = t.e("c").take_outcomes();
  ASSERT_EQ(oc.size(), 1u);
  EXPECT_EQ(oc[0].end, End::accepted) << oc[0].reason;
  EXPECT_EQ(t.e("a").open_encounters(), 0u);
}

TEST(EncounterEngine, AnEncounterThatWaitedTooLongIsDeclinedToThePeer) {
  Trio t;
  const double timeout = unconfirmed().offer_timeout;
  t.e("a").start("b", 1, 0.0);
  t.e("a").start("c", 2, 0.0);
  t.e("c").start("a", 2, 0.0);
  t.pump(0.0, {"b"});  // b never answers
  t.e("a").tick(timeout + 1.0);
  t.pump(timeout + 1.0, {"b"});
  EXPECT_EQ(t.e("a").open_encounters(), 0u);
  const auto oa = t.e("a").take_outcomes();
  ASSERT_EQ(oa.size(), 2u);
  EXPECT_EQ(oa[0].end, End::abandoned);
  EXPECT_NE(oa[0].reason.find("timed out"), std::string::npos) << oa[0].reason;
  EXPECT_EQ(oa[1].end, End::abandoned);
  EXPECT_NE(oa[1].reason.find("earlier encounters"), std::string::npos) << oa[1].reason;
  EXPECT_EQ(t.a.captured.size(), 1u);  // never opened
  const auto oc = t.e("c").take_outcomes();  // told at once, not after its own time-out
  ASSERT_EQ(oc.size(), 1u);
  EXPECT_EQ(oc[0].end, End::declined);
  EXPECT_EQ(t.e("c").open_encounters(), 0u);
}

}  // namespace
}  // namespace dsswarm::protocol
