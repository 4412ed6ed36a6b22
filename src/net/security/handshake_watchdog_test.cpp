#include "net/security/handshake_watchdog.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"

namespace dsswarm::security {
namespace {

using Clock = HandshakeWatchdog::Clock;

class HandshakeWatchdogTest : public ::testing::Test {
 protected:
  HandshakeWatchdogConfig config() const {
    HandshakeWatchdogConfig c;
    c.stuck_after_s = 10;
    c.first_backoff_s = 30;
    c.max_backoff_s = 100;
    return c;
  }
  Clock::time_point at(double s) const { return t0_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s)); }

  Clock::time_point t0_ = Clock::now();
};

TEST_F(HandshakeWatchdogTest, APeerThatMatchesInTimeIsNeverStuck) {
  HandshakeWatchdog w(config());
  EXPECT_FALSE(w.update({"b"}, {}, at(0)));
  EXPECT_FALSE(w.update({"b"}, {"b"}, at(9)));
  EXPECT_FALSE(w.update({"b"}, {"b"}, at(100)));
  EXPECT_TRUE(w.stuck(at(100)).empty());
}

TEST_F(HandshakeWatchdogTest, APeerAliveButUnmatchedTooLongAsksForARecreation) {
  HandshakeWatchdog w(config());
  EXPECT_FALSE(w.update({"a", "b"}, {"a"}, at(0)));
  EXPECT_FALSE(w.update({"a", "b"}, {"a"}, at(9.9)));
  EXPECT_TRUE(w.update({"a", "b"}, {"a"}, at(10)));
  EXPECT_EQ(w.stuck(at(10)), std::vector<std::string>{"b"});
}

TEST_F(HandshakeWatchdogTest, APeerThatLeavesStopsCounting) {
  HandshakeWatchdog w(config());
  w.update({"b"}, {}, at(0));
  EXPECT_FALSE(w.update({}, {}, at(5)));
  EXPECT_FALSE(w.update({"b"}, {}, at(12)));  // back: its clock starts again
  EXPECT_TRUE(w.update({"b"}, {}, at(22)));
}

TEST_F(HandshakeWatchdogTest, RecreationsBackOffExponentiallyUpToTheCap) {
  HandshakeWatchdog w(config());
  w.update({"x"}, {}, at(0));  // x never matches (an intruder, say)
  double t = 10;
  std::vector<double> recreations;
  for (; t < 400; t += 0.5) {
    if (w.update({"x"}, {}, at(t))) {
      recreations.push_back(t);
      w.recreated(at(t));
    }
  }
  // First at 10 s; then every backoff (30, 60, then capped at 100).
  EXPECT_EQ(recreations, (std::vector<double>{10, 40, 100, 200, 300}));
  EXPECT_EQ(w.recreations(), 5u);
}

TEST_F(HandshakeWatchdogTest, AfterARecreationMatchedPeersGetTimeToMatchTheNewParticipant) {
  HandshakeWatchdog w(config());
  w.update({"a", "b"}, {"a"}, at(0));
  ASSERT_TRUE(w.update({"a", "b"}, {"a"}, at(10)));
  w.recreated(at(10));
  // a has not matched the new participant yet: not stuck before another 10 s.
  EXPECT_TRUE(w.stuck(at(15)).empty());
  EXPECT_FALSE(w.update({"a", "b"}, {}, at(15)));
  EXPECT_FALSE(w.update({"a", "b"}, {"a", "b"}, at(16)));  // both recovered
  EXPECT_TRUE(w.stuck(at(60)).empty());
}

TEST_F(HandshakeWatchdogTest, BackoffResetsOnceEveryPeerIsMatched) {
  HandshakeWatchdog w(config());
  w.update({"b"}, {}, at(0));
  ASSERT_TRUE(w.update({"b"}, {}, at(10)));
  w.recreated(at(10));  // next allowed at 40, backoff now 60
  w.update({"b"}, {"b"}, at(11));  // healthy: backoff back to 30
  w.update({"b", "c"}, {"b"}, at(50));  // c arrives and sticks
  ASSERT_TRUE(w.update({"b", "c"}, {"b"}, at(60)));
  w.recreated(at(60));
  EXPECT_FALSE(w.update({"b", "c"}, {"b"}, at(89)));
  EXPECT_TRUE(w.update({"b", "c"}, {"b"}, at(90)));  // 30 s after, not 60
}

TEST_F(HandshakeWatchdogTest, BadConfigIsRefused) {
  HandshakeWatchdogConfig c;
  c.stuck_after_s = 0;
  EXPECT_THROW(HandshakeWatchdog{c}, ConfigError);
  c = {};
  c.max_backoff_s = c.first_backoff_s / 2;
  EXPECT_THROW(HandshakeWatchdog{c}, ConfigError);
}

}  // namespace
}  // namespace dsswarm::security
