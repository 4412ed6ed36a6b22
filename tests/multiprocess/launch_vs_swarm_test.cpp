// The same simulated swarm run twice: in one process (`dsswarm demo`, the
// swarm over the in-memory transport) and as robot processes on loopback
// (`dsswarm launch --sim`, secured DDS). Both must run the same encounters,
// accept the same ones and agree on each accepted transform: the processes
// differ only in when a message arrives, not in the decision.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "geometry/pose2.hpp"
#include "multiprocess.hpp"

namespace dsswarm::mp {
namespace {

// Issue 13: "transforms within 1 cm / 0.1°".
constexpr double kMaxTranslation = 0.01;               // m
constexpr double kMaxRotation = 0.1 * std::numbers::pi / 180.0;  // rad

// The first 72 s of seed 1's run at twice real time: encounters 0-6, of
// which 3 (44.6 s) and 6 (59.6 s) are accepted. Both paths swap a merged map
// in at the same scan (swarm.merge_delay after the encounter's), so the
// launched robots localize the same scans in the same maps as in process
// unless a merge is late. The whole run at real time, 3 and 8 robots, is
// compared in docs/swarm_processes.md.
const std::string kDuration = "72", kRate = "2";

struct Encounter {
  bool accepted = false;
  Pose2 transform;
  std::string reason;
};

// A run's encounters.json, by (id, "A-B").
std::map<std::pair<std::uint64_t, std::string>, Encounter> encounters(const fs::path& run) {
  std::map<std::pair<std::uint64_t, std::string>, Encounter> out;
  const nlohmann::json all = read_json(run / "encounters.json");  // (held: the loop runs over a part of it)
  for (const nlohmann::json& e : all.at("encounters")) {
    const auto& t = e.at("transform");
    const std::string pair = e.at("agents")[0].get<std::string>() + "-" + e.at("agents")[1].get<std::string>();
    const Encounter enc{e.at("accepted").get<bool>(), Pose2(t[0].get<double>(), t[1].get<double>(), t[2].get<double>()),
                        e.value("reason", "")};
    EXPECT_TRUE(out.emplace(std::pair{e.at("id").get<std::uint64_t>(), pair}, enc).second)
        << run.string() << ": encounter " << e.at("id") << " of " << pair << " twice";
  }
  return out;
}

std::string scans_summary(const fs::path& run) {
  std::string text;
  const nlohmann::json stats = read_json(run / "stats.json");
  for (const nlohmann::json& a : stats.at("agents"))
    text += fmt::format(" {}: {} scans, {} skipped;", a.at("name").get<std::string>(), a.value("scans_received", 0),
                        a.value("scans_skipped", 0));
  return text;
}

TEST(LaunchVsSwarmMultiProcess, SimulatedSwarmAcceptsTheSameEncountersWithTheSameTransforms) {
  Rig rig;
  const fs::path in_process = rig.dir() / "swarm", processes = rig.dir() / "launch";
  // In-process first: the two runs would otherwise compete for the cores, and
  // a robot process that falls behind skips scans (and maps differently).
  const std::size_t demo = rig.start("demo", {"demo", "--robots", "3", "--run-seed", "1", "--duration", kDuration,
                                              "--out", in_process.string()});
  ASSERT_EQ(rig.wait(demo, 120s), 0);
  const std::size_t launch = rig.start(
      "launch", {"launch", "--sim", "1", "--robots", "3", "--duration", kDuration, "--rate", kRate, "--out",
                 processes.string(), "--swarm-domain", std::to_string(test_domain(0)), "--ros-domain",
                 std::to_string(test_domain(1))});  // secured: the default
  ASSERT_EQ(rig.wait(launch, 180s), 0);

  const auto want = encounters(in_process), got = encounters(processes);
  ASSERT_FALSE(want.empty());
  std::size_t accepted = 0;
  double worst_translation = 0.0, worst_rotation = 0.0;
  for (const auto& [key, w] : want) {
    const auto it = got.find(key);
    if (it == got.end()) {
      ADD_FAILURE() << "encounter " << key.first << " of " << key.second << " ran in process but not in `launch`";
      continue;
    }
    const Encounter& g = it->second;
    EXPECT_EQ(g.accepted, w.accepted) << "encounter " << key.first << " of " << key.second << ": in process "
                                      << (w.accepted ? "accepted" : "rejected (" + w.reason + ")") << ", launched "
                                      << (g.accepted ? "accepted" : "rejected (" + g.reason + ")");
    if (!(w.accepted && g.accepted)) continue;
    ++accepted;
    const Pose2 d = between(w.transform, g.transform);
    const double translation = std::hypot(d.x, d.y), rotation = std::abs(normalize_angle(d.theta));
    worst_translation = std::max(worst_translation, translation);
    worst_rotation = std::max(worst_rotation, rotation);
    EXPECT_LT(translation, kMaxTranslation) << "encounter " << key.first << " of " << key.second;
    EXPECT_LT(rotation, kMaxRotation) << "encounter " << key.first << " of " << key.second;
  }
  for (const auto& [key, g] : got)
    EXPECT_TRUE(want.count(key)) << "encounter " << key.first << " of " << key.second << " ran only in `launch`";
  EXPECT_GT(accepted, 0u) << "nothing accepted: the comparison of transforms compared nothing";
  std::cout << fmt::format("launch vs in-process: {} encounters, {} accepted by both; worst transform difference "
                           "{:.1f} mm / {:.3f}°; launched robots:{}\n",
                           want.size(), accepted, 1000.0 * worst_translation, worst_rotation * 180.0 / std::numbers::pi,
                           scans_summary(processes));
}

}  // namespace
}  // namespace dsswarm::mp
