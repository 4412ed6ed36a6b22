#include "config/slam_config_json.hpp"

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
}

}  // namespace
}  // namespace dsswarm
