// `dsswarm keys ...` through the command line: what each command prints, and
// that bad input surfaces as the error main() turns into exit 1 or 2.
#include "apps/keys_command.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "apps/cli_test_util.hpp"
#include "common/errors.hpp"
#include "common/test_files.hpp"
#include "net/security/keys_index.hpp"
#include "net/security/openssl_util.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using test::run_cli;

class KeysCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One directory per test: ctest runs them in parallel processes.
    const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = (test::fresh_dir("keys_cli_" + name) / "swarm").string();
  }
  void TearDown() override { fs::remove_all(fs::path(dir_).parent_path()); }
  std::string dir_;
};

TEST_F(KeysCommandTest, InitAddRevokeReportWhatTheyDid) {
  const std::string init = run_cli(add_keys_command, {"keys", "init", dir_, "--swarm", "12", "--days", "90"});
  EXPECT_NE(init.find("swarm 12 keys in"), std::string::npos) << init;
  EXPECT_NE(init.find("DDS domain 12"), std::string::npos) << init;
  const std::string add = run_cli(add_keys_command, {"keys", "add", dir_, "robot1", "--days", "30"});
  EXPECT_NE(add.find("robot robot1: certificate serial 2 for CN=robot1,O=dsswarm-12"), std::string::npos) << add;
  const std::string revoke = run_cli(add_keys_command, {"keys", "revoke", dir_, "robot1"});
  EXPECT_NE(revoke.find("robot robot1 (serial 2) revoked"), std::string::npos) << revoke;
  const auto keys = security::load_swarm_keys(dir_);
  ASSERT_EQ(keys.robots.size(), 1u);
  EXPECT_TRUE(keys.robots[0].revoked_at.has_value());
}

TEST_F(KeysCommandTest, SignProtectionGoesIntoTheGovernance) {
  run_cli(add_keys_command, {"keys", "init", dir_, "--protection", "sign"});
  const std::string governance = security::read_text_file(security::KeysLayout{dir_}.governance_source());
  EXPECT_NE(governance.find("<rtps_protection_kind>SIGN</rtps_protection_kind>"), std::string::npos);
  EXPECT_NE(governance.find("<data_protection_kind>ENCRYPT</data_protection_kind>"), std::string::npos);
}

TEST_F(KeysCommandTest, BadArgumentsAreConfigErrors) {
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "init", dir_, "--swarm", "300"}), ConfigError);
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "init", dir_, "--protection", "rot13"}), ConfigError);
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "init", dir_, "--days", "-1"}), ConfigError);
  run_cli(add_keys_command, {"keys", "init", dir_});
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "add", dir_, "bad name"}), ConfigError);
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "add", dir_, "r1", "--days", "0"}), ConfigError);
}

TEST_F(KeysCommandTest, BadDirectoriesAndRobotsAreInputErrors) {
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "add", dir_, "r1"}), InputError);
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "revoke", dir_, "r1"}), InputError);
  run_cli(add_keys_command, {"keys", "init", dir_});
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "init", dir_}), InputError);
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "revoke", dir_, "r1"}), InputError);
  run_cli(add_keys_command, {"keys", "add", dir_, "r1"});
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "add", dir_, "r1"}), InputError);
}

TEST_F(KeysCommandTest, MissingArgumentsAreParseErrors) {
  EXPECT_THROW(run_cli(add_keys_command, {"keys"}), CLI::ParseError);
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "init"}), CLI::ParseError);
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "add", dir_}), CLI::ParseError);
  EXPECT_THROW(run_cli(add_keys_command, {"keys", "init", dir_, "--swarm", "one"}), CLI::ParseError);
}

}  // namespace
}  // namespace dsswarm
