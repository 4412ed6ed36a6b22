#include "apps/replay_command.hpp"

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "agent/paced_feed.hpp"
#include "apps/log_input.hpp"
#include "apps/start_time.hpp"
#include "apps/stop_signal.hpp"
#include "apps/swarm_scenario.hpp"
#include "common/errors.hpp"
#include "io/logs/log_reader.hpp"
#include "net/dds.hpp"
#include "net/sensor_publisher.hpp"
#include "sensor/play_clock.hpp"

namespace dsswarm {
namespace {

using Clock = std::chrono::steady_clock;

constexpr auto kSleepSlice = std::chrono::milliseconds(50);  // how soon SIGINT is noticed
constexpr auto kProgressPeriod = std::chrono::seconds(2);
constexpr auto kFinalAckTimeout = std::chrono::seconds(2);
constexpr double kLateStartWarning = 1.0;  // s past --start-at before the first scan goes out

struct ReplayArgs {
  std::string log;
  std::string scenario, agent;  // instead of a log: one agent's stream of a scenario
  std::string ns;
  double rate = 1.0;
  double start = 0.0;
  std::optional<double> start_at;
  bool loop = false;
  int wait_for_subscribers = 0;
  double wait_timeout = 30.0;
  int domain = 0;
  std::string interface = "auto";
};

// What goes out: scans in play order and when, in seconds after clock 0 (nullopt: skipped).
struct Playback {
  std::string source;  // for messages
  std::vector<LaserScan> scans;
  std::vector<std::optional<double>> schedule;
};

std::atomic<bool>& g_stop = StopOnSignal::requested();

// Sleeps until `t` unless asked to stop; returns false when stopped.
bool sleep_until(Clock::time_point t) {
  while (!g_stop) {
    const auto now = Clock::now();
    if (now >= t) return true;
    std::this_thread::sleep_for(std::min<Clock::duration>(t - now, kSleepSlice));
  }
  return false;
}

void check_args(const ReplayArgs& a) {
  if (a.log.empty() == a.scenario.empty()) throw ConfigError("give a LOG or --scenario FILE --agent NAME (one of them)");
  if (a.scenario.empty() != a.agent.empty()) throw ConfigError("--scenario and --agent go together");
  if (!a.scenario.empty() && (a.start != 0.0 || a.loop))
    throw ConfigError("--start and --loop go with a LOG: a scenario's agent plays its segment once");
  if (!(std::isfinite(a.rate) && a.rate > 0.0)) throw ConfigError(fmt::format("--rate {} is not > 0", a.rate));
  if (!(std::isfinite(a.start) && a.start >= 0.0)) throw ConfigError(fmt::format("--start {} is not >= 0", a.start));
  if (a.wait_for_subscribers < 0) throw ConfigError("--wait-for-subscribers must be >= 0");
  if (!(std::isfinite(a.wait_timeout) && a.wait_timeout > 0.0)) {
    throw ConfigError(fmt::format("--wait-timeout {} is not > 0", a.wait_timeout));
  }
  if (a.domain < 0) throw ConfigError(fmt::format("--domain {} is negative", a.domain));
  start_time(a.start_at);  // checks it
}

Playback log_playback(const ReplayArgs& a) {
  SensorLog log = read_input_log(a.log);
  std::vector<double> stamps;
  for (const auto& s : log.scans) stamps.push_back(s.timestamp);
  return {a.log, std::move(log.scans), replay_schedule(stamps, a.rate, a.start)};
}

// The agent's stream as the in-process swarm plays it: scan i at clock[i] / rate.
Playback scenario_playback(const ReplayArgs& a) {
  SwarmScenario scenario = load_swarm_scenario(a.scenario);
  for (const auto& w : scenario.warnings) spdlog::warn("{}", w);
  std::string names;
  for (AgentStream& s : scenario.streams) {
    if (s.name != a.agent) {
      names += (names.empty() ? "" : ", ") + s.name;
      continue;
    }
    Playback p{fmt::format("{} (agent {})", a.scenario, a.agent), std::move(s.scans), {}};
    for (const double t : s.clock) p.schedule.emplace_back(t / a.rate);
    return p;
  }
  throw ConfigError(fmt::format("--agent {}: {} has no such agent (it has {})", a.agent, a.scenario, names));
}

struct Progress {
  std::size_t published = 0;
  Clock::time_point last_report = Clock::now();
};

// One pass from `wall_start` (clock 0); returns false when stopped by a signal.
bool play_once(const Playback& p, Clock::time_point wall_start, double rate, net::SensorPublisher& publisher,
               Progress& progress) {
  const double seconds = p.schedule.back().value_or(0.0) * rate;
  for (std::size_t i = 0; i < p.scans.size(); ++i) {
    if (!p.schedule[i]) continue;
    const auto offset = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(*p.schedule[i]));
    if (!sleep_until(wall_start + offset)) return false;
    publisher.publish(p.scans[i]);
    ++progress.published;
    if (Clock::now() - progress.last_report >= kProgressPeriod) {
      fmt::print(stderr, "replay: scan {}/{}, play time {:.1f} of {:.1f} s, rate {}x, {} subscriber(s)\n", i + 1,
                 p.scans.size(), *p.schedule[i] * rate, seconds, rate, publisher.subscribers());
      progress.last_report = Clock::now();
    }
  }
  return true;
}

// Holds the first scan until `a.wait_for_subscribers` subscribers know us
// (matched, and /tf_static acknowledged). Returns false when stopped by a
// signal; throws after --wait-timeout.
bool wait_for_subscribers(const ReplayArgs& a, const Playback& p, net::SensorPublisher& publisher) {
  fmt::print(stderr, "replay: waiting for {} subscriber(s) on scan and odom\n", a.wait_for_subscribers);
  const bool with_odometry =
      std::any_of(p.scans.begin(), p.scans.end(), [](const LaserScan& s) { return s.odometry.has_value(); });
  const auto deadline = Clock::now() + std::chrono::milliseconds(std::llround(a.wait_timeout * 1000.0));
  const auto slice = std::chrono::duration_cast<std::chrono::milliseconds>(kSleepSlice);
  while (!publisher.wait_for_subscribers(a.wait_for_subscribers, slice, with_odometry)) {
    if (g_stop) return false;
    if (Clock::now() >= deadline) {
      throw std::runtime_error(
          fmt::format("replay: fewer than {} subscriber(s) within {} s", a.wait_for_subscribers, a.wait_timeout));
    }
  }
  const LaserScan& first = p.scans.front();
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  if (!publisher.latch_laser_offset(first.laser_offset, first.timestamp, std::max(left, slice))) {
    spdlog::warn("replay: a subscriber did not acknowledge /tf_static in time; its first scans may be lost");
  }
  return true;
}

// Clock 0 of the first pass: --start-at, else now.
Clock::time_point first_start(const ReplayArgs& a) {
  const auto start = agent::steady_start(start_time(a.start_at));
  const double late = std::chrono::duration<double>(Clock::now() - start).count();
  if (late > kLateStartWarning)
    spdlog::warn("replay: started {:.1f} s after --start-at; the scans due by now go out at once", late);
  return start;
}

void replay(const ReplayArgs& a) {
  check_args(a);
  const Playback playback = a.scenario.empty() ? log_playback(a) : scenario_playback(a);

  net::ParticipantConfig participant_config;
  participant_config.domain_id = static_cast<std::uint32_t>(a.domain);
  participant_config.interface = a.interface;
  net::Participant participant(participant_config);
  net::SensorPublisherConfig publisher_config;
  publisher_config.ns = a.ns;
  net::SensorPublisher publisher(participant, publisher_config);
  const StopOnSignal stop_on_signal;

  bool completed = a.wait_for_subscribers == 0 || wait_for_subscribers(a, playback, publisher);
  Progress progress;
  const auto t0 = Clock::now();
  for (auto start = first_start(a); completed; start = Clock::now()) {
    completed = play_once(playback, start, a.rate, publisher, progress);
    if (!a.loop) break;
  }
  publisher.wait_for_acks(kFinalAckTimeout);  // reliable subscribers get the last scans
  fmt::print("{} {} scans in {:.1f} s\n", completed ? "replayed" : "interrupted after", progress.published,
             std::chrono::duration<double>(Clock::now() - t0).count());
}

}  // namespace

std::vector<std::optional<double>> replay_schedule(const std::vector<double>& stamps, double rate, double start) {
  std::vector<std::optional<double>> out;
  out.reserve(stamps.size());
  for (const double elapsed : play_clock(stamps))
    out.push_back(elapsed < start ? std::nullopt : std::optional<double>((elapsed - start) / rate));
  return out;
}

void add_replay_command(CLI::App& app) {
  auto args = std::make_shared<ReplayArgs>();
  CLI::App* cmd = app.add_subcommand(
      "replay", "Publish a log (CARMEN or ROS1 bag), or one agent's part of a scenario, as ROS 2 LaserScan, Odometry "
                "and tf over DDS, in real time");
  cmd->add_option("log", args->log, "Log file")->check(CLI::ExistingFile);
  cmd->add_option("--scenario", args->scenario,
                  "Instead of a LOG: a scenario file (as `swarm` takes); plays the stream of --agent");
  cmd->add_option("--agent", args->agent,
                  "With --scenario: the agent whose segment, direction and start to play, on the scenario's clock");
  cmd->add_option("--namespace", args->ns, "ROS namespace of the robot, e.g. /robot1");
  cmd->add_option("--rate", args->rate, "Playback speed factor")->capture_default_str();
  cmd->add_option("--start", args->start, "With a LOG: skip the first S seconds of it")->capture_default_str();
  cmd->add_option("--start-at", args->start_at,
                  "Unix time of clock 0 (the replays of a launch start together); default: now");
  cmd->add_flag("--loop", args->loop, "With a LOG: start over at the end (until SIGINT)");
  cmd->add_option("--wait-for-subscribers", args->wait_for_subscribers,
                  "Before publishing, wait for N subscribers on scan and odom")
      ->capture_default_str();
  cmd->add_option("--wait-timeout", args->wait_timeout, "Seconds to wait for them (then fail)")->capture_default_str();
  cmd->add_option("--domain", args->domain, "DDS domain id (ROS_DOMAIN_ID)")->capture_default_str();
  cmd->add_option("--interface", args->interface, "Network interface (name or address); lo = loopback")
      ->capture_default_str();
  cmd->callback([args] { replay(*args); });
}

}  // namespace dsswarm
