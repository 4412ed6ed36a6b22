#pragma once
// Shared set-up of the DDS Security tests: a scratch directory per test, keys
// made with the library, and security_test_peer processes on loopback.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/test_files.hpp"
#include "net/security/keystore.hpp"
#include "net/security/test/peer_process.hpp"

namespace dsswarm::sectest {

// Generous against a handshake of ~0.2 s on loopback: a loaded CI machine
// must not fail a positive test.
inline constexpr double kExchangeTimeoutS = 20.0;
// How long a refused peer is watched for any sample after the authorised
// peers have exchanged theirs (the handshake takes ~0.2 s here).
inline constexpr double kRefusalWindowS = 3.0;

class PeerFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_dir(std::string("security_dds_") +
                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override {
    for (std::size_t i = 0; i < peers_.size(); ++i) {
      peers_[i]->kill_now();
      peers_[i]->drain(0.0);
      if (HasFailure()) {  // keep what each peer printed next to its stderr
        std::string text;
        for (const auto& l : peers_[i]->lines()) text += l + "\n";
        test::write_text(root_ / (names_[i] + "." + std::to_string(i) + ".stdout"), text);
      }
    }
    peers_.clear();
    if (!HasFailure()) std::filesystem::remove_all(root_);
  }

  // A keys directory root_/dirname for swarm (= domain) `domain` with `robots`.
  std::filesystem::path make_keys(const std::string& dirname, int domain, const std::vector<std::string>& robots) {
    security::KeysInitOptions o;
    o.swarm_id = domain;
    const std::filesystem::path dir = root_ / dirname;
    security::init_keys(dir, o);
    for (const auto& r : robots) security::add_robot(dir, r);
    return dir;
  }

  // Starts a peer named `name` with keys from `keys` ("" = unsecured).
  PeerProcess& start(int domain, const std::string& name, const std::filesystem::path& keys,
                     std::vector<std::string> extra = {}) {
    std::vector<std::string> args{"--domain", std::to_string(domain), "--name", name, "--lifetime-s", "120"};
    if (!keys.empty()) args.insert(args.end(), {"--keys", keys.string()});
    args.insert(args.end(), extra.begin(), extra.end());
    const auto log = root_ / (name + "." + std::to_string(peers_.size()) + ".stderr");
    if (!launcher_.empty()) {  // e.g. ip netns exec NS security_test_peer ...
      args.insert(args.begin(), SECURITY_TEST_PEER);
      args.insert(args.begin(), launcher_.begin() + 1, launcher_.end());
    }
    peers_.push_back(std::make_unique<PeerProcess>(launcher_.empty() ? SECURITY_TEST_PEER : launcher_[0], args, log));
    names_.push_back(name);
    return *peers_.back();
  }

  std::filesystem::path root_;
  std::vector<std::unique_ptr<PeerProcess>> peers_;
  std::vector<std::string> names_;
  std::vector<std::string> launcher_;  // program and arguments that run the peer; empty: run it directly
};

// The origin names of every "first <origin> <incarnation> <ms>" line.
inline std::vector<std::string> senders_heard(const PeerProcess& p) {
  std::vector<std::string> out;
  for (const auto& l : p.lines_with("first ")) out.push_back(l.substr(6, l.find(' ', 6) - 6));
  return out;
}

}  // namespace dsswarm::sectest
