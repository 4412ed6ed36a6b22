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

#include "net/security/keystore.hpp"
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
  double restart_and_measure(PeerProcess& a, PeerProcess*& b, const fs::path& keys, int domain, int round) {
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
    const double s = restart_and_measure(a, b, keys, domain, round);
    std::printf("restart %d: exchange resumed after %.3f s\n", round + 1, s);
    EXPECT_GE(s, 0.0) << "restart " << round + 1 << ": no exchange within " << kResumeTimeoutS << " s";
    if (s < 0) break;
  }
}

// The watchdog end to end. A deterministic way to leave a peer alive in
// discovery but never matched: a's participant loads a CRL that lists x.
// The test then gives a's directory the CRL without x; a running
// participant keeps the CRL it loaded, so only recreating it (what the
// watchdog does when a peer stays unmatched) lets x in. b, with the CRL
// without x, talks to both all along.
class HandshakeWatchdogDdsTest : public PeerFixture {
 protected:
  struct Swarm {
    fs::path keys_a, keys_bx;
  };
  // a's directory has x revoked (crl.pem lists it); b's and x's do not.
  Swarm make_swarm(int domain) {
    const fs::path keys = make_keys("keys", domain, {"a", "b", "x"});
    const fs::path bx = root_ / "keys_bx";
    fs::copy(keys, bx, fs::copy_options::recursive);
    security::revoke_robot(keys, "x");
    return {keys, bx};
  }
  // Starts a with the CRL listing x loaded, then swaps in the one without.
  PeerProcess& start_a(int domain, const Swarm& s, std::vector<std::string> extra) {
    PeerProcess& a = start(domain, "a", s.keys_a, std::move(extra));
    EXPECT_TRUE(a.wait_for("ready", kExchangeTimeoutS));
    fs::copy_file(s.keys_bx / "crl.pem", s.keys_a / "crl.pem", fs::copy_options::overwrite_existing);
    return a;
  }
};

std::size_t index_of(const std::vector<std::string>& lines, const std::string& prefix) {
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind(prefix, 0) == 0) return i;
  return lines.size();
}

TEST_F(HandshakeWatchdogDdsTest, RecreatesTheParticipantWhenAPeerStaysUnmatchedAndTheExchangeResumes) {
  const int domain = 166;
  const Swarm s = make_swarm(domain);
  PeerProcess& a = start_a(domain, s, {"--recover-s", "2"});
  PeerProcess& b = start(domain, "b", s.keys_bx);
  PeerProcess& x = start(domain, "x", s.keys_bx);
  ASSERT_TRUE(a.wait_for("first b ", kExchangeTimeoutS));
  ASSERT_TRUE(a.wait_for("stuck ", kExchangeTimeoutS)) << "the watchdog never saw x stuck";
  ASSERT_TRUE(a.wait_for("recreated", kExchangeTimeoutS));
  EXPECT_TRUE(a.wait_for("first x ", kExchangeTimeoutS)) << "x still unheard after the recreation";
  EXPECT_TRUE(x.wait_for("first a ", kExchangeTimeoutS));
  EXPECT_LT(index_of(a.lines(), "recreated"), index_of(a.lines(), "first x ")) << "x was heard before: not stuck";
  // After the recreation a matches both peers again (its own reader + b + x).
  EXPECT_TRUE(a.wait_for("matched 3 ", kExchangeTimeoutS));
  EXPECT_TRUE(b.wait_for("first x ", kExchangeTimeoutS));
}

TEST_F(HandshakeWatchdogDdsTest, WithoutItThePeerStaysUnmatched) {
  const int domain = 167;
  const Swarm s = make_swarm(domain);
  PeerProcess& a = start_a(domain, s, {});
  PeerProcess& x = start(domain, "x", s.keys_bx);
  PeerProcess& b = start(domain, "b", s.keys_bx);
  ASSERT_TRUE(a.wait_for("first b ", kExchangeTimeoutS));
  ASSERT_TRUE(b.wait_for("first x ", kExchangeTimeoutS));
  a.drain(kRefusalWindowS + 2);
  EXPECT_TRUE(a.lines_with("first x ").empty()) << "a heard x without recreating its participant";
  EXPECT_TRUE(a.lines_with("recreated").empty());
  EXPECT_TRUE(x.lines_with("first a ").empty());
}

}  // namespace
}  // namespace dsswarm::sectest
