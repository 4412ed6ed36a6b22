#include "apps/proximity_command.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <thread>

#include "agent/agent_runtime.hpp"
#include "agent/proximity_player.hpp"
#include "apps/sim_swarm_run.hpp"
#include "apps/start_time.hpp"
#include "apps/stop_signal.hpp"
#include "apps/swarm_options.hpp"
#include "apps/swarm_scenario.hpp"
#include "common/errors.hpp"
#include "protocol/wire.hpp"

namespace dsswarm {
namespace {

using namespace std::chrono_literals;

constexpr auto kRetryPause = 100ms;  // between attempts at an undiscovered inbox

struct ProximityArgs {
  std::string scenario;
  std::optional<std::uint64_t> sim_seed;
  int robots = 3;
  std::uint64_t world_seed = 1;
  double proximity_range = 3.0;
  double rate = 1.0;
  std::optional<double> start_at;
  double lead = 1.0;
  double wait = 10.0;
  SwarmNetOptions net;
};

void check(const ProximityArgs& a) {
  if (a.scenario.empty() == !a.sim_seed.has_value())
    throw ConfigError("give a SCENARIO file or --sim SEED (one of them)");
  if (!(std::isfinite(a.rate) && a.rate > 0.0)) throw ConfigError(fmt::format("--rate {} is not > 0", a.rate));
  if (!(std::isfinite(a.lead) && a.lead >= 0.0)) throw ConfigError(fmt::format("--lead {} is not >= 0", a.lead));
  if (!(std::isfinite(a.wait) && a.wait > 0.0)) throw ConfigError(fmt::format("--wait {} is not > 0", a.wait));
  // Agents wait this long (wall time, from its arrival) for the scan an event names.
  const double patience = agent::AgentOptions{}.trigger_patience;
  if (a.lead >= patience / 2)
    spdlog::warn("--lead {} s: agents wait at most {} s for the scan an event names; events may fire late", a.lead,
                 patience);
  start_time(a.start_at);  // checks it
}

std::vector<agent::TimedProximity> schedule_of(const ProximityArgs& a) {
  if (a.sim_seed) {
    const SimSwarmRun sim = simulate_swarm_run({a.robots, *a.sim_seed, a.world_seed, a.proximity_range});
    return agent::proximity_schedule(sim.streams, sim.events);
  }
  const SwarmScenario scenario = load_swarm_scenario(a.scenario);
  for (const std::string& w : scenario.warnings) spdlog::warn("{}", w);
  return agent::proximity_schedule(scenario.streams, scenario.events);
}

std::string after_text(double stamp) { return std::isnan(stamp) ? "(no scan yet)" : fmt::format("{:.6f}", stamp); }

void run_proximity(const ProximityArgs& a) {
  check(a);
  const std::vector<agent::TimedProximity> schedule = schedule_of(a);
  const std::string source = a.sim_seed ? fmt::format("simulated swarm (seed {})", *a.sim_seed) : a.scenario;
  if (schedule.empty()) {
    fmt::print("no encounter events in {}\n", source);
    return;
  }
  const StopOnSignal stop_on_signal;
  SwarmNet net(a.net, "proximity", false);
  protocol::MessageStamper stamper("proximity", incarnation_now());
  const auto wait = std::chrono::milliseconds(std::llround(a.wait * 1000.0));
  std::atomic<std::size_t> sent{0}, undelivered{0};
  // Robots missed before (stopped, crashed) get one attempt, not --wait: the others' events must stay on time.
  std::set<std::string> given_up;
  {
    agent::ProximityPlayer player(schedule, a.rate, a.lead, start_time(a.start_at), [&](const protocol::Proximity& e) {
      const std::vector<std::string> missed =
          send_proximity(net.link(), stamper, e, wait, StopOnSignal::requested(), given_up);
      for (const std::string& robot : {e.a, e.b}) given_up.erase(robot);
      given_up.insert(missed.begin(), missed.end());
      ++sent;
      undelivered += missed.empty() ? 0 : 1;
      fmt::print("event {} at {:.3f} s: {} after {}, {} after {}{}\n", e.event, schedule[e.event].time, e.a,
                 after_text(e.a_stamp), e.b, after_text(e.b_stamp),
                 missed.empty() ? "" : fmt::format(" - NOT delivered to {}", fmt::join(missed, ", ")));
      std::fflush(stdout);
    });
    while (!player.done() && !StopOnSignal::requested()) std::this_thread::sleep_for(50ms);
  }
  if (StopOnSignal::requested()) fmt::print("interrupted after {} of {} events\n", sent.load(), schedule.size());
  if (undelivered > 0)
    throw std::runtime_error(fmt::format("{} of {} events did not reach both robots within --wait {} s (swarm '{}', "
                                         "domain {})",
                                         undelivered.load(), sent.load(), a.wait, a.net.swarm, net.swarm_domain()));
}

}  // namespace

std::uint64_t incarnation_now() {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count());
}

std::vector<std::string> send_proximity(protocol::SwarmLink& link, protocol::MessageStamper& stamper,
                                        const protocol::Proximity& event, std::chrono::milliseconds wait,
                                        const std::atomic<bool>& stop, const std::set<std::string>& given_up) {
  std::vector<std::string> missed;
  const auto deadline = std::chrono::steady_clock::now() + wait;
  for (const std::string& robot : {event.a, event.b}) {
    const std::vector<std::uint8_t> bytes = protocol::encode(stamper.stamp(robot, event));
    while (!link.send(robot, bytes)) {
      if (stop || given_up.count(robot) > 0 || std::chrono::steady_clock::now() >= deadline) {
        missed.push_back(robot);
        break;
      }
      std::this_thread::sleep_for(kRetryPause);
    }
  }
  return missed;
}

void add_proximity_command(CLI::App& app) {
  auto args = std::make_shared<ProximityArgs>();
  CLI::App* cmd = app.add_subcommand(
      "proximity", "Publish a scenario's (or the simulated swarm's) encounter events on time, as Proximity messages "
                   "to both robots; identity 'proximity' (with --keys: `dsswarm keys add DIR proximity`)");
  cmd->add_option("scenario", args->scenario, "Scenario file (as `swarm` takes)");
  cmd->add_option("--sim", args->sim_seed, "Instead: the built-in simulated swarm's events (this run seed)");
  cmd->add_option("--robots", args->robots, "With --sim: robots in the simulated swarm")->capture_default_str();
  cmd->add_option("--world-seed", args->world_seed, "With --sim: seed of the generated building")->capture_default_str();
  cmd->add_option("--proximity-range", args->proximity_range, "With --sim: proximity sensor range (m)")
      ->capture_default_str();
  cmd->add_option("--rate", args->rate, "Playback speed factor (as the replays')")->capture_default_str();
  cmd->add_option("--start-at", args->start_at, "Unix time of clock 0 (as the replays'); default: now");
  cmd->add_option("--lead", args->lead,
                  "Seconds (wall time, whatever --rate) before its time that an event is sent, so that it reaches the "
                  "robots before the scan it names")
      ->capture_default_str();
  cmd->add_option("--wait", args->wait, "Seconds to keep trying a robot whose inbox is not discovered")
      ->capture_default_str();
  add_swarm_net_options(*cmd, args->net);
  cmd->callback([args] { run_proximity(*args); });
}

}  // namespace dsswarm
