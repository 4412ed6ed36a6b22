#include "protocol/gate.hpp"

#include <gtest/gtest.h>

namespace dsswarm::protocol {
namespace {

std::vector<std::uint8_t> from(MessageStamper& s, const std::string& to, Body body = Decline{1, "x"}) {
  return encode(s.stamp(to, std::move(body)));
}

TEST(MessageGate, AdmitsInOrderAndRefusesReplays) {
  MessageGate gate("robot2");
  MessageStamper robot1("robot1", 100);
  const auto first = from(robot1, "robot2");
  const auto second = from(robot1, "robot2");
  EXPECT_TRUE(gate.admit(first).message);
  EXPECT_TRUE(gate.admit(second).message);
  const MessageGate::Verdict again = gate.admit(first);
  EXPECT_FALSE(again.message);
  EXPECT_NE(again.rejected.find("sequence 1 after 2"), std::string::npos);
  EXPECT_EQ(gate.rejected_by_reason().at("replayed"), 1u);
  // Broadcasts are numbered apart from messages to us: both streams go on.
  EXPECT_TRUE(gate.admit(from(robot1, "", Heartbeat{})).message);
  EXPECT_TRUE(gate.admit(from(robot1, "robot2")).message);
  EXPECT_EQ(gate.accepted(), 4u);
}

TEST(MessageGate, ARestartedSenderIsWelcomeAndItsOldRunIsNot) {
  MessageGate gate("robot2");
  MessageStamper old_run("robot1", 100), new_run("robot1", 200);
  const auto old_message = from(old_run, "robot2");
  EXPECT_FALSE(gate.admit(old_message).peer_restarted);
  const MessageGate::Verdict restarted = gate.admit(from(new_run, "robot2"));
  EXPECT_TRUE(restarted.message);
  EXPECT_TRUE(restarted.peer_restarted);
  EXPECT_FALSE(gate.admit(from(old_run, "robot2")).message);
  EXPECT_EQ(gate.rejected_by_reason().at("stale"), 1u);
}

TEST(MessageGate, IgnoresItsOwnEchoAndRefusesOthersMail) {
  MessageGate gate("robot2");
  MessageStamper self("robot2", 1), robot1("robot1", 1);
  const MessageGate::Verdict echo = gate.admit(from(self, ""));
  EXPECT_FALSE(echo.message);
  EXPECT_TRUE(echo.rejected.empty());
  EXPECT_FALSE(gate.admit(from(robot1, "robot3")).message);
  EXPECT_EQ(gate.rejected_by_reason().at("misdirected"), 1u);
  auto garbage = from(robot1, "robot2");
  garbage.resize(garbage.size() - 5);
  EXPECT_FALSE(gate.admit(garbage).message);
  EXPECT_EQ(gate.rejected_by_reason().at("malformed"), 1u);
  EXPECT_EQ(gate.rejected(), 2u);
}

TEST(MessageGate, InventedSendersCannotGrowItsMemory) {
  MessageGate gate("robot2", {}, 3);
  for (int i = 0; i < 5; ++i) {
    MessageStamper sender("robot" + std::to_string(10 + i), 1);
    gate.admit(from(sender, "robot2"));
  }
  EXPECT_EQ(gate.accepted(), 3u);
  EXPECT_EQ(gate.rejected_by_reason().at("too many senders"), 2u);
}

}  // namespace
}  // namespace dsswarm::protocol
