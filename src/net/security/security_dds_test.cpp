// DDS Security with the files `dsswarm keys` makes, through Cyclone DDS
// itself: secured peers (separate processes on loopback) exchange samples on a
// swarm topic; a peer from another CA, an unsecured one, a revoked one, and
// ones with expired or not-yet-valid grants never do. Each test uses its own
// domain id (160-169) so ctest -j can run them side by side.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "net/security/keystore.hpp"
#include "net/security/test/peer_fixture.hpp"

namespace dsswarm::sectest {
namespace {

namespace fs = std::filesystem;
using security::RobotKeyOptions;
using security::Validity;

bool heard(const PeerProcess& p, const std::string& origin) {
  const auto s = senders_heard(p);
  return std::find(s.begin(), s.end(), origin) != s.end();
}

class SecurityDdsTest : public PeerFixture {
 protected:
  // a and b (already started) hear each other; then, for the refusal
  // window, nobody hears `outsider` and `outsider` hears nobody.
  void expect_pair_and_refusal(PeerProcess& a, PeerProcess& b, PeerProcess& outsider, const std::string& name) {
    ASSERT_TRUE(a.wait_for("first b ", kExchangeTimeoutS)) << "a never heard b";
    ASSERT_TRUE(b.wait_for("first a ", kExchangeTimeoutS)) << "b never heard a";
    outsider.drain(kRefusalWindowS);
    a.drain(0.1);
    b.drain(0.1);
    EXPECT_FALSE(heard(a, name)) << "a heard " << name;
    EXPECT_FALSE(heard(b, name)) << "b heard " << name;
    EXPECT_TRUE(senders_heard(outsider).empty()) << name << " heard the swarm";
    EXPECT_TRUE(outsider.lines_with("matched 2").empty()) << name << "'s writer matched a swarm reader";
  }
};

TEST_F(SecurityDdsTest, SecuredPeersExchangeSamplesOnASwarmTopic) {
  const int domain = 160;
  const fs::path keys = make_keys("keys", domain, {"a", "b"});
  PeerProcess& a = start(domain, "a", keys);
  PeerProcess& b = start(domain, "b", keys);
  ASSERT_TRUE(a.wait_for("ready", kExchangeTimeoutS)) << "a: participant not created";
  EXPECT_TRUE(a.wait_for("first b ", kExchangeTimeoutS));
  EXPECT_TRUE(b.wait_for("first a ", kExchangeTimeoutS));
  EXPECT_EQ(a.stop(5), 0);
  EXPECT_EQ(b.stop(5), 0);
}

TEST_F(SecurityDdsTest, ACertificateFromAnotherCaNeverExchangesWithTheSwarm) {
  const int domain = 161;
  const fs::path keys = make_keys("keys", domain, {"a", "b"});
  const fs::path other = make_keys("other_ca", domain, {"mallory"});  // same swarm id, its own CA
  PeerProcess& mallory = start(domain, "mallory", other);
  PeerProcess& a = start(domain, "a", keys);
  PeerProcess& b = start(domain, "b", keys);
  ASSERT_TRUE(mallory.wait_for("ready", kExchangeTimeoutS)) << "mallory's own files are consistent";
  expect_pair_and_refusal(a, b, mallory, "mallory");
}

TEST_F(SecurityDdsTest, AnUnsecuredParticipantGetsNothing) {
  const int domain = 162;
  const fs::path keys = make_keys("keys", domain, {"a", "b"});
  PeerProcess& plain = start(domain, "plain", "");
  PeerProcess& a = start(domain, "a", keys);
  PeerProcess& b = start(domain, "b", keys);
  ASSERT_TRUE(plain.wait_for("ready", kExchangeTimeoutS));
  expect_pair_and_refusal(a, b, plain, "plain");
}

TEST_F(SecurityDdsTest, ARevokedRobotCannotJoinWhileOthersCan) {
  const int domain = 163;
  const fs::path keys = make_keys("keys", domain, {"a", "b", "c"});
  const fs::path before = root_ / "keys_before_revocation";  // what c still holds: the old CRL
  fs::copy(keys, before, fs::copy_options::recursive);
  security::revoke_robot(keys, "c");
  PeerProcess& c = start(domain, "c", before);
  PeerProcess& a = start(domain, "a", keys);
  PeerProcess& b = start(domain, "b", keys);
  ASSERT_TRUE(c.wait_for("ready", kExchangeTimeoutS)) << "c's old files still make a participant";
  expect_pair_and_refusal(a, b, c, "c");

  // Given the new CRL, c's own participant is refused outright.
  fs::copy_file(keys / "crl.pem", before / "crl.pem", fs::copy_options::overwrite_existing);
  PeerProcess& c_new_crl = start(domain, "c", before);
  EXPECT_TRUE(c_new_crl.wait_for("create-failed", kExchangeTimeoutS));
  EXPECT_EQ(c_new_crl.exit_code(kExchangeTimeoutS), 3);
}

TEST_F(SecurityDdsTest, ExpiredOrNotYetValidGrantsAndCertificatesAreRefused) {
  const int domain = 164;
  const fs::path keys = make_keys("keys", domain, {"ok"});
  const auto now = std::chrono::system_clock::now();
  const Validity past{now - std::chrono::hours(48), now - std::chrono::hours(1)};
  const Validity future{now + std::chrono::hours(1), now + std::chrono::hours(48)};
  RobotKeyOptions expired_grant, future_grant, expired_cert;
  expired_grant.permissions_validity = past;
  future_grant.permissions_validity = future;
  expired_cert.certificate_validity = past;
  security::add_robot(keys, "expired_grant", expired_grant);
  security::add_robot(keys, "future_grant", future_grant);
  security::add_robot(keys, "expired_cert", expired_cert);
  for (const std::string name : {"expired_grant", "future_grant", "expired_cert"}) {
    PeerProcess& p = start(domain, name, keys);
    EXPECT_TRUE(p.wait_for("create-failed", kExchangeTimeoutS)) << name;
    EXPECT_EQ(p.exit_code(kExchangeTimeoutS), 3) << name;
  }
  EXPECT_TRUE(start(domain, "ok", keys).wait_for("ready", kExchangeTimeoutS)) << "the control robot is accepted";
}

}  // namespace
}  // namespace dsswarm::sectest
