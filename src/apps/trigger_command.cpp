#include "apps/trigger_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>

#include "apps/proximity_command.hpp"
#include "apps/stop_signal.hpp"
#include "apps/swarm_options.hpp"
#include "common/agent_name.hpp"
#include "common/errors.hpp"

namespace dsswarm {
namespace {

struct TriggerArgs {
  std::string a, b;
  std::optional<std::uint64_t> event;
  std::string identity = "trigger";
  double wait = 10.0;
  SwarmNetOptions net;
};

void check(const TriggerArgs& t) {
  for (const std::string& name : {t.a, t.b, t.identity})
    if (!is_valid_agent_name(name))
      throw ConfigError(fmt::format("'{}' is not a valid robot name (letters, digits, '_', '-', '.')", name));
  if (t.a == t.b) throw ConfigError(fmt::format("{} cannot meet itself: name two robots", t.a));
  if (!(std::isfinite(t.wait) && t.wait > 0.0)) throw ConfigError(fmt::format("--wait {} is not > 0", t.wait));
}

// Random, so that ids never repeat those of earlier triggers or of a scenario's events (0, 1, 2...).
std::uint64_t fresh_event_id() {
  std::random_device device;
  return (static_cast<std::uint64_t>(device()) << 32) ^ static_cast<std::uint64_t>(device());
}

void run_trigger(const TriggerArgs& t) {
  check(t);
  const StopOnSignal stop_on_signal;
  SwarmNet net(t.net, t.identity, false);
  protocol::MessageStamper stamper(t.identity, incarnation_now());
  protocol::Proximity event;
  event.a = t.a;
  event.b = t.b;
  event.event = t.event.value_or(fresh_event_id());
  const auto wait = std::chrono::milliseconds(std::llround(t.wait * 1000.0));
  const std::vector<std::string> missed = send_proximity(net.link(), stamper, event, wait, StopOnSignal::requested());
  if (!missed.empty())
    throw std::runtime_error(fmt::format("{} not reached within --wait {} s (is its agent running, in swarm '{}', "
                                         "domain {}?)",
                                         fmt::join(missed, " and "), t.wait, t.net.swarm, net.swarm_domain()));
  fmt::print("proximity event {} sent to {} and {}\n", event.event, t.a, t.b);
}

}  // namespace

void add_trigger_command(CLI::App& app) {
  auto args = std::make_shared<TriggerArgs>();
  CLI::App* cmd = app.add_subcommand("trigger", "Tell two robots they are near each other, now: they run an encounter");
  cmd->add_option("a", args->a, "A robot's name")->required();
  cmd->add_option("b", args->b, "The other robot's name")->required();
  cmd->add_option("--event", args->event, "Encounter id (default: a random 64-bit number)");
  cmd->add_option("--as", args->identity,
                  "This tool's identity in the swarm (with --keys it needs a certificate: `dsswarm keys add DIR NAME`)")
      ->capture_default_str();
  cmd->add_option("--wait", args->wait, "Seconds to keep trying a robot whose inbox is not discovered")
      ->capture_default_str();
  add_swarm_net_options(*cmd, args->net);
  cmd->callback([args] { run_trigger(*args); });
}

}  // namespace dsswarm
