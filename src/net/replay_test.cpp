// `dsswarm replay` as a separate process on loopback, read back by a
// LiveScanSource in this one; and its pacing.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "apps/replay_command.hpp"
#include "io/logs/carmen_writer.hpp"
#include "io/logs/log_reader.hpp"
#include "net/net_test_util.hpp"
#include "net/ros2_input.hpp"

extern char** environ;

namespace dsswarm::net {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

constexpr auto kReplayTimeout = 10s;
using test::bits;

// A child process, killed and reaped if the test ends before it does.
class Child {
 public:
  Child(const std::vector<std::string>& args, const fs::path& out) {
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    if (posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Child() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  bool started() const { return pid_ > 0; }
  void signal(int sig) const { kill(pid_, sig); }
  // The exit code (128 + signal if killed by one), or nullopt after `timeout`.
  std::optional<int> wait(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(10ms);
    }
    return std::nullopt;
  }

 private:
  pid_t pid_ = -1;
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A small CARMEN log: 40 scans at 20 Hz, 180 beams, odometry, a laser offset.
fs::path write_test_log(const fs::path& dir) {
  std::vector<LaserScan> scans;
  for (int i = 0; i < 40; ++i) {
    LaserScan s;
    s.timestamp = 966647577.1234 + 0.05 * i;
    s.angle_min = -std::numbers::pi / 2;
    s.angle_increment = std::numbers::pi / 179;
    s.range_min = 0.0;
    s.range_max = 80.0;
    for (int b = 0; b < 180; ++b) s.ranges.push_back(b == 7 ? 81.91f : 0.5f + 0.013f * static_cast<float>(b + i));
    s.odometry = Pose2(0.03 * i, 0.01 * i, 0.005 * i);
    s.laser_offset = Pose2(0.04, 0.0, 0.0);
    scans.push_back(s);
  }
  const fs::path log = dir / "replay.log";
  write_carmen(log, scans);
  return log;
}

struct ReplayTest : testing::Test {
  void SetUp() override {
    dir = fs::path(DSSWARM_TEST_TMP) / ("replay_" + test::test_id());
    fs::create_directories(dir);
    log = write_test_log(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  std::vector<std::string> replay_args(std::vector<std::string> extra) const {
    std::vector<std::string> args = {DSSWARM_CLI,  "replay",    log.string(),
                                     "--namespace", test::test_namespace(), "--domain",
                                     std::to_string(test::test_domain()), "--interface", "lo"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }

  fs::path dir, log;
};

TEST_F(ReplayTest, ALiveSourceGetsTheScansReadLogReads) {
  const SensorLog expected = read_log(log);
  Participant agent(test::loopback_config());
  LiveInputConfig config;
  config.ns = test::test_namespace();
  config.queue_capacity = 64;
  config.wait_for_odometry = 5.0;  // a loaded machine may deliver a scan's odometry after the default 0.25 s
  // replay publishes reliably: read it so, or a loaded machine may lose a
  // sample from the best-effort reader's short history (the last scan's
  // odometry then never comes), and this test checks every sample's content.
  config.reliable = true;
  LiveScanSource input(agent, config);
  Child replay(replay_args({"--rate", "5", "--wait-for-subscribers", "1"}), dir / "replay.out");
  ASSERT_TRUE(replay.started());

  for (const LaserScan& want : expected.scans) {
    const std::optional<LaserScan> got = input.next(kReplayTimeout);
    ASSERT_TRUE(got.has_value()) << read_text(dir / "replay.out");
    EXPECT_NEAR(got->timestamp, want.timestamp, 1e-6);
    EXPECT_EQ(bits(got->ranges), bits(want.ranges));
    EXPECT_FLOAT_EQ(static_cast<float>(got->angle_min), static_cast<float>(want.angle_min));
    EXPECT_FLOAT_EQ(static_cast<float>(got->angle_increment), static_cast<float>(want.angle_increment));
    EXPECT_FLOAT_EQ(static_cast<float>(got->range_max), static_cast<float>(want.range_max));
    ASSERT_TRUE(got->odometry.has_value());
    EXPECT_NEAR(got->odometry->x, want.odometry->x, 1e-9);
    EXPECT_NEAR(got->odometry->y, want.odometry->y, 1e-9);
    EXPECT_NEAR(got->odometry->theta, want.odometry->theta, 1e-9);
    EXPECT_NEAR(got->laser_offset.x, want.laser_offset.x, 1e-9);
    EXPECT_NEAR(got->laser_offset.theta, want.laser_offset.theta, 1e-9);
  }
  EXPECT_EQ(replay.wait(kReplayTimeout), 0) << read_text(dir / "replay.out");
  EXPECT_EQ(input.stats().scans_dropped, 0u);
  EXPECT_NE(read_text(dir / "replay.out").find("replayed 40 scans"), std::string::npos);
}

TEST_F(ReplayTest, SigintEndsALoopingReplayCleanly) {
  Participant agent(test::loopback_config());
  LiveInputConfig config;
  config.ns = test::test_namespace();
  LiveScanSource input(agent, config);
  Child replay(replay_args({"--loop", "--rate", "4", "--wait-for-subscribers", "1"}), dir / "replay.out");
  ASSERT_TRUE(replay.started());
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(input.next(kReplayTimeout).has_value()) << "scan " << i;  // past one loop
  replay.signal(SIGINT);
  EXPECT_EQ(replay.wait(kReplayTimeout), 0) << read_text(dir / "replay.out");
  EXPECT_NE(read_text(dir / "replay.out").find("interrupted after"), std::string::npos);
}

TEST_F(ReplayTest, NoSubscriberInTimeIsAnError) {
  Child replay(replay_args({"--wait-for-subscribers", "1", "--wait-timeout", "0.3"}), dir / "replay.out");
  ASSERT_TRUE(replay.started());
  EXPECT_EQ(replay.wait(kReplayTimeout), 1);
  EXPECT_NE(read_text(dir / "replay.out").find("error: replay: fewer than 1 subscriber"), std::string::npos)
      << read_text(dir / "replay.out");
}

TEST_F(ReplayTest, BadSettingsAreConfigErrors) {
  for (const auto& [option, value] : std::vector<std::pair<std::string, std::string>>{
           {"--rate", "0"}, {"--start", "-1"}, {"--domain", "300"}, {"--namespace", "/bad name"}}) {
    // Nothing is published: each setting fails before the first scan.
    Child replay({DSSWARM_CLI, "replay", log.string(), "--interface", "lo", option, value}, dir / "replay.out");
    ASSERT_TRUE(replay.started());
    EXPECT_EQ(replay.wait(kReplayTimeout), 2) << option;
    EXPECT_NE(read_text(dir / "replay.out").find("error: "), std::string::npos) << read_text(dir / "replay.out");
  }
}

// A whole real log through `replay` and a LiveScanSource: the scans read_log
// reads, in order. DSSWARM_REPLAY_LOG / DSSWARM_REPLAY_RATE pick another log.
TEST_F(ReplayTest, RealDataLogArrivesWhole) {
  const char* chosen = std::getenv("DSSWARM_REPLAY_LOG");
  const fs::path real = chosen ? fs::path(chosen) : fs::path(DSSWARM_SHARED_DATA) / "carmen/fr079.log.gz";
  if (!fs::exists(real)) GTEST_SKIP() << "real data not found at " << real.string();
  const char* rate = std::getenv("DSSWARM_REPLAY_RATE");
  const SensorLog expected = read_log(real);
  Participant agent(test::loopback_config());
  LiveInputConfig config;
  config.ns = test::test_namespace();
  config.queue_capacity = expected.scans.size();  // a loaded machine may not keep up with 200x: keep every scan
  config.wait_for_odometry = 5.0;  // nor deliver a scan's odometry within the default 0.25 s: wait for it
  LiveScanSource input(agent, config);
  log = real;
  Child replay(replay_args({"--rate", rate ? rate : "200", "--wait-for-subscribers", "1"}), dir / "replay.out");
  ASSERT_TRUE(replay.started());
  std::size_t same_odometry = 0, backwards = 0;
  double newest = -1e300;
  for (const LaserScan& want : expected.scans) {
    const std::optional<LaserScan> got = input.next(kReplayTimeout);
    ASSERT_TRUE(got.has_value()) << read_text(dir / "replay.out");
    ASSERT_NEAR(got->timestamp, want.timestamp, 1e-6);
    ASSERT_EQ(bits(got->ranges), bits(want.ranges));
    EXPECT_NEAR(got->laser_offset.x, want.laser_offset.x, 1e-9);
    backwards += want.timestamp < newest ? 1 : 0;
    newest = std::max(newest, want.timestamp);
    ASSERT_TRUE(got->odometry.has_value());
    const Pose2 d = between(*want.odometry, *got->odometry);
    same_odometry += std::hypot(d.x, d.y) < 1e-6 && std::abs(d.theta) < 1e-6 ? 1 : 0;
  }
  EXPECT_EQ(replay.wait(kReplayTimeout), 0) << read_text(dir / "replay.out");
  // A scan stamped before an earlier one may be interpolated between its neighbours.
  EXPECT_GE(same_odometry + backwards, expected.scans.size());
  std::cout << expected.scans.size() << " scans, " << backwards << " stamped backwards, " << same_odometry
            << " with exactly their odometry\n";
}

TEST(ReplaySchedule, BackwardStampsGoOutAtOnceAndStartSkips) {
  const std::vector<double> stamps = {10.0, 10.5, 10.2, 11.0, 12.0};
  const std::vector<std::optional<double>> all = {0.0, 0.25, 0.25, 0.5, 1.0};
  EXPECT_EQ(replay_schedule(stamps, 2.0, 0.0), all);
  const std::vector<std::optional<double>> later = {std::nullopt, std::nullopt, std::nullopt, 0.0, 1.0};
  EXPECT_EQ(replay_schedule(stamps, 1.0, 1.0), later);
  EXPECT_TRUE(replay_schedule({}, 1.0, 0.0).empty());
}

}  // namespace
}  // namespace dsswarm::net
