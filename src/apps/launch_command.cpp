#include "apps/launch_command.hpp"

#include <fmt/core.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <thread>

#include "agent/proximity_player.hpp"
#include "apps/launch_gather.hpp"
#include "apps/process_group.hpp"
#include "apps/sim_swarm_run.hpp"
#include "apps/slam_options.hpp"
#include "apps/stop_signal.hpp"
#include "apps/swarm_command.hpp"
#include "apps/swarm_report.hpp"
#include "apps/swarm_runner.hpp"
#include "apps/swarm_scenario.hpp"
#include "common/errors.hpp"
#include "config/config_json.hpp"
#include "io/atomic_file.hpp"
#include "io/output_paths.hpp"
#include "net/security/keystore.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

struct LaunchArgs {
  std::string scenario;
  std::optional<std::uint64_t> sim_seed;
  int robots = 3;
  std::uint64_t world_seed = 1;
  double proximity_range = 3.0;
  std::string out;
  double rate = 1.0;
  bool no_security = false;
  std::optional<int> swarm_domain, ros_domain;
  double startup = 5.0;  // s for every process to come up before the clocks start
  double settle = 10.0;  // s after the last scan for the last encounters to finish
  SlamOptions slam;
};

// What the launch plays: robot names, their streams (for timing and the
// proximity schedule), and, simulated, the truth.
struct Plan {
  std::vector<AgentStream> streams;
  std::vector<EncounterEvent> events;
  std::optional<SwarmTruth> truth;
  SwarmConfig config;
  std::string relations;  // scenario: relations file for the evaluation
};

Plan make_plan(const LaunchArgs& a) {
  Plan p;
  SlamOptions slam = a.slam;
  if (a.sim_seed) {
    SimSwarmRun sim = simulate_swarm_run({a.robots, *a.sim_seed, a.world_seed, a.proximity_range});
    p.streams = std::move(sim.streams);
    p.events = std::move(sim.events);
    p.truth = std::move(sim.truth);
    p.config = slam.resolve_swarm();
    p.config.encounter.locate.search_radius = a.proximity_range;  // as the demo
    return p;
  }
  SwarmScenario s = load_swarm_scenario(a.scenario);
  for (const std::string& w : s.warnings) spdlog::warn("{}", w);
  if (slam.config_file.empty() && s.config) slam.config_file = *s.config;
  p.streams = std::move(s.streams);
  p.events = std::move(s.events);
  p.config = slam.resolve_swarm();
  p.relations = s.relations;
  return p;
}

double seconds_of(const Plan& p) {
  double end = 0.0;
  for (const AgentStream& s : p.streams)
    if (!s.clock.empty()) end = std::max(end, s.clock.back());
  return end;
}

std::string text(double v) { return fmt::format("{}", v); }

// Domains of their own for this run (another launch or test on the machine stays apart).
std::pair<int, int> domains(const LaunchArgs& a) {
  const int base = 100 + static_cast<int>(getpid() % 60) * 2;
  return {a.swarm_domain.value_or(base), a.ros_domain.value_or(a.swarm_domain ? *a.swarm_domain + 1 : base + 1)};
}

class Launch {
 public:
  Launch(const LaunchArgs& a, Plan plan) : a_(a), plan_(std::move(plan)), out_(a.out), exe_(fs::read_symlink("/proc/self/exe")) {
    std::tie(swarm_domain_, ros_domain_) = domains(a);
    fs::create_directories(out_ / "logs");
    write_file_atomically(out_ / "config.json", to_json(plan_.config).dump(2) + "\n");
    if (!a.no_security) make_keys();
  }

  // Starts everything, waits for the run to end, stops what still runs.
  void run() {
    const double start_at = unix_now() + a_.startup;
    for (std::size_t k = 0; k < plan_.streams.size(); ++k) start_agent(k, start_at);
    if (!a_.sim_seed) {
      for (const AgentStream& s : plan_.streams) start_replay(s.name, start_at);
      if (!plan_.events.empty()) proximity_ = group_.start(proximity_argv(start_at), out_ / "logs" / "proximity.log");
    }
    const double run_seconds = a_.startup + seconds_of(plan_) / a_.rate;
    fmt::print(stderr, "launch: {} robot process(es){}, about {:.0f} s; logs in {}\n", plan_.streams.size(),
               a_.sim_seed ? "" : fmt::format(" + {} replay(s) + proximity", plan_.streams.size()), run_seconds,
               (out_ / "logs").string());
    wait_for_the_end(run_seconds);
  }

  const Plan& plan() const { return plan_; }
  const fs::path& out() const { return out_; }

 private:
  static double unix_now() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  }

  void make_keys() {
    const fs::path keys = out_ / "keys";
    fs::remove_all(keys);  // a fresh swarm CA per run: nothing of an earlier one is trusted
    security::KeysInitOptions init;
    init.swarm_id = swarm_domain_;
    security::init_keys(keys, init);
    for (const AgentStream& s : plan_.streams) security::add_robot(keys, s.name);
    security::add_robot(keys, "proximity");
  }

  std::vector<std::string> swarm_options() const {
    std::vector<std::string> o{"--swarm", "launch", "--interface", "lo", "--ros-domain", std::to_string(ros_domain_)};
    if (a_.no_security) {
      o.insert(o.end(), {"--swarm-domain", std::to_string(swarm_domain_)});
    } else {
      o.insert(o.end(), {"--keys", (out_ / "keys").string()});
    }
    return o;
  }

  void start_agent(std::size_t k, double start_at) {
    const std::string& name = plan_.streams[k].name;
    std::vector<std::string> argv{exe_.string(), "agent", "--name", name, "--out", (out_ / "agents" / name).string(),
                                  "--config", (out_ / "config.json").string(), "--namespace", "/" + name,
                                  "--checkpoint-period", "10",
                                  // Two seconds of a 10 Hz lidar at the playback rate may wait.
                                  "--queue", std::to_string(std::max(8, static_cast<int>(std::ceil(20.0 * a_.rate))))};
    const auto net = swarm_options();
    argv.insert(argv.end(), net.begin(), net.end());
    if (a_.sim_seed)
      argv.insert(argv.end(), {"--sim", std::to_string(*a_.sim_seed), "--robot", std::to_string(k + 1), "--robots",
                               std::to_string(a_.robots), "--world-seed", std::to_string(a_.world_seed),
                               "--proximity-range", text(a_.proximity_range), "--rate", text(a_.rate), "--start-at",
                               fmt::format("{:.6f}", start_at), "--linger", text(a_.settle)});
    agents_.push_back(group_.start(argv, out_ / "logs" / (name + ".log")));
  }

  void start_replay(const std::string& name, double start_at) {
    replays_.push_back(group_.start({exe_.string(), "replay", "--scenario", a_.scenario, "--agent", name,
                                     "--namespace", "/" + name, "--domain", std::to_string(ros_domain_), "--interface",
                                     "lo", "--rate", text(a_.rate), "--start-at", fmt::format("{:.6f}", start_at),
                                     "--wait-for-subscribers", "1", "--wait-timeout", text(a_.startup + 60.0)},
                                    out_ / "logs" / ("replay_" + name + ".log")));
  }

  std::vector<std::string> proximity_argv(double start_at) const {
    std::vector<std::string> argv{exe_.string(), "proximity", a_.scenario, "--rate", text(a_.rate), "--start-at",
                                  fmt::format("{:.6f}", start_at)};
    const auto net = swarm_options();
    argv.insert(argv.end(), net.begin(), net.end());
    return argv;
  }

  bool all_ended(const std::vector<std::size_t>& which) {
    return std::all_of(which.begin(), which.end(), [&](std::size_t i) { return group_.poll(i).has_value(); });
  }

  void wait_for_the_end(double run_seconds) {
    const auto t0 = Clock::now();
    auto next_report = t0 + 5s;
    // Scenario: robots run until told; their input ends with the replays.
    // Simulated: each robot stops by itself once its run and the settle time are over.
    std::vector<std::size_t> inputs = a_.sim_seed ? agents_ : replays_;
    if (proximity_) inputs.push_back(*proximity_);
    while (!StopOnSignal::requested() && !all_ended(inputs)) {
      std::this_thread::sleep_for(100ms);
      if (Clock::now() < next_report) continue;
      const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
      fmt::print(stderr, "launch: {:.0f} of about {:.0f} s\n", elapsed, run_seconds);
      next_report += 5s;
    }
    if (!a_.sim_seed && !StopOnSignal::requested()) {
      const auto settle_until = Clock::now() + std::chrono::milliseconds(static_cast<long>(a_.settle * 1000));
      while (!StopOnSignal::requested() && Clock::now() < settle_until) std::this_thread::sleep_for(100ms);
    }
    // SIGTERM: every robot writes its outputs and a last checkpoint.
    for (std::size_t i : agents_) group_.signal(i, SIGTERM);
    for (std::size_t i : agents_)
      if (const auto status = group_.wait(i, 60s); status && *status != 0)
        spdlog::warn("launch: robot process {} ended with status {} (see its log)", i, *status);
    group_.stop_all(5s);
  }

  const LaunchArgs& a_;
  Plan plan_;
  fs::path out_;
  fs::path exe_;
  int swarm_domain_ = 0, ros_domain_ = 0;
  ProcessGroup group_;
  std::vector<std::size_t> agents_, replays_;
  std::optional<std::size_t> proximity_;
};

void check(const LaunchArgs& a) {
  if (a.scenario.empty() == !a.sim_seed)
    throw ConfigError("launch takes a SCENARIO.yaml or --sim SEED (one of the two)");
  if (!(std::isfinite(a.rate) && a.rate > 0.0)) throw ConfigError(fmt::format("--rate {} is not > 0", a.rate));
  if (!(a.startup >= 1.0) || !(a.settle >= 0.0)) throw ConfigError("--startup must be >= 1 s and --settle >= 0 s");
}

void run_launch(const LaunchArgs& a) {
  check(a);
  check_output_directory(a.out, "--out");
  const StopOnSignal stop_on_signal;
  Launch launch(a, make_plan(a));
  const auto t0 = Clock::now();
  launch.run();
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  const Plan& plan = launch.plan();
  std::vector<std::string> names;
  for (const AgentStream& s : plan.streams) names.push_back(s.name);
  std::map<std::uint64_t, double> times;
  const auto schedule = agent::proximity_schedule(plan.streams, plan.events);
  for (const agent::TimedProximity& e : schedule) times[e.event.event] = e.time;
  const GatheredRun g = gather_launch(launch.out(), names, plan.config, times);
  for (const std::string& p : g.problems) spdlog::warn("launch: {}", p);
  SwarmOutputOptions options;
  options.wall_seconds = seconds;
  options.truth = plan.truth && g.run.agents.size() == names.size() ? &*plan.truth : nullptr;
  options.agent_files = false;
  nlohmann::json stats = write_swarm_outputs(launch.out(), g.run, options);
  fmt::print("launch: {} robot processes, {:.1f} s; outputs in {}\n", g.run.agents.size(), seconds, a.out);
  fmt::print("{}", describe_robot_processes(g.run, g.agent_stats));
  fmt::print("{} encounters, {} accepted; mean match {:.0f} ms, {:.0f} kB exchanged\n",
             stats["encounters"].get<std::size_t>(), stats["encounters_accepted"].get<std::size_t>(),
             stats["mean_match_ms"].get<double>(), stats["mean_bytes"].get<double>() / 1000.0);
  if (options.truth) fmt::print("{}", describe_simulated_outcome(stats));
  if (!plan.relations.empty()) evaluate_scenario_run(a.out, read_relations(plan.relations));
}

}  // namespace

void add_launch_command(CLI::App& app) {
  auto args = std::make_shared<LaunchArgs>();
  CLI::App* cmd = app.add_subcommand(
      "launch", "Run a swarm on this machine as separate processes: per robot a replay (or a simulated robot) and an "
                "agent, plus the proximity source; gather and evaluate the outputs as `swarm` does");
  cmd->add_option("scenario", args->scenario, "Scenario YAML (as for `dsswarm swarm`)");
  cmd->add_option("--sim", args->sim_seed, "Instead: the built-in simulated swarm with this run seed");
  cmd->add_option("--robots", args->robots, "With --sim: robots")->check(CLI::Range(1, 16))->capture_default_str();
  cmd->add_option("--world-seed", args->world_seed, "With --sim: seed of the building")->capture_default_str();
  cmd->add_option("--proximity-range", args->proximity_range, "With --sim: proximity sensor range (m)")
      ->capture_default_str();
  cmd->add_option("--out", args->out, "Output directory")->required();
  cmd->add_option("--rate", args->rate, "Playback speed factor (1 = real time)")->capture_default_str();
  cmd->add_flag("--no-security", args->no_security, "Swarm topics without DDS Security (default: a fresh swarm CA)");
  cmd->add_option("--swarm-domain", args->swarm_domain, "DDS domain of the swarm (default: one of this run's own)");
  cmd->add_option("--ros-domain", args->ros_domain, "DDS domain of the robots' ROS 2 topics (default: the next one)");
  cmd->add_option("--startup", args->startup, "Seconds for the processes to start before the clocks do")
      ->capture_default_str();
  cmd->add_option("--settle", args->settle, "Seconds after the last scan for the last encounters")
      ->capture_default_str();
  add_slam_options(*cmd, args->slam);
  cmd->callback([args] { run_launch(*args); });
}

}  // namespace dsswarm
