// Tests of `dsswarm eval ...` as wired by add_eval_command (src/apps/eval_command.cpp).
#include "apps/eval_command.hpp"

#include <gtest/gtest.h>

#include "apps/cli_test_util.hpp"

#include "common/test_files.hpp"
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "io/trajectory/tum.hpp"

namespace dsswarm {
namespace {

using test::fresh_dir;

namespace fs = std::filesystem;

std::string run_cli(const std::vector<std::string>& args) { return test::run_cli(add_eval_command, args); }

std::string last_line(const std::string& text) {
  std::string trimmed = text;
  while (!trimmed.empty() && trimmed.back() == '\n') trimmed.pop_back();
  const auto pos = trimmed.rfind('\n');
  return pos == std::string::npos ? trimmed : trimmed.substr(pos + 1);
}

struct Files {
  fs::path estimate, truth, relations;
};

// Truth walks straight; the estimate drifts 1 cm sideways per step.
Files write_inputs(const std::string& name) {
  const fs::path dir = fresh_dir(name);
  Trajectory truth, estimate;
  std::ofstream rel(dir / "run.relations");
  for (int i = 0; i < 10; ++i) {
    truth.push_back({10.0 + i, Pose2(0.5 * i, 0.0, 0.0)});
    estimate.push_back({10.0 + i, Pose2(0.5 * i, 0.01 * i, 0.0)});
    if (i > 0) rel << (9.0 + i) << ' ' << (10.0 + i) << " 0.5 0 0 0 0 0\n";
  }
  rel << "50 51 0.5 0 0 0 0 0\n";  // no poses there: missing
  rel.close();
  write_tum(dir / "estimate.tum", estimate);
  write_tum(dir / "truth.tum", truth);
  return {dir / "estimate.tum", dir / "truth.tum", dir / "run.relations"};
}

TEST(EvalCommand, RelationsPrintsSummaryThenJsonLastLine) {
  const Files f = write_inputs("cli_relations");
  const std::string out = run_cli({"eval", "relations", f.estimate.string(), f.relations.string()});
  EXPECT_NE(out.find("translational error"), std::string::npos) << out;
  const auto j = nlohmann::json::parse(last_line(out));
  EXPECT_EQ(j.size(), 6u);
  EXPECT_EQ(j.at("used").get<int>(), 9);
  EXPECT_EQ(j.at("missing").get<int>(), 1);
  EXPECT_NEAR(j.at("trans_mean").get<double>(), 0.01, 1e-6);  // each step drifts 1 cm sideways
  EXPECT_NEAR(j.at("rot_mean_deg").get<double>(), 0.0, 1e-6);
}

TEST(EvalCommand, AtePrintsSummaryThenJsonLastLine) {
  const Files f = write_inputs("cli_ate");
  const std::string out = run_cli({"eval", "ate", f.estimate.string(), f.truth.string(), "--max-dt", "0.001"});
  EXPECT_NE(out.find("rmse"), std::string::npos) << out;
  const auto j = nlohmann::json::parse(last_line(out));
  EXPECT_EQ(j.size(), 5u);
  EXPECT_EQ(j.at("matched").get<int>(), 10);
  EXPECT_GT(j.at("ate_rmse").get<double>(), 0.0);  // a rotation cannot fully absorb a linear drift...
  EXPECT_LT(j.at("ate_rmse").get<double>(), 0.01);  // ...but nearly
}

TEST(EvalCommand, InputProblemsPropagateAsInputError) {
  const Files f = write_inputs("cli_errors");
  EXPECT_THROW(run_cli({"eval", "relations", (f.estimate.parent_path() / "nope.tum").string(), f.relations.string()}),
               InputError);
  std::ofstream(f.relations, std::ios::app) << "1 2 3\n";
  try {
    run_cli({"eval", "relations", f.estimate.string(), f.relations.string()});
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("run.relations:11"), std::string::npos) << e.what();
  }
}

// `eval swarm`: two agents on a straight line; b's frame is a's shifted by
// (10, 0) and the joint trajectory places b 5 cm off.
fs::path write_swarm_run(const std::string& name) {
  const fs::path dir = fresh_dir(name);
  Trajectory a, b, b_joint;
  for (int i = 0; i <= 4; ++i) a.push_back({100.0 + i, Pose2(i, 0, 0)});
  for (int i = 8; i >= 3; --i) {
    b.push_back({100.0 + i, Pose2(i - 10.0, 0, 0)});
    b_joint.push_back({100.0 + i, Pose2(i + 0.05, 0, 0)});
  }
  for (const auto& [agent, trajectory] : {std::pair{"a", a}, std::pair{"b", b}}) {
    fs::create_directories(dir / "agents" / agent);
    write_tum(dir / "agents" / agent / "trajectory.tum", trajectory);
  }
  fs::create_directories(dir / "joint");
  write_tum(dir / "joint" / "a.tum", a);
  write_tum(dir / "joint" / "b.tum", b_joint);
  // At log times 101 / 107 a is at 1 and b at −3 in its frame; the transform says +10.03: 6.03 for a true 6.
  test::write_text(dir / "encounters.json", R"({"encounters": [{"time": 1, "agents": ["a", "b"],
    "log_times": [101, 107], "poses": [[1, 0, 0], [-3, 0, 0]], "transform": [10.03, 0, 0], "accepted": true,
    "reason": "", "match_ms": 20, "merge_ms": 5, "bytes": 4096}]})");
  std::ofstream rel(dir / "run.relations");
  for (int i = 0; i < 8; ++i) rel << (100 + i) << ' ' << (101 + i) << " 1 0 0 0 0 0\n";
  rel << "101 107 6 0 0 0 0 0\n";  // a only → b only
  rel << "100 108 8 0 0 0 0 0\n";  // a only → b only
  return dir;
}

TEST(EvalCommand, SwarmPrintsTables) {
  const fs::path dir = write_swarm_run("cli_swarm");
  const std::string out = run_cli({"eval", "swarm", dir.string(), (dir / "run.relations").string()});
  EXPECT_NE(out.find("per agent"), std::string::npos) << out;
  EXPECT_NE(out.find("cross-agent"), std::string::npos) << out;
  EXPECT_NE(out.find("0.0500 ± 0.0000"), std::string::npos) << out;  // both cross relations 5 cm off
  EXPECT_NE(out.find("0.0300"), std::string::npos) << out;            // the encounter
}

TEST(EvalCommand, SwarmJson) {
  const fs::path dir = write_swarm_run("cli_swarm_json");
  const std::string out = run_cli({"eval", "swarm", dir.string(), (dir / "run.relations").string(), "--json"});
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j.at("agents").size(), 2u);
  EXPECT_EQ(j.at("agents")[0].at("relations_covered").get<int>(), 4);  // 100-101 .. 103-104
  EXPECT_EQ(j.at("agents")[1].at("relations_covered").get<int>(), 5);  // 103-104 .. 107-108
  EXPECT_EQ(j.at("cross").at("relations").get<int>(), 2);
  EXPECT_NEAR(j.at("cross").at("metrics").at("trans_mean").get<double>(), 0.05, 1e-9);
  EXPECT_NEAR(j.at("encounters")[0].at("trans_error").get<double>(), 0.03, 1e-9);
  EXPECT_EQ(j.at("encounters")[0].at("truth"), "relation");
  EXPECT_THROW(run_cli({"eval", "swarm", (dir / "nope").string(), (dir / "run.relations").string()}), InputError);
}

}  // namespace
}  // namespace dsswarm
