#include "apps/swarm_command.hpp"

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>

#include "apps/sim_swarm_run.hpp"
#include "apps/slam_options.hpp"
#include "apps/slam_runner.hpp"
#include "apps/swarm_report.hpp"
#include "apps/swarm_runner.hpp"
#include "apps/swarm_scenario.hpp"
#include "eval/relations.hpp"
#include "eval/swarm_eval.hpp"
#include "io/atomic_file.hpp"
#include "io/output_paths.hpp"

namespace dsswarm {
namespace {

struct DemoArgs {
  std::string out = "out/demo";  // as README and scripts/demo.sh
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
  check_output_directory(a.out, "--out");
  SwarmConfig config = a.slam.resolve_swarm();
  config.encounter.locate.search_radius = a.range;  // the proximity range bounds where the other robot is
  config.merge = !a.no_merge;
  const auto t0 = std::chrono::steady_clock::now();
  SimSwarmRun sim = simulate_swarm_run({a.robots, a.seed, a.world_seed, a.range});
  fmt::print("simulated {} robot(s) × {} scans, {} proximity events, in {:.2f} s\n", a.robots,
             sim.streams.front().scans.size(), sim.events.size(),
             std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  const std::size_t planned = sim.events.size();
  SwarmSession session(std::move(sim.streams), std::move(sim.events), config);
  const double seconds = run_swarm_session(session, "demo");
  SwarmOutputOptions options;
  options.wall_seconds = seconds;
  options.truth = &sim.truth;
  const nlohmann::json stats = write_swarm_outputs(a.out, run_result(session), options);
  fmt::print("{} scans in {:.2f} s ({:.0f} scans/s); outputs in {}\n", stats["scans"].get<std::size_t>(), seconds,
             stats["scans_per_second"].get<double>(), a.out);
  print_encounter_summary(stats);
  fmt::print("{}\n",
             describe_encounter_events("proximity events", planned, session.encounters().size(), session.skipped()));
  fmt::print("{}", describe_simulated_outcome(stats));
}

struct SwarmArgs {
  std::string scenario;
  std::string out;
  bool no_merge = false;
  SlamOptions slam;
};

void run_scenario(SwarmArgs a) {
  check_output_directory(a.out, "--out");
  SwarmScenario scenario = load_swarm_scenario(a.scenario);
  for (const std::string& w : scenario.warnings) spdlog::warn("{}", w);
  if (a.slam.config_file.empty() && scenario.config) a.slam.config_file = *scenario.config;
  SwarmConfig config = a.slam.resolve_swarm();
  config.merge = !a.no_merge;
  // Read before the run, so that a bad file cannot cost the outputs a complete set.
  const std::vector<Relation> relations =
      scenario.relations.empty() ? std::vector<Relation>{} : read_relations(scenario.relations);
  std::size_t scans = 0;
  for (const AgentStream& s : scenario.streams) {
    scans += s.scans.size();
    if (!has_returns(s.scans))
      spdlog::warn("agent {}: none of its {} scans has a valid return: its map stays empty", s.name, s.scans.size());
  }
  fmt::print("scenario {}: {} agents, {} scans, {} scripted encounters\n", scenario.name, scenario.streams.size(),
             scans, scenario.events.size());
  const std::size_t planned = scenario.events.size();
  SwarmSession session(std::move(scenario.streams), std::move(scenario.events), config);
  const double seconds = run_swarm_session(session, scenario.name);
  SwarmOutputOptions options;
  options.wall_seconds = seconds;
  const nlohmann::json stats = write_swarm_outputs(a.out, run_result(session), options);
  fmt::print("{} scans in {:.2f} s ({:.0f} scans/s); outputs in {}\n", stats["scans"].get<std::size_t>(), seconds,
             stats["scans_per_second"].get<double>(), a.out);
  print_encounter_summary(stats);
  fmt::print("{}\n",
             describe_encounter_events("scripted encounters", planned, session.encounters().size(), session.skipped()));
  for (const EncounterRecord& r : session.encounters())
    fmt::print("  t={:.1f} s {}–{}: {}\n", r.time, r.a, r.b, r.accepted ? "accepted" : "rejected: " + r.reason);
  // The scenario names its relations: score the run right away.
  if (!scenario.relations.empty()) evaluate_scenario_run(a.out, relations);
}

}  // namespace

void evaluate_scenario_run(const std::filesystem::path& out, const std::vector<Relation>& relations) {
  const SwarmEvaluation ev = evaluate_swarm(read_swarm_output(out), relations);
  write_file_atomically(out / "evaluation.json", to_json(ev).dump(2) + "\n");
  fmt::print("{}", format_swarm_evaluation(ev));
}

void add_swarm_command(CLI::App& app) {
  auto args = std::make_shared<SwarmArgs>();
  CLI::App* cmd = app.add_subcommand(
      "swarm", "Several robots from recorded logs (scenario file: agents, log segments, encounters), each mapping in "
               "its own frame and merging maps when they meet");
  cmd->add_option("scenario", args->scenario, "Scenario YAML (see scenarios/README.md)")->required();
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
  cmd->add_option("--run-seed", args->seed, "Seed of the robots' starts, routes and sensor noise")
      ->check(non_negative_integer())
      ->capture_default_str();
  cmd->add_option("--world-seed", args->world_seed, "Seed of the generated building")
      ->check(non_negative_integer())
      ->capture_default_str();
  cmd->add_option("--range", args->range, "Proximity sensor range (m)")->check(CLI::Range(0.5, 20.0))->capture_default_str();
  cmd->add_flag("--no-merge", args->no_merge, "Ignore encounters: every robot maps alone (the baseline)");
  add_slam_options(*cmd, args->slam);
  cmd->callback([args] { run_demo(*args); });
}

}  // namespace dsswarm
