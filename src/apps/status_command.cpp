#include "apps/status_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/stop_signal.hpp"
#include "apps/swarm_options.hpp"
#include "common/errors.hpp"
#include "protocol/gate.hpp"

namespace dsswarm {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr double kDefaultTimeout = 3.0;  // s: a couple of heartbeat periods (1 s) and discovery
constexpr auto kRefresh = 1s;            // --watch
constexpr auto kReceiveSlice = 100ms;    // how soon a signal or a deadline is noticed

struct StatusArgs {
  std::optional<double> timeout;
  bool watch = false;
  double peer_timeout = 6.0;
  std::optional<std::string> identity;
  SwarmNetOptions net;
};

struct Heard {
  protocol::AgentStatus status;
  Clock::time_point at;
};

void check(const StatusArgs& a) {
  if (a.timeout && !(std::isfinite(*a.timeout) && *a.timeout > 0.0))
    throw ConfigError(fmt::format("--timeout {} is not > 0", *a.timeout));
  if (!(std::isfinite(a.peer_timeout) && a.peer_timeout > 0.0))
    throw ConfigError(fmt::format("--peer-timeout {} is not > 0", a.peer_timeout));
}

std::string seconds_text(double s) { return s < 0.0 ? "-" : fmt::format("{:.1f}s", s); }

std::string table(const std::map<std::string, Heard>& agents, Clock::time_point now, double peer_timeout) {
  std::size_t width = 5;
  for (const auto& [name, heard] : agents) width = std::max(width, name.size());
  std::string out = fmt::format("{:<{}}  {:<5} {:>6} {:>9} {:>7} {:>9} {:>7} {:>5} {:>10} {:>10} {:>9} {:>7}\n",
                                "AGENT", width, "STATE", "HEARD", "UPTIME", "SCANS/S", "PROCESSED", "SKIPPED", "PEERS",
                                "ENCOUNTERS", "LAST-MERGE", "MAP", "REFUSED");
  for (const auto& [name, heard] : agents) {
    const protocol::AgentStatus& s = heard.status;
    const double age = std::chrono::duration<double>(now - heard.at).count();
    out += fmt::format("{:<{}}  {:<5} {:>6} {:>9} {:>7.1f} {:>9} {:>7} {:>5} {:>10} {:>10} {:>9} {:>7}\n", name,
                       width, age > peer_timeout ? "gone" : "live", seconds_text(age), seconds_text(s.uptime),
                       s.scans_per_second, s.scans_processed, s.scans_skipped, s.peers_known,
                       fmt::format("{}/{}", s.encounters_accepted, s.encounters), seconds_text(s.last_merge_age),
                       s.map_version, s.messages_rejected);
  }
  return out;
}

void show(const StatusArgs& a, const SwarmNet& net, const std::map<std::string, Heard>& agents, Clock::time_point now) {
  std::size_t gone = 0;
  for (const auto& [name, heard] : agents)
    gone += std::chrono::duration<double>(now - heard.at).count() > a.peer_timeout ? 1 : 0;
  const bool tty = a.watch && isatty(STDOUT_FILENO);
  if (tty) fmt::print("\033[H\033[2J");  // refresh in place
  fmt::print("swarm '{}' (domain {}): {} agent(s) live, {} gone\n", a.net.swarm, net.swarm_domain(),
             agents.size() - gone, gone);
  fmt::print("{}", agents.empty() ? "no agents heard yet\n" : table(agents, now, a.peer_timeout));
  if (a.watch && !tty) fmt::print("\n");
  std::fflush(stdout);
}

void run_status(const StatusArgs& a) {
  check(a);
  const std::string identity =
      a.identity.value_or(a.net.keys.empty() ? fmt::format("status_{}", getpid()) : std::string("status"));
  const StopOnSignal stop_on_signal;
  SwarmNet net(a.net, identity, true);
  protocol::MessageGate gate(identity);
  std::map<std::string, Heard> agents;
  // --watch runs until interrupted, or for --timeout if given.
  const std::optional<double> limit = a.watch ? a.timeout : a.timeout.value_or(kDefaultTimeout);
  const auto started = Clock::now();
  const auto deadline =
      started + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit.value_or(0.0)));
  auto next_refresh = started + kRefresh;
  while (!StopOnSignal::requested() && (!limit || Clock::now() < deadline)) {
    for (const std::vector<std::uint8_t>& bytes : net.link().receive(kReceiveSlice)) {
      const protocol::MessageGate::Verdict v = gate.admit(bytes);
      if (!v.message) continue;
      if (const auto* h = std::get_if<protocol::Heartbeat>(&v.message->body))
        agents[v.message->header.sender] = {h->status, Clock::now()};
    }
    if (a.watch && Clock::now() >= next_refresh) {
      show(a, net, agents, Clock::now());
      next_refresh += kRefresh;
    }
  }
  if (a.watch) return;
  if (agents.empty()) {
    fmt::print("no agents heard in swarm '{}' (domain {}) within {} s\n", a.net.swarm, net.swarm_domain(), *limit);
    return;
  }
  show(a, net, agents, Clock::now());
}

}  // namespace

void add_status_command(CLI::App& app) {
  auto args = std::make_shared<StatusArgs>();
  CLI::App* cmd = app.add_subcommand("status", "List the swarm's agents, from their heartbeats");
  cmd->add_flag("--watch", args->watch, "Keep listening, refreshing the table every second (until SIGINT)");
  cmd->add_option("--timeout", args->timeout,
                  fmt::format("Seconds to listen (default {}; with --watch: until interrupted)", kDefaultTimeout));
  cmd->add_option("--peer-timeout", args->peer_timeout, "Seconds without a heartbeat before an agent counts as gone")
      ->capture_default_str();
  cmd->add_option("--as", args->identity,
                  "This tool's identity in the swarm (default status_PID; with --keys 'status', which needs a "
                  "certificate: `dsswarm keys add DIR status`)");
  add_swarm_net_options(*cmd, args->net);
  cmd->callback([args] { run_status(*args); });
}

}  // namespace dsswarm
