// Tests of `dsswarm filter ...` as wired by add_filter_command (src/apps/filter_command.cpp).
#include "apps/filter_command.hpp"

#include <gtest/gtest.h>

#include "apps/cli_test_util.hpp"

#include "common/test_files.hpp"
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "io/logs/carmen_writer.hpp"
#include "io/logs/log_reader.hpp"

namespace dsswarm {
namespace {

using test::fresh_dir;

namespace fs = std::filesystem;

std::string run_cli(const std::vector<std::string>& args) { return test::run_cli(add_filter_command, args); }

std::string last_line(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const auto pos = text.rfind('\n');
  return pos == std::string::npos ? text : text.substr(pos + 1);
}

// A robot standing for 40 scans (the same two walls, a little noise on one beam).
fs::path write_standing_log(const fs::path& dir) {
  std::vector<LaserScan> scans;
  for (int i = 0; i < 40; ++i) {
    LaserScan s;
    s.timestamp = 100.0 + 0.1 * i;
    s.angle_min = -1.5;
    s.angle_increment = 0.05;
    s.range_max = 30.0;
    for (int b = 0; b < 61; ++b) s.ranges.push_back(b < 30 ? 2.0f + 0.05f * float(b) : 6.0f - 0.03f * float(b - 30));
    s.ranges[static_cast<std::size_t>(i % 61)] += 0.01f;
    s.odometry = Pose2(1.0, 2.0, 0.5);
    scans.push_back(s);
  }
  const fs::path log = dir / "standing.log";
  write_carmen(log, scans);
  return log;
}

TEST(FilterCommand, WritesKeptScansDecisionsAndJsonSummary) {
  const fs::path dir = fresh_dir("filter_cli");
  const fs::path log = write_standing_log(dir);
  const std::string out = run_cli({"filter", log.string(), "--out", (dir / "kept.log").string(), "--decisions",
                                   (dir / "decisions.csv").string()});
  const auto summary = nlohmann::json::parse(last_line(out));
  EXPECT_EQ(summary.at("scans_read"), 40);
  // Window 10 (standing), then 5 dropped + 1 kept by the cap, five times.
  EXPECT_EQ(summary.at("scans_dropped"), 25);
  EXPECT_EQ(summary.at("scans_kept"), 15);
  EXPECT_NEAR(summary.at("drop_ratio").get<double>(), 25.0 / 40.0, 1e-12);
  EXPECT_GE(summary.at("filter_seconds").get<double>(), 0.0);

  const SensorLog kept = read_log(dir / "kept.log");
  ASSERT_EQ(kept.scans.size(), 15u);
  EXPECT_DOUBLE_EQ(kept.scans[0].timestamp, 100.0);
  EXPECT_DOUBLE_EQ(kept.scans[10].timestamp, 100.0 + 0.1 * 15);  // the first scan the cap kept

  std::ifstream csv(dir / "decisions.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "index,timestamp,kept,min_correlation,product,window,reason");
  int rows = 0, kept_rows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> fields;
    std::stringstream split(line);
    for (std::string f; std::getline(split, f, ',');) fields.push_back(f);
    ASSERT_EQ(fields.size(), 7u) << line;
    EXPECT_EQ(fields[0], std::to_string(rows));
    kept_rows += fields[2] == "1" ? 1 : 0;
    // A dropped scan was similar; a kept one names its valve.
    if (fields[2] == "0") {
      EXPECT_EQ(fields[6], "similar") << line;
    } else {
      EXPECT_NE(fields[6], "similar") << line;
    }
    ++rows;
  }
  EXPECT_EQ(kept_rows, 15);
  EXPECT_EQ(rows, 40);
}

TEST(FilterCommand, PlotIsAPngOfTheDecisionsOverTime) {
  const fs::path dir = fresh_dir("filter_cli_plot");
  const fs::path log = write_standing_log(dir);
  run_cli({"filter", log.string(), "--out", (dir / "kept.log").string(), "--plot", (dir / "plot.png").string()});
  std::ifstream png(dir / "plot.png", std::ios::binary);
  std::string head(24, '\0');
  ASSERT_TRUE(png.read(head.data(), 24));
  EXPECT_EQ(head.substr(1, 3), "PNG");
  // IHDR: width and height, big-endian, at bytes 16 and 20.
  auto be32 = [&](int at) {
    return (static_cast<unsigned char>(head[at]) << 24) | (static_cast<unsigned char>(head[at + 1]) << 16) |
           (static_cast<unsigned char>(head[at + 2]) << 8) | static_cast<unsigned char>(head[at + 3]);
  };
  EXPECT_EQ(be32(16), 1600);
  EXPECT_EQ(be32(20), 590);
}

TEST(FilterCommand, OptionsReachTheFilter) {
  const fs::path dir = fresh_dir("filter_cli_options");
  const fs::path log = write_standing_log(dir);
  const std::string out = run_cli({"filter", log.string(), "--out", (dir / "kept.log").string(), "--max-drops", "0",
                                   "--columns", "20", "--statistic", "mean", "--binning", "sector", "--pair", "0.95"});
  EXPECT_EQ(nlohmann::json::parse(last_line(out)).at("scans_dropped"), 0);
  const std::string fixed = run_cli({"filter", log.string(), "--out", (dir / "kept2.log").string(), "--no-odometry"});
  // Fixed window 5 without odometry: 5 kept, then 5 times 5 dropped + 1 kept, then 5 dropped.
  const auto summary = nlohmann::json::parse(last_line(fixed));
  EXPECT_EQ(summary.at("scans_kept"), 5 + 5);
}

// `--config FILE` as for the other commands: the file's filter section, then the flags given.
TEST(FilterCommand, ConfigFileSectionFilterThenFlags) {
  const fs::path dir = fresh_dir("filter_cli_config");
  const fs::path log = write_standing_log(dir);
  const fs::path config =
      test::write_text(dir / "c.json", R"({"filter": {"max_consecutive_drops": 0, "min_window": 2}})");
  const auto dropped = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"filter", log.string(), "--out", (dir / "kept.log").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return nlohmann::json::parse(last_line(run_cli(args))).at("scans_dropped").get<int>();
  };
  EXPECT_EQ(dropped({}), 25);
  EXPECT_EQ(dropped({"--config", config.string()}), 0);                      // the file's 0 drops in a row
  EXPECT_EQ(dropped({"--config", config.string(), "--max-drops", "5"}), 25);  // a flag beats the file
  const fs::path typo = test::write_text(dir / "typo.json", R"({"filter": {"max_drops": 0}})");
  try {
    run_cli({"filter", log.string(), "--out", (dir / "kept.log").string(), "--config", typo.string()});
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("max_drops"), std::string::npos) << e.what();
  }
}

TEST(FilterCommand, BadValuesAreConfigErrorsNamingTheField) {
  const fs::path dir = fresh_dir("filter_cli_bad");
  const fs::path log = write_standing_log(dir);
  const std::string out = (dir / "kept.log").string();
  try {
    run_cli({"filter", log.string(), "--out", out, "--pair", "0.5"});
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("pair_threshold"), std::string::npos) << e.what();
  }
  try {
    run_cli({"filter", log.string(), "--out", out, "--common", "1.5"});
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("common_threshold"), std::string::npos) << e.what();
  }
  EXPECT_THROW(run_cli({"filter", log.string(), "--out", out, "--columns", "1"}), ConfigError);
  EXPECT_THROW(run_cli({"filter", log.string(), "--out", out, "--statistic", "mode"}), CLI::ValidationError);
  EXPECT_THROW(run_cli({"filter", (dir / "missing.log").string(), "--out", out}), InputError);  // input: exit 1
  EXPECT_FALSE(fs::exists(out));
}

TEST(FilterCommand, CorruptLogIsAnInputError) {
  const fs::path dir = fresh_dir("filter_cli_corrupt");
  std::ofstream(dir / "bad.log") << "FLASER 3 1.0 2.0\n";
  EXPECT_THROW(run_cli({"filter", (dir / "bad.log").string(), "--out", (dir / "kept.log").string()}), InputError);
  EXPECT_FALSE(fs::exists(dir / "kept.log"));
}

}  // namespace
}  // namespace dsswarm
