#include "apps/swarm_command.hpp"

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>

#include "apps/slam_options.hpp"
#include "apps/swarm_runner.hpp"
#include "apps/swarm_scenario.hpp"
#include "eval/relations.hpp"
#include "eval/swarm_eval.hpp"
#include "io/atomic_file.hpp"
#include "sim/proximity.hpp"
#include "sim/swarm_sim.hpp"

namespace dsswarm {
namespace {

struct DemoArgs {
  std::string out = "demo_out";
  int robots = 3;
  std::uint64_t seed = 1;
  std::uint64_t world_seed = 1;
  double range = 3.0;
  bool no_merge = false;
  SlamOptions slam;
};

void print_encounter_summary(const nlohmann::json& stats) {
  fmt::print("{} encounters, {} accepted; mean match {:.0f} ms, merge {:.0f} ms, {:.0f} kB exchanged\n",
             stats["encounters"].get<std::size_t>(), stats["encounters_accepted"].get<std::size_t>(),
             stats["mean_match_ms"].get<double>(), stats["mean_merge_ms"].get<double>(),
             stats["mean_bytes"].get<double>() / 1000.0);
}

void run_demo(const DemoArgs& a) {
  SwarmConfig config = a.slam.resolve_swarm();
  config.encounter.locate.search_radius = a.range;  // the proximity range bounds where the other robot is
  config.merge = !a.no_merge;
  SwarmSimConfig sim;
  sim.robots = a.robots;
  sim.seed = a.seed;
  sim.world = swarm_world_config(a.robots);
  sim.world.seed = a.world_seed;
  const auto t0 = std::chrono::steady_clock::now();
  const SimulatedSwarm swarm = simulate_swarm(sim);
  ProximityConfig proximity;
  proximity.range = a.range;
  const std::vector<ProximityEvent> near = proximity_events(swarm.world, swarm, proximity);
  fmt::print("simulated {} robot(s) × {} scans, {} proximity events, in {:.2f} s\n", a.robots,
             swarm.runs.front().log.scans.size(), near.size(),
             std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

  std::vector<AgentStream> streams;
  SwarmTruth truth;
  for (std::size_t i = 0; i < swarm.runs.size(); ++i) {
    AgentStream s{swarm.names[i], swarm.runs[i].log.scans, {}};
    for (const LaserScan& scan : s.scans) s.clock.push_back(scan.timestamp);
    streams.push_back(std::move(s));
    Trajectory t;
    for (const auto& [time, pose] : swarm.runs[i].ground_truth) t.push_back({time, pose});
    truth.world_poses.push_back(std::move(t));
  }
  std::vector<EncounterEvent> events;
  for (const ProximityEvent& e : near)
    events.push_back({e.time, static_cast<std::size_t>(e.a), static_cast<std::size_t>(e.b)});

  SwarmSession session(std::move(streams), std::move(events), config);
  const double seconds = run_swarm_session(session, "demo");
  const nlohmann::json stats = write_swarm_outputs(a.out, session, seconds, &truth);
  fmt::print("{} scans in {:.2f} s ({:.0f} scans/s); outputs in {}\n", stats["scans"].get<std::size_t>(), seconds,
             stats["scans_per_second"].get<double>(), a.out);
  print_encounter_summary(stats);
  for (const auto& agent : stats["agents"])
    fmt::print("  {}: ATE RMSE {:.3f} m, map covers {:.0f}% of what the swarm explored, knows {} other robot(s)\n",
               agent["name"].get<std::string>(), agent["ate_rmse"].get<double>(),
               100.0 * agent["coverage"].get<double>(), agent["knows"].size());
  fmt::print("worst accepted transform error {:.3f} m / {:.2f}° against the map frames as they stood (causal), "
             "{:.3f} m / {:.2f}° against the robots' true relative pose; {} wrong merges (> 0.3 m or 3° against both "
             "the robots' true relative pose and the aligned frames)\n",
             stats["worst_accepted_causal_error"][0].get<double>(), stats["worst_accepted_causal_error"][1].get<double>(),
             stats["worst_accepted_error"][0].get<double>(), stats["worst_accepted_error"][1].get<double>(),
             stats["wrong_merges"].get<std::size_t>());
}

struct SwarmArgs {
  std::string scenario;
  std::string out;
  bool no_merge = false;
  SlamOptions slam;
};

void run_scenario(SwarmArgs a) {
  SwarmScenario scenario = load_swarm_scenario(a.scenario);
  for (const std::string& w : scenario.warnings) spdlog::warn("{}", w);
  if (a.slam.config_file.empty() && scenario.config) a.slam.config_file = *scenario.config;
  SwarmConfig config = a.slam.resolve_swarm();
  config.merge = !a.no_merge;
  std::size_t scans = 0;
  for (const AgentStream& s : scenario.streams) scans += s.scans.size();
  fmt::print("scenario {}: {} agents, {} scans, {} scripted encounters\n", scenario.name, scenario.streams.size(),
             scans, scenario.events.size());
  SwarmSession session(std::move(scenario.streams), std::move(scenario.events), config);
  const double seconds = run_swarm_session(session, scenario.name);
  const nlohmann::json stats = write_swarm_outputs(a.out, session, seconds);
  fmt::print("{} scans in {:.2f} s ({:.0f} scans/s); outputs in {}\n", stats["scans"].get<std::size_t>(), seconds,
             stats["scans_per_second"].get<double>(), a.out);
  print_encounter_summary(stats);
  for (const EncounterRecord& r : session.encounters())
    fmt::print("  t={:.1f} s {}–{}: {}\n", r.time, r.a, r.b, r.accepted ? "accepted" : "rejected: " + r.reason);
  if (!scenario.relations.empty()) {
    // The scenario names its relations: score the run right away.
    const SwarmEvaluation ev = evaluate_swarm(read_swarm_output(a.out), read_relations(scenario.relations));
    const std::filesystem::path out(a.out);
    write_file_atomically(out / "evaluation.json", to_json(ev).dump(2) + "\n");
    fmt::print("{}", format_swarm_evaluation(ev));
  }
}

}  // namespace

void add_swarm_command(CLI::App& app) {
  auto args = std::make_shared<SwarmArgs>();
  CLI::App* cmd = app.add_subcommand(
      "swarm", "Several robots from recorded logs (scenario file: agents, log segments, encounters), each mapping in "
               "its own frame and merging maps when they meet");
  cmd->add_option("scenario", args->scenario, "Scenario YAML (see scenarios/README.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Output directory (created if needed)")->required();
  cmd->add_flag("--no-merge", args->no_merge, "Ignore encounters: every robot maps alone (the baseline)");
  add_slam_options(*cmd, args->slam);
  cmd->callback([args] { run_scenario(*args); });
}

void add_swarm_demo_command(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* cmd = app.add_subcommand(
      "demo", "Simulate a swarm of robots in a generated building: each maps alone until a proximity sensor says "
              "another is near, then they merge maps; scored against ground truth");
  cmd->add_option("--out", args->out, "Output directory")->capture_default_str();
  cmd->add_option("--robots", args->robots, "Number of robots")->check(CLI::Range(1, 64))->capture_default_str();
  cmd->add_option("--run-seed", args->seed, "Seed of the robots' starts, routes and sensor noise")->capture_default_str();
  cmd->add_option("--world-seed", args->world_seed, "Seed of the generated building")->capture_default_str();
  cmd->add_option("--range", args->range, "Proximity sensor range (m)")->check(CLI::Range(0.5, 20.0))->capture_default_str();
  cmd->add_flag("--no-merge", args->no_merge, "Ignore encounters: every robot maps alone (the baseline)");
  add_slam_options(*cmd, args->slam);
  cmd->callback([args] { run_demo(*args); });
}

}  // namespace dsswarm
