#include "apps/swarm_scenario.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>

#include <filesystem>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/test_files.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

// Twelve scans one second apart from t = 100, except the fifth, whose
// timestamp runs backwards (102.5 after 103) as intel's do. Odometry x = file index.
const std::vector<double> kStamps = {100, 101, 102, 103, 102.5, 104, 105, 106, 107, 108, 109, 110};

std::string synthetic_log() {
  std::string text = "# synthetic CARMEN log\n";
  for (std::size_t i = 0; i < kStamps.size(); ++i) {
    text += "FLASER 3 1 2 3 " + std::to_string(i) + " 0 0 " + std::to_string(i) + " 0 0 " +
            std::to_string(kStamps[i]) + " host 0\n";
  }
  return text;
}

// A scratch folder holding log.txt, and scenario.yaml with `body`.
fs::path scenario_with(const std::string& test, const std::string& body) {
  const fs::path dir = test::fresh_dir("swarm_scenario/" + test);
  test::write_text(dir / "log.txt", synthetic_log());
  return test::write_text(dir / "scenario.yaml", body);
}

std::vector<double> stamps_of(const AgentStream& s) {
  std::vector<double> out;
  for (const LaserScan& scan : s.scans) out.push_back(scan.timestamp);
  return out;
}

bool mentions(const std::vector<std::string>& lines, const std::string& what) {
  for (const auto& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

const char* kTwoRobots = R"(
agents:
  - name: robot1
    log: log.txt
    from: 2
    to: 5
  - name: robot2
    log: log.txt
    from_fraction: 0.5
    to_fraction: 1.0
    direction: backward
    start: 0.5
)";

TEST(SwarmScenario, ForwardSegmentPlaysItsScansInFileOrderOnAHeldClock) {
  const SwarmScenario s = load_swarm_scenario(scenario_with("forward", kTwoRobots));
  EXPECT_EQ(s.name, "scenario");  // the file's stem
  ASSERT_EQ(s.streams.size(), 2u);
  const AgentStream& r1 = s.streams[0];
  EXPECT_EQ(r1.name, "robot1");
  // [102, 105] by the running maximum: the glitch at 102.5 stays in its place.
  EXPECT_EQ(stamps_of(r1), (std::vector<double>{102, 103, 102.5, 104, 105}));
  EXPECT_EQ(r1.clock, (std::vector<double>{0, 1, 1, 2, 3}));  // held, never backwards
  ASSERT_TRUE(r1.scans[2].odometry);
  EXPECT_DOUBLE_EQ(r1.scans[2].odometry->x, 4.0);  // file index 4
  EXPECT_TRUE(mentions(s.warnings, "agent robot1: 1 of 5 scans"));
}

TEST(SwarmScenario, BackwardSegmentPlaysLastToFirstFromItsStart) {
  const SwarmScenario s = load_swarm_scenario(scenario_with("backward", kTwoRobots));
  const AgentStream& r2 = s.streams.at(1);
  EXPECT_EQ(stamps_of(r2), (std::vector<double>{110, 109, 108, 107, 106, 105}));  // from 105 (50%) to 110
  EXPECT_EQ(r2.clock, (std::vector<double>{0.5, 1.5, 2.5, 3.5, 4.5, 5.5}));
  EXPECT_DOUBLE_EQ(r2.scans.front().odometry->x, 11.0);
  EXPECT_FALSE(mentions(s.warnings, "agent robot2"));
}

TEST(SwarmScenario, DefaultsPlayTheWholeLogForwardFromZero) {
  const SwarmScenario s = load_swarm_scenario(scenario_with("defaults", "name: whole\nagents:\n  - name: a\n    log: log.txt\n"));
  EXPECT_EQ(s.name, "whole");
  EXPECT_EQ(stamps_of(s.streams.at(0)), kStamps);
  EXPECT_EQ(s.streams[0].clock.front(), 0.0);
  EXPECT_EQ(s.streams[0].clock.back(), 10.0);
  EXPECT_TRUE(s.events.empty());
  EXPECT_FALSE(s.config);
  EXPECT_EQ(s.relations, "");
}

std::vector<std::string> s_warnings_of(const fs::path& yaml) { return load_swarm_scenario(yaml).warnings; }

TEST(SwarmScenario, ALogSharedByTwoAgentsIsReadOnce) {
  // The reader warns about the backwards timestamp; read twice, the warning would be there twice.
  const fs::path yaml = scenario_with("read_once", kTwoRobots);
  int reader_warnings = 0;
  for (const auto& w : s_warnings_of(yaml)) reader_warnings += w.find("scan timestamps run backwards") != std::string::npos;
  EXPECT_EQ(reader_warnings, 1) << ::testing::PrintToString(s_warnings_of(yaml));
}

TEST(SwarmScenario, PathsAreResolvedAgainstTheScenarioFolder) {
  const fs::path yaml = scenario_with("paths", std::string("config: sub/slam.json\nrelations: log.relations\n") + kTwoRobots);
  fs::create_directories(yaml.parent_path() / "sub");
  test::write_text(yaml.parent_path() / "sub" / "slam.json", "{}");
  test::write_text(yaml.parent_path() / "log.relations", "100 101 1 0 0 0 0 0\n");
  const SwarmScenario s = load_swarm_scenario(yaml);
  ASSERT_TRUE(s.config);
  EXPECT_TRUE(fs::equivalent(*s.config, yaml.parent_path() / "sub" / "slam.json"));
  EXPECT_TRUE(fs::equivalent(s.relations, yaml.parent_path() / "log.relations"));
}

TEST(SwarmScenario, EncountersByTimeAndByLogTimes) {
  const SwarmScenario s = load_swarm_scenario(scenario_with("encounters", std::string(kTwoRobots) + R"(
encounters:
  - agents: [robot2, robot1]
    time: 2.25
  - agents: [robot1, robot2]
    log_times: [104.0004, 108]
  - agents: [robot2, robot1]
    log_times: [106, 103]
)"));
  ASSERT_EQ(s.events.size(), 3u);
  EXPECT_EQ(s.events[0].a, 1u);
  EXPECT_EQ(s.events[0].b, 0u);
  EXPECT_DOUBLE_EQ(s.events[0].time, 2.25);
  // robot1 plays log time 104 at session time 2; robot2 is then at 108 (0.5 + 2 − 0.5 s): no warning.
  EXPECT_EQ(s.events[1].a, 0u);
  EXPECT_DOUBLE_EQ(s.events[1].time, 2.0);
  EXPECT_FALSE(mentions(s.warnings, "encounter 1"));
  // robot2 plays 106 at 4.5; robot1 is then at 105, not 103: a warning, not an error.
  EXPECT_DOUBLE_EQ(s.events[2].time, 4.5);
  EXPECT_TRUE(mentions(s.warnings, "encounter 2 at session time 4.500 s: agent robot1 is at log time 105.000"))
      << ::testing::PrintToString(s.warnings);
}

TEST(SwarmScenario, EncounterBeforeAnAgentStartsIsLoadedWithAWarning) {
  const SwarmScenario s = load_swarm_scenario(scenario_with("early", std::string(kTwoRobots) + R"(
encounters:
  - agents: [robot1, robot2]
    time: 0.25
)"));
  ASSERT_EQ(s.events.size(), 1u);
  EXPECT_TRUE(mentions(s.warnings, "agent robot2 starts only at 0.500 s")) << ::testing::PrintToString(s.warnings);
}

// Each bad scenario must be refused with a message naming the file, the
// agent or encounter where it applies, and the key.
struct BadCase {
  const char* label;
  std::string yaml;
  std::vector<std::string> expected;  // substrings of the message
};

std::string agents_with(const std::string& robot1_extra, const std::string& robot2_extra = "") {
  return "agents:\n  - name: robot1\n    log: log.txt\n" + robot1_extra + "  - name: robot2\n    log: log.txt\n" +
         robot2_extra;
}

TEST(SwarmScenario, BadScenariosNameTheFileTheAgentAndTheKey) {
  const std::string encounter = "encounters:\n  - agents: [robot1, robot2]\n";
  const std::vector<BadCase> cases = {
      {"no agents", "name: x\n", {"missing key 'agents'"}},
      {"empty agents", "agents: []\n", {"key 'agents'", "non-empty"}},
      {"unknown top key", "agent:\n  - name: a\n", {"line 1", "key 'agent'", "unknown key"}},
      {"unknown agent key", agents_with("    form: 3\n"), {"agents[0] (robot1)", "key 'form'", "unknown key"}},
      {"missing log", "agents:\n  - name: robot1\n", {"agents[0] (robot1)", "missing key 'log'"}},
      {"missing name", "agents:\n  - log: log.txt\n", {"agents[0]:", "missing key 'name'"}},
      {"bad name", "agents:\n  - name: a/b\n    log: log.txt\n", {"agents[0] (a/b)", "key 'name'"}},
      {"duplicate names", "agents:\n  - name: r\n    log: log.txt\n  - name: r\n    log: log.txt\n",
       {"agents[1] (r)", "key 'name'", "already the name of agents[0]"}},
      {"log not found", "agents:\n  - name: r\n    log: nope.log\n", {"agents[0] (r)", "key 'log'", "not found"}},
      {"unreadable log", "agents:\n  - name: r\n    log: scenario.yaml\n", {"agents[0] (r)", "key 'log'", "cannot read"}},
      {"bad direction", agents_with("", "    direction: sideways\n"), {"agents[1] (robot2)", "key 'direction'", "sideways"}},
      {"from after to", agents_with("    from: 5\n    to: 5\n"), {"agents[0] (robot1)", "key 'to'", "greater than from"}},
      {"from after to mixed", agents_with("    from: 6\n    to_fraction: 0.5\n"), {"key 'to_fraction'", "not after 'from'"}},
      {"fraction above 1", agents_with("    from_fraction: 1.5\n"), {"key 'from_fraction'", "outside [0, 1]"}},
      {"fraction below 0", agents_with("", "    to_fraction: -0.1\n"), {"agents[1] (robot2)", "key 'to_fraction'"}},
      {"both from and fraction", agents_with("    from: 1\n    from_fraction: 0.1\n"), {"key 'from_fraction'", "not both"}},
      {"empty segment", agents_with("    from: 50\n"), {"agents[0] (robot1)", "key 'from'", "no scans"}},
      {"negative from", agents_with("    from: -1\n"), {"key 'from'", "negative"}},
      {"negative start", agents_with("", "    start: -2\n"), {"agents[1] (robot2)", "key 'start'", "negative"}},
      {"text start", agents_with("", "    start: soon\n"), {"key 'start'", "not a number"}},
      {"negative time", agents_with("") + encounter + "    time: -1\n", {"encounters[0]", "key 'time'", "negative"}},
      {"no time", agents_with("") + encounter, {"encounters[0]", "missing key 'time'"}},
      {"time and log_times", agents_with("") + encounter + "    time: 1\n    log_times: [101, 102]\n",
       {"encounters[0]", "key 'log_times'", "not both"}},
      {"unknown encounter key", agents_with("") + encounter + "    tim: 1\n", {"encounters[0]", "key 'tim'"}},
      {"unknown agent", agents_with("") + "encounters:\n  - agents: [robot1, robot3]\n    time: 1\n",
       {"encounters[0]", "key 'agents'", "robot3"}},
      {"same agent twice", agents_with("") + "encounters:\n  - agents: [robot1, robot1]\n    time: 1\n",
       {"encounters[0]", "key 'agents'", "itself"}},
      {"one agent", agents_with("") + "encounters:\n  - agents: [robot1]\n    time: 1\n", {"key 'agents'", "two"}},
      {"log time outside a", agents_with("    to: 3\n") + encounter + "    log_times: [104, 104]\n",
       {"encounters[0]", "key 'log_times'", "outside the segment of agent robot1"}},
      {"log time outside b", agents_with("", "    direction: backward\n    from: 5\n") + encounter + "    log_times: [101, 104]\n",
       {"encounters[0]", "key 'log_times'", "outside the segment of agent robot2"}},
      {"missing relations", "relations: x.relations\n" + agents_with(""), {"key 'relations'", "not found"}},
      {"invalid yaml", "agents: [\n", {"invalid YAML"}},
  };
  for (const BadCase& c : cases) {
    const fs::path yaml = scenario_with("bad", c.yaml);
    try {
      load_swarm_scenario(yaml);
      ADD_FAILURE() << c.label << ": accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(yaml.string()), std::string::npos) << c.label << ": " << message;
      for (const std::string& part : c.expected)
        EXPECT_NE(message.find(part), std::string::npos) << c.label << ": expected '" << part << "' in: " << message;
    }
  }
}

TEST(SwarmScenario, MissingScenarioFileIsAnInputError) {
  const fs::path missing = test::fresh_dir("swarm_scenario/missing") / "none.yaml";
  EXPECT_THROW(load_swarm_scenario(missing), InputError);
}

// The real-data scenarios in scenarios/: they load without complaint, and at
// each encounter both robots have just played the scans its log_times name
// (the picking script aligned the start times to make that exact).
TEST(SwarmScenarioRealData, ShippedScenariosLoadWithEncountersWhereTheySay) {
  const fs::path scenarios = fs::path(DSSWARM_SOURCE_DIR) / "scenarios";
  const fs::path data(DSSWARM_SHARED_DATA);
  if (!fs::exists(data / "carmen" / "intel.log.gz")) GTEST_SKIP() << "real data not found at " << data;
  std::vector<fs::path> files;
  for (const auto& item : fs::directory_iterator(scenarios))
    if (item.path().extension() == ".yaml") files.push_back(item.path());
  std::sort(files.begin(), files.end());
  ASSERT_EQ(files.size(), 6u) << scenarios;
  for (const fs::path& file : files) {
    const SwarmScenario s = load_swarm_scenario(file);
    SCOPED_TRACE(file.string());
    EXPECT_EQ(s.name, file.stem().string());
    EXPECT_TRUE(fs::exists(s.relations));
    ASSERT_EQ(s.streams.size(), 2u);
    ASSERT_FALSE(s.events.empty());
    EXPECT_FALSE(mentions(s.warnings, "encounter")) << ::testing::PrintToString(s.warnings);
    const YAML::Node encounters = YAML::LoadFile(file.string())["encounters"];
    ASSERT_EQ(encounters.size(), s.events.size());
    for (std::size_t k = 0; k < s.events.size(); ++k) {
      const EncounterEvent& e = s.events[k];
      for (const std::size_t who : {e.a, e.b}) {
        // The last scan an agent has played when the event fires: clock <= time (SwarmSession).
        const AgentStream& stream = s.streams[who];
        const auto after = std::upper_bound(stream.clock.begin(), stream.clock.end(), e.time);
        ASSERT_NE(after, stream.clock.begin());
        const double played = stream.scans[static_cast<std::size_t>(after - stream.clock.begin()) - 1].timestamp;
        const double wanted = encounters[k]["log_times"][who == e.a ? 0 : 1].as<double>();
        EXPECT_NEAR(played, wanted, 1e-3) << "encounter " << k << ", agent " << stream.name;
      }
    }
  }
}

TEST(SwarmScenario, TextInMemoryReadsAsTheFileDoes) {
  const fs::path file = scenario_with("in_memory", kTwoRobots);
  const SwarmScenario from_file = load_swarm_scenario(file);
  // The text is parsed as if it were the file: same folder for the logs, same name.
  const SwarmScenario from_text = parse_swarm_scenario(kTwoRobots, file);
  EXPECT_EQ(from_text.name, "scenario");
  ASSERT_EQ(from_text.streams.size(), from_file.streams.size());
  for (std::size_t i = 0; i < from_text.streams.size(); ++i) {
    EXPECT_EQ(stamps_of(from_text.streams[i]), stamps_of(from_file.streams[i])) << i;
    EXPECT_EQ(from_text.streams[i].clock, from_file.streams[i].clock) << i;
  }
  EXPECT_EQ(from_text.warnings, from_file.warnings);
  const fs::path typed = file.parent_path() / "typed.yaml";
  try {
    parse_swarm_scenario("agents: [", typed);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(typed.string() + ": line 1:", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace dsswarm
