#include "config/config_json.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

TEST(SlamConfigJson, RoundTripsEveryField) {
  SlamConfig c;
  c.map.resolution = 0.1;
  c.matcher.evaluations = 99;
  c.use_odometry = false;
  c.seed = 12345;
  c.points.forward_gain = 2.5;
  SlamConfig d;
  apply_json(to_json(c), d);
  EXPECT_EQ(to_json(d), to_json(c));
  EXPECT_EQ(d.matcher.evaluations, 99);
  EXPECT_FALSE(d.use_odometry);
  // Floats as written by a person: 0.4, not 0.4000000059604645.
  EXPECT_EQ(to_json(c).at("evidence").at("hit_occupied").dump(), "0.4");
}

TEST(ConfigJson, SwarmSectionsRoundTripAndSingleRobotsIgnoreThem) {
  SwarmConfig c;
  c.slam.matcher.evaluations = 77;
  c.encounter.agree_xy = 0.03;
  c.encounter.locate.surroundings_radius = 12.0;
  c.confirm_theta = 0.01;
  c.confirm = false;
  c.encounter.reject_bent_maps = true;
  const nlohmann::json j = to_json(c);
  EXPECT_EQ(j.at("encounter").at("agree_xy"), 0.03);
  EXPECT_EQ(j.at("swarm").at("confirm"), false);
  SwarmConfig d;
  apply_json(j, d);
  EXPECT_EQ(to_json(d), j);
  EXPECT_DOUBLE_EQ(d.encounter.locate.surroundings_radius, 12.0);
  EXPECT_FALSE(d.confirm);
  EXPECT_TRUE(d.encounter.reject_bent_maps);
  // A single robot reads the same file: its sections apply, the swarm's are
  // checked (a typo there is still an error) and otherwise ignored.
  SlamConfig single;
  apply_json(j, single);
  EXPECT_EQ(single.matcher.evaluations, 77);
  EXPECT_FALSE(to_json(single).contains("encounter"));
  EXPECT_THROW(apply_json(nlohmann::json::parse(R"({"swarm": {"confirmxy": 1}})"), single), ConfigError);
}

TEST(SlamConfigJson, UnknownKeyIsNamed) {
  SlamConfig c;
  try {
    apply_json(nlohmann::json::parse(R"({"matcher": {"evaluatons": 10}})"), c, "my.json");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("matcher.evaluatons"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("my.json"), std::string::npos);
  }
}

TEST(ConfigJson, EnumerationsByName) {
  SlamConfig c;
  apply_json(nlohmann::json::parse(R"({"filter": {"statistic": "mean", "binning": "distance"}})"), c);
  EXPECT_EQ(c.filter.statistic, HistogramStatistic::mean);
  EXPECT_EQ(c.filter.binning, HistogramBinning::distance);
  EXPECT_EQ(to_json(c).at("filter").at("statistic"), "mean");
  try {
    apply_json(nlohmann::json::parse(R"({"filter": {"statistic": "mode"}})"), c, "my.json");
    FAIL();
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("filter.statistic"), std::string::npos) << m;
    EXPECT_NE(m.find("median, mean"), std::string::npos) << m;
  }
  EXPECT_THROW(apply_json(nlohmann::json::parse(R"({"filter": {"binning": 3}})"), c), ConfigError);
}

TEST(SlamConfigJson, WrongTypeIsNamed) {
  SlamConfig c;
  try {
    apply_json(nlohmann::json::parse(R"({"map": {"resolution": "fine"}})"), c);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("map.resolution"), std::string::npos);
  }
}

TEST(SlamConfigJson, FileWithOutOfRangeValueFailsValidation) {
  const std::filesystem::path p = std::filesystem::path(DSSWARM_TEST_TMP) / "bad_config.json";
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << R"({"map": {"levels": 0}})";
  SlamConfig c;
  EXPECT_THROW(load_slam_config(p, c), ConfigError);
  std::ofstream(p) << "{ not json";
  EXPECT_THROW(load_slam_config(p, c), ConfigError);
  std::ofstream(p) << R"({"encounter": {"agree_xy": -1}})";
  SwarmConfig swarm;
  try {
    load_config(p, swarm);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("agree_xy"), std::string::npos) << e.what();
  }
}

TEST(SwarmConfigJson, ParsesTextInMemoryAsItLoadsFiles) {
  SwarmConfig c;
  parse_config(R"({"map": {"levels": 2}, "swarm": {"confirm": false}})", "inline.json", c);
  EXPECT_EQ(c.slam.map.levels, 2);
  EXPECT_FALSE(c.confirm);
  for (const char* bad : {"{ not json", R"({"map": {"levels": 0}})", R"({"mapp": {}})"}) {
    try {
      parse_config(bad, "inline.json", c);
      ADD_FAILURE() << "expected ConfigError for " << bad;
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("inline.json: ", 0), 0u) << e.what();
    }
  }
}

// One robot and the swarm both map with loop closure by default, the swarm
// with shorter rounds (swarm_config.hpp). A file turns it off, and on again
// keeps the swarm's rounds unless it sets them too.
TEST(SwarmConfigJson, LoopClosureIsOnForOneRobotAndTheSwarmAndAFileTurnsItOff) {
  EXPECT_TRUE(SlamConfig{}.loop_closure.enabled);
  SwarmConfig c;
  EXPECT_TRUE(c.slam.loop_closure.enabled);
  EXPECT_LT(c.slam.loop_closure.round_nodes, SlamConfig{}.loop_closure.round_nodes);
  parse_config(R"({"loop_closure": {"enabled": false}})", "inline.json", c);
  EXPECT_FALSE(c.slam.loop_closure.enabled);
  parse_config(R"({"loop_closure": {"enabled": true}})", "inline.json", c);
  EXPECT_TRUE(c.slam.loop_closure.enabled);
  EXPECT_LT(c.slam.loop_closure.round_nodes, SlamConfig{}.loop_closure.round_nodes);
  parse_config(R"({"loop_closure": {"round_nodes": 30}})", "inline.json", c);
  EXPECT_EQ(c.slam.loop_closure.round_nodes, 30);
}

// Found by fuzzing (fuzz/config.cpp): nlohmann's parser reports a number too
// large for a double as out_of_range, not parse_error, which escaped as a
// plain std::exception.
TEST(SwarmConfigJson, NumberTooLargeForADoubleIsAConfigError) {
  SwarmConfig c;
  try {
    parse_config(R"({"swarm": {"confirm_xy": 1e400}})", "huge.json", c);
    ADD_FAILURE() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("huge.json: not valid JSON"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1e400"), std::string::npos) << e.what();
  }
  const std::filesystem::path p = std::filesystem::path(DSSWARM_TEST_TMP) / "huge.json";
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << R"({"map": {"resolution": -1e400}})";
  EXPECT_THROW(load_config(p, c), ConfigError);
}

// Found by fuzzing (fuzz/config.cpp): 9.1e92 for an int field was converted
// with undefined behaviour; 2.5, 4294967298 and true were silently read as 2, 2, 1.
TEST(SwarmConfigJson, WholeNumberFieldsTakeOnlyWholeNumbersInRange) {
  SwarmConfig c;
  parse_config(R"({"map": {"levels": 2.0}, "slam": {"seed": 18446744073709551615}})", "ok.json", c);
  EXPECT_EQ(c.slam.map.levels, 2);
  EXPECT_EQ(c.slam.seed, 18446744073709551615ULL);
  for (const char* value : {"9.1e92", "2.5", "4294967298", "-2147483649", "true", "\"2\""}) {
    const std::string text = std::string(R"({"map": {"levels": )") + value + "}}";
    try {
      parse_config(text, "bad.json", c);
      ADD_FAILURE() << "expected ConfigError for " << value;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.json: 'map.levels' must be a whole number"), std::string::npos)
          << e.what();
    }
  }
  try {
    parse_config(R"({"slam": {"seed": -1}})", "bad.json", c);
    ADD_FAILURE() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'slam.seed' must be a whole number from 0 to 18446744073709551615"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace dsswarm
