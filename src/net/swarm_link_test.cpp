#include "net/swarm_link.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "net/net_test_util.hpp"

namespace dsswarm::net {
namespace {

using namespace std::chrono_literals;

std::vector<std::vector<std::uint8_t>> receive_for(DdsSwarmLink& link, std::size_t want, std::chrono::milliseconds max) {
  std::vector<std::vector<std::uint8_t>> got;
  const auto until = std::chrono::steady_clock::now() + max;
  while (got.size() < want && std::chrono::steady_clock::now() < until)
    for (auto& m : link.receive(100ms)) got.push_back(std::move(m));
  return got;
}

SwarmLinkConfig robot(const std::string& name, const std::string& swarm = "s1") {
  SwarmLinkConfig c;
  c.name = name;
  c.partition = swarm_partition(swarm + "_" + std::to_string(getpid()));
  return c;
}

TEST(DdsSwarmLink, MessagesReachTheirRecipientOnlyAndBroadcastsReachEveryone) {
  Participant p(test::loopback_config());
  DdsSwarmLink a(p, robot("a")), b(p, robot("b")), c(p, robot("c"));
  const std::vector<std::uint8_t> to_b(100000, 7);  // larger than a UDP datagram
  ASSERT_TRUE(a.send("b", to_b));
  const auto at_b = receive_for(b, 1, 5s);
  ASSERT_EQ(at_b.size(), 1u);
  EXPECT_EQ(at_b[0], to_b);
  EXPECT_TRUE(c.receive(300ms).empty());  // not for c
  std::this_thread::sleep_for(200ms);     // best-effort heartbeats: let discovery settle
  ASSERT_TRUE(a.send("", std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_EQ(receive_for(b, 1, 3s).size(), 1u);
  EXPECT_EQ(receive_for(c, 1, 3s).size(), 1u);
}

TEST(DdsSwarmLink, SwarmsSharingADomainNeverSeeEachOther) {
  Participant p(test::loopback_config());
  DdsSwarmLink a(p, robot("a", "blue")), b(p, robot("b", "blue")), intruder(p, robot("b", "red"));
  ASSERT_TRUE(a.send("b", std::vector<std::uint8_t>{42}));
  EXPECT_EQ(receive_for(b, 1, 3s).size(), 1u);
  EXPECT_TRUE(intruder.receive(500ms).empty());
}

TEST(DdsSwarmLink, ARobotNobodyListensForIsReportedUnreachable) {
  Participant p(test::loopback_config());
  SwarmLinkConfig c = robot("a");
  c.match_wait = 300ms;
  DdsSwarmLink a(p, c);
  EXPECT_FALSE(a.send("nobody", std::vector<std::uint8_t>{1}));
  EXPECT_FALSE(a.send("not a name", std::vector<std::uint8_t>{1}));
}

TEST(DdsSwarmLink, WakeEndsAWaitingReceive) {
  Participant p(test::loopback_config());
  DdsSwarmLink a(p, robot("a"));
  std::thread waker([&] {
    std::this_thread::sleep_for(100ms);
    a.wake();
  });
  const auto t0 = std::chrono::steady_clock::now();
  a.receive(10s);
  waker.join();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 5s);
  EXPECT_THROW(DdsSwarmLink(p, robot("bad name")), ConfigError);
}

}  // namespace
}  // namespace dsswarm::net
