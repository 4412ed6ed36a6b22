#include "agent/send_queue.hpp"

#include <gtest/gtest.h>

#include <set>

namespace dsswarm::agent {
namespace {

// A link whose peers' inboxes are full (refuse) or gone (unreachable) as the test says.
class FakeLink : public protocol::SwarmLink {
 public:
  bool send(const std::string& recipient, std::span<const std::uint8_t> bytes) override {
    if (gone.contains(recipient) || full.contains(recipient)) return false;
    sent.emplace_back(recipient, bytes.empty() ? -1 : bytes[0]);
    return true;
  }
  bool reachable(const std::string& recipient) override { return !gone.contains(recipient); }
  std::vector<std::vector<std::uint8_t>> receive(std::chrono::milliseconds) override { return {}; }
  void wake() override {}

  std::set<std::string> full, gone;
  std::vector<std::pair<std::string, int>> sent;
};

std::vector<std::uint8_t> message(int k) { return {static_cast<std::uint8_t>(k)}; }

TEST(SendQueue, ABusyPeersMessagesWaitAndGoOutInOrderWhenItsInboxTakesThem) {
  FakeLink link;
  SendQueue queue(30.0);
  link.full.insert("b");
  queue.send(link, "b", message(1), 0.0);
  queue.send(link, "c", message(2), 0.0);  // another peer is not held up
  queue.send(link, "b", message(3), 0.1);
  queue.retry(link, 1.0);
  EXPECT_EQ(queue.waiting(), 2u);
  EXPECT_TRUE(queue.take_given_up().empty());
  link.full.clear();
  queue.send(link, "b", message(4), 2.0);  // behind the waiting ones, not ahead of them
  queue.retry(link, 2.0);
  EXPECT_EQ(queue.waiting(), 0u);
  EXPECT_EQ(queue.deferred(), 3u);
  const std::vector<std::pair<std::string, int>> expected{{"c", 2}, {"b", 1}, {"b", 3}, {"b", 4}};
  EXPECT_EQ(link.sent, expected);
  EXPECT_TRUE(queue.take_given_up().empty());
}

TEST(SendQueue, APeerThatIsGoneOrTakesNothingForTooLongIsGivenUp) {
  FakeLink link;
  SendQueue queue(5.0);
  link.gone.insert("ghost");
  queue.send(link, "ghost", message(1), 0.0);
  queue.send(link, "ghost", message(2), 0.0);  // dropped with it, not tried again
  link.full.insert("busy");
  queue.send(link, "busy", message(3), 0.0);
  queue.retry(link, 4.0);
  auto given_up = queue.take_given_up();
  ASSERT_EQ(given_up.size(), 1u);
  EXPECT_EQ(given_up[0].first, "ghost");
  EXPECT_NE(given_up[0].second.find("cannot be reached"), std::string::npos) << given_up[0].second;
  queue.retry(link, 5.5);
  given_up = queue.take_given_up();
  ASSERT_EQ(given_up.size(), 1u);
  EXPECT_EQ(given_up[0].first, "busy");
  EXPECT_NE(given_up[0].second.find("took no message for 5 s"), std::string::npos) << given_up[0].second;
  EXPECT_EQ(queue.waiting(), 0u);
  EXPECT_TRUE(link.sent.empty());
  // A peer that leaves while its messages wait is given up at the next retry.
  queue.send(link, "busy", message(4), 6.0);
  link.gone.insert("busy");
  queue.retry(link, 6.1);
  EXPECT_EQ(queue.take_given_up().size(), 1u);
}

TEST(SendQueue, ProgressKeepsABusyPeerAndForgetDropsWhatWaits) {
  FakeLink link;
  SendQueue queue(5.0);
  link.full.insert("b");
  queue.send(link, "b", message(1), 0.0);
  queue.send(link, "b", message(2), 0.0);
  link.full.clear();
  queue.retry(link, 4.0);  // both out: the clock starts again
  link.full.insert("b");
  queue.send(link, "b", message(3), 4.0);
  queue.retry(link, 8.0);  // 4 s since progress: kept
  EXPECT_TRUE(queue.take_given_up().empty());
  EXPECT_EQ(queue.waiting(), 1u);
  queue.forget("b");
  EXPECT_EQ(queue.waiting(), 0u);
  link.full.clear();
  queue.retry(link, 9.0);
  EXPECT_EQ(link.sent.size(), 2u);
}

}  // namespace
}  // namespace dsswarm::agent
