// Cyclone DDS 0.10.2 can fail to redo the security handshake after a peer
// restarts (cyclonedds #1895). This test does exactly that, on loopback: A and
// B exchange samples, B is killed with SIGKILL (no goodbye: A still holds B's
// old participant until its lease expires) and started again with the same
// identity, several times; the exchange must resume within kResumeTimeoutS
// each time. It prints how long each resumption took; run it many times with
// --gtest_repeat=N (docs/security.md has the figures).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include "net/security/test/peer_fixture.hpp"

namespace dsswarm::sectest {
namespace {

namespace fs = std::filesystem;

constexpr int kRestarts = 3;
// A resumption takes ~0.2 s here; the lease (10 s) is the longest any stale
// state should matter.
constexpr double kResumeTimeoutS = 15.0;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

class SecurityRestartTest : public PeerFixture {
 protected:
  // Kills `b`, restarts it, and returns the seconds until samples flow both
  // ways again (A hears B's new incarnation: its `round`+1-th "first b").
  double restart_and_measure(PeerProcess& a, PeerProcess*& b, const fs::path& keys, int domain, int round,
                             const std::vector<std::string>& a_extra) {
    (void)a_extra;
    b->kill_now();
    const auto t0 = Clock::now();
    b = &start(domain, "b", keys);
    const bool a_hears = a.wait_for("first b ", kResumeTimeoutS, static_cast<std::size_t>(round) + 2).has_value();
    const bool b_hears = b->wait_for("first a ", kResumeTimeoutS - seconds_since(t0)).has_value();
    return a_hears && b_hears ? seconds_since(t0) : -1.0;
  }
};

TEST_F(SecurityRestartTest, ExchangeResumesAfterAPeerIsKilledAndRestartedWithTheSameIdentity) {
  const int domain = 165;
  const fs::path keys = make_keys("keys", domain, {"a", "b"});
  PeerProcess& a = start(domain, "a", keys);
  PeerProcess* b = &start(domain, "b", keys);
  ASSERT_TRUE(a.wait_for("first b ", kExchangeTimeoutS));
  ASSERT_TRUE(b->wait_for("first a ", kExchangeTimeoutS));
  for (int round = 0; round < kRestarts; ++round) {
    const double s = restart_and_measure(a, b, keys, domain, round, {});
    std::printf("restart %d: exchange resumed after %.3f s\n", round + 1, s);
    EXPECT_GE(s, 0.0) << "restart " << round + 1 << ": no exchange within " << kResumeTimeoutS << " s";
    if (s < 0) break;
  }
}

}  // namespace
}  // namespace dsswarm::sectest
