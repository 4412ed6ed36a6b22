// Every bad input to the key tooling: the right error type, a message naming
// the problem, and nothing changed on disk.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <vector>

#include "common/errors.hpp"
#include "common/test_files.hpp"
#include "net/security/keystore.hpp"
#include "net/security/openssl_util.hpp"
#include "net/security/security_config.hpp"

namespace dsswarm::security {
namespace {

namespace fs = std::filesystem;

// Runs `f`, expects it to throw E with `fragment` in its message.
template <typename E>
void expect_error(const std::function<void()>& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one mentioning '" << fragment << "'";
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << "message: " << e.what();
  }
}

// Every file under `dir` with its contents, to check that nothing changed.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    files[e.path().string()] = e.is_regular_file() ? read_text_file(e.path()) : "<dir>";
  }
  return files;
}

class KeystoreErrorsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_dir(std::string("keystore_err_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    dir_ = root_ / "keys";
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_, dir_;
};

TEST_F(KeystoreErrorsTest, InitRefusesBadOptionsAndOccupiedDirectories) {
  KeysInitOptions bad_swarm;
  bad_swarm.swarm_id = 233;
  expect_error<ConfigError>([&] { init_keys(dir_, bad_swarm); }, "--swarm 233");
  KeysInitOptions bad_days;
  bad_days.days = 0;
  expect_error<ConfigError>([&] { init_keys(dir_, bad_days); }, "--days 0");
  expect_error<InputError>([&] { init_keys(root_ / "no" / "such" / "keys", {}); }, "does not exist");
  fs::create_directories(dir_);
  test::write_text(dir_ / "notes.txt", "x");
  expect_error<InputError>([&] { init_keys(dir_, {}); }, "not an empty directory");
  test::write_text(root_ / "file", "x");
  expect_error<InputError>([&] { init_keys(root_ / "file", {}); }, "not an empty directory");
  fs::remove_all(dir_);
  init_keys(dir_, {});
  const auto before = snapshot(dir_);
  expect_error<InputError>([&] { init_keys(dir_, {}); }, "already holds a swarm's keys");
  EXPECT_EQ(snapshot(dir_), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(root_), fs::directory_iterator()), 2);  // keys, file: no leftovers
}

TEST_F(KeystoreErrorsTest, InitIntoAnEmptyDirectoryWorks) {
  fs::create_directories(dir_);
  init_keys(dir_ / "", {});
  EXPECT_TRUE(fs::exists(KeysLayout{dir_}.index()));
}

TEST_F(KeystoreErrorsTest, AddAndRevokeNeedAKeysDirectory) {
  expect_error<InputError>([&] { add_robot(dir_, "r1"); }, "does not exist");
  expect_error<InputError>([&] { revoke_robot(dir_, "r1"); }, "does not exist");
  fs::create_directories(dir_);
  expect_error<InputError>([&] { add_robot(dir_, "r1"); }, "is not a dsswarm keys directory");
  test::write_text(dir_ / "swarm.json", "{\"format\": \"dsswarm-keys\", \"version\": 1, \"swarm_id\": ");
  expect_error<InputError>([&] { add_robot(dir_, "r1"); }, "swarm.json");
  test::write_text(dir_ / "swarm.json", "{\"format\": \"something-else\"}");
  expect_error<InputError>([&] { add_robot(dir_, "r1"); }, "not a dsswarm keys index");
  EXPECT_FALSE(fs::exists(dir_ / "robots"));
}

TEST_F(KeystoreErrorsTest, RobotNamesAreChecked) {
  init_keys(dir_, {});
  const auto before = snapshot(dir_);
  for (const std::string& name : std::vector<std::string>{"", "a b", "../x", "x/y", "-x", "_x", "r\xc3\xa9", "a,O=evil", std::string(64, 'a')}) {
    expect_error<ConfigError>([&] { add_robot(dir_, name); }, "robot name");
    expect_error<ConfigError>([&] { revoke_robot(dir_, name); }, "robot name");
  }
  EXPECT_EQ(snapshot(dir_), before);
  add_robot(dir_, std::string(63, 'a'));
  add_robot(dir_, "Robot_7-b");
}

TEST_F(KeystoreErrorsTest, AddRefusesExistingAndRevokedNames) {
  init_keys(dir_, {});
  add_robot(dir_, "r1");
  expect_error<InputError>([&] { add_robot(dir_, "r1"); }, "already has keys");
  revoke_robot(dir_, "r1");
  expect_error<InputError>([&] { add_robot(dir_, "r1"); }, "was revoked");
  fs::create_directories(dir_ / "robots" / "stray");
  expect_error<InputError>([&] { add_robot(dir_, "stray"); }, "not in swarm.json");
  RobotKeyOptions too_long;
  too_long.days = 5000;
  expect_error<ConfigError>([&] { add_robot(dir_, "r2", too_long); }, "past the swarm CA's expiry");
  EXPECT_EQ(load_swarm_keys(dir_).robots.size(), 1u);
}

TEST_F(KeystoreErrorsTest, RevokeRefusesUnknownAndAlreadyRevokedRobots) {
  init_keys(dir_, {});
  add_robot(dir_, "r1");
  expect_error<InputError>([&] { revoke_robot(dir_, "r9"); }, "no robot r9");
  revoke_robot(dir_, "r1");
  const auto before = snapshot(dir_);
  expect_error<InputError>([&] { revoke_robot(dir_, "r1"); }, "already revoked");
  EXPECT_EQ(snapshot(dir_), before);
}

TEST_F(KeystoreErrorsTest, AFailedAddLeavesNoTrace) {
  init_keys(dir_, {});
  test::write_text(dir_ / "ca_key.pem", "-----BEGIN PRIVATE KEY-----\ngarbage\n-----END PRIVATE KEY-----\n");
  const auto before = snapshot(dir_);
  expect_error<InputError>([&] { add_robot(dir_, "r1"); }, "ca_key.pem");
  EXPECT_EQ(snapshot(dir_), before);
}

TEST_F(KeystoreErrorsTest, SecurityConfigRefusesUnknownRevokedOrIncompleteRobots) {
  init_keys(dir_, {});
  expect_error<InputError>([&] { security_config_xml(dir_, "r1"); }, "no robot r1");
  add_robot(dir_, "r1");
  add_robot(dir_, "r2");
  fs::remove(dir_ / "robots" / "r2" / "key.pem");
  expect_error<InputError>([&] { security_config_xml(dir_, "r2"); }, "key.pem is missing");
  revoke_robot(dir_, "r1");
  expect_error<InputError>([&] { security_config_xml(dir_, "r1"); }, "was revoked");
  expect_error<ConfigError>([&] { security_config_xml(dir_, "../r1"); }, "robot name");
}

}  // namespace
}  // namespace dsswarm::security
