// A log mapped two ways: `dsswarm run LOG` reads the file; `dsswarm agent`
// gets the same scans live, as ROS 2 LaserScan + Odometry that `dsswarm
// replay LOG` publishes over DDS on loopback. The agent's trajectory must be
// the run's.
#include <gtest/gtest.h>
#include <signal.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <iostream>
#include <sstream>

#include "eval/ate.hpp"
#include "eval/relations.hpp"
#include "io/logs/carmen_writer.hpp"
#include "io/logs/log_reader.hpp"
#include "multiprocess.hpp"
#include "sim/scenario.hpp"
#include "swarm/swarm_agent.hpp"

namespace dsswarm::mp {
namespace {

// How far one trajectory is from another: ATE (rigidly aligned) and the
// relation metric over consecutive poses (the step-to-step motions).
struct Difference {
  AteResult ate;
  RelationMetrics steps;
};

Difference difference(const Trajectory& estimate, const Trajectory& reference) {
  std::vector<Relation> steps;
  for (std::size_t i = 1; i < reference.size(); ++i)
    steps.push_back({reference[i - 1].timestamp, reference[i].timestamp,
                     between(reference[i - 1].pose, reference[i].pose)});
  return {evaluate_ate(estimate, reference, 1e-3), evaluate_relations(estimate, steps, 1e-3)};
}

std::string describe(const Difference& d) {
  return fmt::format("ATE RMSE {:.1f} mm (max {:.1f} mm), step error mean {:.2f} mm / {:.3f}°",
                     1000.0 * d.ate.rmse, 1000.0 * d.ate.max, 1000.0 * d.steps.trans_mean, d.steps.rot_mean_deg);
}

class ReplayVsRun {
 public:
  // Both with loop closure on (a robot's default is off, run's on), so that
  // the agent's background loop closing and its optimized trajectory are
  // what is compared.
  ReplayVsRun(Rig& rig, fs::path log)
      : rig_(rig), log_(std::move(log)), scans_(read_log(log_).scans.size()), config_(rig_.dir() / "loop_closure.json") {
    std::ofstream(config_) << R"({"loop_closure": {"enabled": true}})";
  }

  // `dsswarm run LOG [--seed S]`: its trajectory.
  Trajectory run(const std::string& name, const std::vector<std::string>& extra = {}) {
    const fs::path out = rig_.dir() / name;
    std::vector<std::string> args{"run", log_.string(), "--out", out.string(), "--config", config_.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const std::size_t p = rig_.start(name, args);
    EXPECT_EQ(rig_.wait(p, 180s), 0);
    return read_tum(out / "trajectory.tum");
  }

  // An agent on live topics, `replay LOG --rate R` feeding it; every scan
  // processed, then SIGTERM: its trajectory.
  Trajectory replayed(double rate) {
    const fs::path out = rig_.dir() / "agent";
    const std::string ns = fmt::format("/replayed_{}", getpid());
    const std::string ros_domain = std::to_string(test_domain(1)), swarm_domain = std::to_string(test_domain(0));
    // A queue that holds the whole log and reliable input: nothing is
    // skipped or lost, whatever the load (best effort, as from a lidar
    // driver, lost one scan in 400 on a busy machine), so that the agent sees
    // exactly the scans `run` does.
    const std::size_t agent =
        rig_.start("agent", {"agent", "--name", "robot1", "--out", out.string(), "--namespace", ns, "--ros-domain",
                             ros_domain, "--swarm-domain", swarm_domain, "--interface", "lo",
                             "--no-ros-output", "--queue", "10000", "--reliable-input", "--config", config_.string()});
    const std::size_t replay =
        rig_.start("replay", {"replay", log_.string(), "--namespace", ns, "--domain", ros_domain, "--interface", "lo",
                              "--rate", fmt::format("{}", rate), "--wait-for-subscribers", "1", "--wait-timeout", "60"});
    EXPECT_EQ(rig_.wait(replay, 240s), 0);
    // A live agent runs until told: stop it once its heartbeat says it has
    // processed every scan (its queue may still hold some when replay ends).
    const bool all_processed = wait_until([&] { return heard_processed(swarm_domain) >= scans_; }, 120s);
    rig_.group().signal(agent, SIGTERM);
    EXPECT_EQ(rig_.wait(agent, 60s), 0);
    EXPECT_TRUE(all_processed) << "the agent did not process all " << scans_ << " scans";
    const nlohmann::json stats = read_json(out / "stats.json");
    EXPECT_EQ(stats.at("scans_received").get<std::size_t>(), scans_) << "scans lost between replay and agent";
    EXPECT_EQ(stats.at("scans_skipped").get<std::size_t>(), 0u);
    return read_tum(out / "trajectory.tum");
  }

  std::size_t scans() const { return scans_; }

 private:
  // Scans robot1 has processed, as `dsswarm status` hears it (0 if unheard).
  std::size_t heard_processed(const std::string& swarm_domain) {
    const std::size_t status = rig_.start("status", {"status", "--swarm-domain", swarm_domain, "--interface", "lo",
                                                     "--timeout", "2"});
    if (rig_.wait(status, 30s) != 0) return 0;
    std::istringstream table(rig_.log_tail("status", 4));  // the log grows by one table a call
    std::size_t processed = 0;
    for (std::string line; std::getline(table, line);) {
      std::istringstream row(line);
      std::vector<std::string> cells{std::istream_iterator<std::string>(row), {}};
      // AGENT STATE HEARD UPTIME SCANS/S PROCESSED ...
      if (cells.size() > 5 && cells[0] == "robot1") processed = std::strtoul(cells[5].c_str(), nullptr, 10);
    }
    return processed;
  }

  Rig& rig_;
  fs::path log_;
  std::size_t scans_;
  fs::path config_;
};

// Replays `log` at `rate` into an agent named robot1 and compares its
// trajectory with `run`'s. An agent seeds its matcher per robot (peers must
// not draw the same numbers), so the reference is `run` with robot1's seed:
// the same scans give the same trajectory, except that ROS messages carry
// stamps in nanoseconds and headings as quaternions, an ulp can tip a
// Monte-Carlo match, and from there on the two drift apart as runs with
// different seeds do. Matching
// noise is measured on the same log: `run` with two other seeds against the
// reference; the agent must stay within the larger.
void expect_replayed_like_run(Rig& rig, const fs::path& log, double rate) {
  ReplayVsRun r(rig, log);
  const std::string agent_seed = std::to_string(agent_slam_config(SlamConfig{}, "robot1").seed);
  const Trajectory reference = r.run("run_agent_seed", {"--seed", agent_seed});
  const Trajectory replayed = r.replayed(rate);
  ASSERT_EQ(reference.size(), r.scans());
  ASSERT_EQ(replayed.size(), r.scans()) << "a pose per scan";
  for (std::size_t i = 0; i < reference.size(); ++i)
    ASSERT_NEAR(replayed[i].timestamp, reference[i].timestamp, 1e-6) << "pose " << i << ": stamps cross ROS time";
  const Difference got = difference(replayed, reference);
  std::cout << fmt::format("{} ({} scans, replay at {}×):\n  agent fed by replay vs `run --seed {}` (the agent's "
                           "seed): {}\n",
                           log.filename().string(), r.scans(), rate, agent_seed, describe(got));
  double noise_ate = 0.0, noise_steps = 0.0;
  for (const char* seed : {"1", "2"}) {  // 1: `run`'s default
    const Difference noise = difference(r.run(std::string("run_seed_") + seed, {"--seed", seed}), reference);
    std::cout << fmt::format("  `run --seed {}` vs `run --seed {}` (matching noise): {}\n", seed, agent_seed,
                             describe(noise));
    noise_ate = std::max(noise_ate, noise.ate.rmse);
    noise_steps = std::max(noise_steps, noise.steps.trans_mean);
  }
  EXPECT_EQ(got.ate.matched, r.scans());
  EXPECT_LE(got.ate.rmse, noise_ate) << describe(got);
  EXPECT_LE(got.steps.trans_mean, noise_steps) << describe(got);
}

TEST(ReplayVsRunMultiProcess, SimulatedLogGivesTheRunsTrajectory) {
  Rig rig;
  SimulatedRun sim = simulate_demo(DemoConfig{});
  sim.log.scans.resize(400);  // 40 s of a 10 Hz lidar: a few rooms
  const fs::path log = rig.dir() / "sim.log";
  write_carmen(log, sim.log.scans, "simulated (DemoConfig defaults), first 400 scans");
  expect_replayed_like_run(rig, log, 4.0);
}

TEST(ReplayVsRunMultiProcessRealData, MitCsailGivesTheRunsTrajectory) {
  const fs::path log = fs::path(DSSWARM_SHARED_DATA) / "carmen/mit-csail.log.gz";
  if (!fs::exists(log)) GTEST_SKIP() << "real data not found at " << log.string();
  Rig rig;
  expect_replayed_like_run(rig, log, 20.0);  // 424 s of log in about 21 s
}

}  // namespace
}  // namespace dsswarm::mp
