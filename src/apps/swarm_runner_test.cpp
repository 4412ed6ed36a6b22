// Swarm outputs in a reused folder, and the console's account of the encounter events.
#include "apps/swarm_runner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <limits>

#include "apps/stale_outputs.hpp"
#include "apps/swarm_picture.hpp"
#include "apps/swarm_report.hpp"
#include "common/test_files.hpp"
#include "sim/scenario.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

std::vector<AgentStream> streams(const std::vector<std::string>& names) {
  SimulatedRun sim = simulate_demo(DemoConfig{});
  sim.log.scans.resize(40);
  std::vector<AgentStream> out;
  for (const std::string& name : names) {
    AgentStream s{name, sim.log.scans, {}};
    for (const LaserScan& scan : s.scans) s.clock.push_back(scan.timestamp);
    out.push_back(std::move(s));
  }
  return out;
}

void write_session(const fs::path& dir, const std::vector<std::string>& names) {
  SwarmSession session(streams(names), {}, SwarmConfig{});
  session.run();
  SwarmOutputOptions options;
  options.wall_seconds = 1.0;
  write_swarm_outputs(dir, run_result(session), options);
}

std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  return files;
}

TEST(SwarmOutputs, ReusedFolderKeepsNoFilesOfAgentsThatAreGoneAndEveryOtherFile) {
  const fs::path dir = test::fresh_dir("swarm_outputs_reused");
  write_session(dir, {"a", "b"});
  // Everything dsswarm wrote per agent is known to the clean-up.
  const std::vector<fs::path> known = previous_swarm_outputs(dir);
  for (const fs::path& f : files_under(dir)) {
    const std::string rel = fs::relative(f, dir).string();
    if (rel.starts_with("agents/") || rel.starts_with("joint/")) {
      EXPECT_NE(std::find(known.begin(), known.end(), f), known.end()) << rel << " would be left behind";
    }
  }
  ASSERT_TRUE(fs::exists(dir / "agents" / "b" / "trajectory.tum"));
  test::write_text(dir / "agents" / "b" / "notes.txt", "mine");
  test::write_text(dir / "notes.txt", "mine");
  test::write_text(dir / "agents" / "c.txt", "mine");

  write_session(dir, {"a"});
  EXPECT_TRUE(fs::exists(dir / "agents" / "a" / "trajectory.tum"));
  for (const char* f : {"trajectory.tum", "map.yaml", "map.pgm", "merged_map.png"})
    EXPECT_FALSE(fs::exists(dir / "agents" / "b" / f)) << f;
  EXPECT_TRUE(fs::exists(dir / "agents" / "b" / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir / "agents" / "c.txt"));

  fs::remove(dir / "agents" / "b" / "notes.txt");
  write_session(dir, {"a"});  // b is not in stats.json any more: its empty folder stays
  write_session(dir, {"b"});
  write_session(dir, {"a"});
  EXPECT_FALSE(fs::exists(dir / "agents" / "b"));  // emptied by dsswarm, so removed
}

TEST(SwarmOutputs, StatsJsonThatNamesNoAgentsRemovesNothing) {
  const fs::path dir = test::fresh_dir("swarm_outputs_foreign");
  test::write_text(dir / "stats.json", R"({"agents": [{"name": "../../etc"}, {"name": 3}]})");
  EXPECT_TRUE(previous_swarm_outputs(dir).empty());
  test::write_text(dir / "stats.json", "not json");
  EXPECT_TRUE(previous_swarm_outputs(dir).empty());
}

// swarm.png: a legend naming each robot in its colour and a scale bar in a
// band under the map, and paths wider than a hairline.
TEST(SwarmPicture, LegendScaleBarAndPathsAPersonCanTellApart) {
  SwarmSession session(streams({"a", "b"}), {}, SwarmConfig{});
  session.run();
  const GridRaster raster = session.agent(0).slam().map().finest().to_raster();
  const std::vector<std::optional<Pose2>> frames = {Pose2(), Pose2(0.5, 0.5, 0.0)};
  SwarmRunResult run = run_result(session);
  run.agents[1].map_versions.clear();  // all of b's path in its colour (they never met)
  const Image picture = swarm_picture(run, raster, frames);
  const Image map = render_map(raster, fitting_scale(raster));
  ASSERT_GT(picture.height, map.height);
  auto count = [&](Rgb colour, int y0, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < picture.width; ++x) n += picture.at(x, y) == colour ? 1 : 0;
    return n;
  };
  for (int i = 0; i < 2; ++i)
    EXPECT_GT(count(agent_colour(i), map.height, picture.height), 0) << "legend of agent " << i;
  EXPECT_GT(count(Rgb{0, 0, 0}, map.height, picture.height), 100) << "scale bar and labels";
  Image hairline = map;
  std::vector<Eigen::Vector2d> path;
  for (const SlamStep& step : session.track(1).steps) path.push_back(Pose2(0.5, 0.5, 0.0) * step.pose.translation());
  draw_polyline(hairline, raster, path, agent_colour(1), 1);
  const auto thin = std::count(hairline.pixels.begin(), hairline.pixels.end(), agent_colour(1));
  EXPECT_GE(count(agent_colour(1), 0, map.height), 2 * thin) << "paths are hairlines";
}

// Another robot's path past the last map of it the first robot holds is pale:
// that ground is not in the map drawn.
TEST(SwarmPicture, AnotherRobotsPathPastTheMapHeldIsPale) {
  SwarmSession session(streams({"a", "b"}), {}, SwarmConfig{});
  session.run();
  const GridRaster raster = session.agent(0).slam().map().finest().to_raster();
  const std::vector<std::optional<Pose2>> frames = {Pose2(), Pose2(0.5, 0.5, 0.0)};
  const int map_height = render_map(raster, fitting_scale(raster)).height;
  auto count = [&](const Image& picture, Rgb colour) {
    int n = 0;
    for (int y = 0; y < map_height; ++y)
      for (int x = 0; x < picture.width; ++x) n += picture.at(x, y) == colour ? 1 : 0;
    return n;
  };
  const Rgb full = agent_colour(1), faded = pale(agent_colour(1));
  SwarmRunResult run = run_result(session);
  const std::vector<std::size_t>& versions = run.agents[1].map_versions;
  ASSERT_EQ(versions.size(), run.agents[1].trajectory.size());
  ASSERT_GT(versions.back(), versions.front());
  // Versions unknown: all in its colour, as before.
  SwarmRunResult unknown = run;
  unknown.agents[1].map_versions.clear();
  const Image all = swarm_picture(unknown, raster, frames);
  EXPECT_EQ(count(all, faded), 0);
  // They never met: a holds nothing of b, whose path is pale (its start marker is not).
  const Image none = swarm_picture(run, raster, frames);
  EXPECT_GT(count(none, faded), 20);
  EXPECT_LT(count(none, full) + 20, count(all, full));
  // a holds b's map as it stood halfway: its first half in its colour, the rest pale.
  MapLayer held;
  held.origin = "b";
  held.version = versions[versions.size() / 2];
  held.hops = 1;
  run.agents[0].knows.push_back(held);
  const Image some = swarm_picture(run, raster, frames);
  EXPECT_GT(count(some, full), count(none, full) + 20);
  EXPECT_LT(count(some, full) + 20, count(all, full));
  EXPECT_GT(count(some, faded), 20);
}

TEST(SwarmReport, SkippedEventsSayWhy) {
  EXPECT_EQ(describe_encounter_events("scripted encounters", 5, 2,
                                      {"robot2 had not started", "robot1 and robot2 merged less than 10 s before",
                                       "robot2 had not started"}),
            "5 scripted encounters: 2 run, 3 skipped (robot2 had not started: 2; robot1 and robot2 merged less "
            "than 10 s before: 1)");
  EXPECT_EQ(describe_encounter_events("proximity events", 5, 0, std::vector<std::string>(5, "merging is off")),
            "5 proximity events: 0 run, 5 skipped (merging is off)");
  EXPECT_EQ(describe_encounter_events("scripted encounters", 0, 0, {}), "0 scripted encounters");
  EXPECT_EQ(describe_encounter_events("scripted encounters", 1, 1, {}), "1 scripted encounters: 1 run");
}

}  // namespace
}  // namespace dsswarm
