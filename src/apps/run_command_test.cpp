// `dsswarm run` options for benchmarks and profiling: --max-scans, --no-images.
#include "apps/run_command.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/cli_test_util.hpp"
#include "common/test_files.hpp"
#include "config/config_json.hpp"
#include "io/logs/carmen_writer.hpp"
#include "io/trajectory/tum.hpp"
#include "sim/scenario.hpp"
#include "swarm/swarm_config.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

fs::path simulated_log(const fs::path& dir, std::size_t scans) {
  SimulatedRun sim = simulate_demo(DemoConfig{});
  sim.log.scans.resize(scans);
  const fs::path log = dir / "sim.log";
  write_carmen(log, sim.log.scans);
  return log;
}

nlohmann::json read_stats(const fs::path& dir) {
  std::ifstream in(dir / "stats.json");
  return nlohmann::json::parse(in);
}

TEST(RunCommand, MaxScansStopsEarlyAndNoImagesWritesTrajectoryAndStatsOnly) {
  const fs::path dir = test::fresh_dir("run_command_max_scans");
  const fs::path log = simulated_log(dir, 60);
  const fs::path out = dir / "out";
  test::run_cli(add_run_command, {"run", log.string(), "--out", out.string(), "--max-scans", "25", "--no-images"});
  EXPECT_EQ(read_tum(out / "trajectory.tum").size(), 25u);
  EXPECT_EQ(read_stats(out)["scans_read"].get<std::size_t>(), 25u);
  for (const char* f : {"map.png", "map.pgm", "map.yaml"}) EXPECT_FALSE(fs::exists(out / f)) << f;

  // More than the log holds: the whole log; images by default.
  const fs::path all = dir / "all";
  test::run_cli(add_run_command, {"run", log.string(), "--out", all.string(), "--max-scans", "1000"});
  EXPECT_EQ(read_tum(all / "trajectory.tum").size(), 60u);
  for (const char* f : {"map.png", "map.pgm", "map.yaml"}) EXPECT_TRUE(fs::exists(all / f)) << f;
}

TEST(RunCommand, MaxScansMustBePositive) {
  const fs::path dir = test::fresh_dir("run_command_max_scans_zero");
  const fs::path log = simulated_log(dir, 5);
  for (const char* bad : {"0", "-3", "x"})
    EXPECT_THROW(test::run_cli(add_run_command, {"run", log.string(), "--out", (dir / "o").string(), "--max-scans", bad}),
                 CLI::ParseError)
        << bad;
}

// `config` prints run's defaults; `config --swarm` the swarm commands', and a
// file made from it gives a swarm exactly its defaults back.
TEST(ConfigCommand, SwarmFlagPrintsTheSwarmCommandsDefaults) {
  const auto run = nlohmann::json::parse(test::run_cli(add_config_command, {"config"}));
  const auto swarm = nlohmann::json::parse(test::run_cli(add_config_command, {"config", "--swarm"}));
  EXPECT_TRUE(run["loop_closure"]["enabled"].get<bool>());
  EXPECT_TRUE(swarm["loop_closure"]["enabled"].get<bool>());
  EXPECT_LT(swarm["loop_closure"]["round_nodes"].get<int>(), run["loop_closure"]["round_nodes"].get<int>());
  SwarmConfig parsed;
  parsed.slam = SlamConfig{};  // start from run's, as a file given to `swarm` overrides everything it names
  parse_config(swarm.dump(), "printed.json", parsed);
  EXPECT_EQ(to_json(parsed), to_json(SwarmConfig{}));
}

}  // namespace
}  // namespace dsswarm
