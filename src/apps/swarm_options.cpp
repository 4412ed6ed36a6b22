#include "apps/swarm_options.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <optional>

#include "common/errors.hpp"
#include "net/security/discovery_probe.hpp"
#include "net/security/handshake_watchdog.hpp"
#include "net/security/security_config.hpp"

#include <shared_mutex>
#include <spdlog/spdlog.h>

namespace dsswarm {
namespace {

constexpr int kDefaultSwarmDomain = 42;

int ros_domain_of(const std::optional<int>& given) {
  if (given) return *given;
  if (const char* env = std::getenv("ROS_DOMAIN_ID"); env && *env) {
    char* end = nullptr;
    const long v = std::strtol(env, &end, 10);
    if (*end != '\0' || v < 0 || v > 232) throw ConfigError(fmt::format("ROS_DOMAIN_ID='{}' is not a domain id 0..232", env));
    return static_cast<int>(v);
  }
  return 0;
}

net::ParticipantConfig participant(int domain, const std::string& interface, std::string security = {},
                                   std::optional<double> lease = std::nullopt) {
  if (domain < 0 || domain > 232) throw ConfigError(fmt::format("DDS domain {} is outside 0..232", domain));
  net::ParticipantConfig c;
  if (lease) c.lease = std::chrono::milliseconds(std::llround(*lease * 1000.0));
  c.domain_id = static_cast<std::uint32_t>(domain);
  c.interface = interface;
  c.security_xml = std::move(security);
  return c;
}

}  // namespace

void add_swarm_net_options(CLI::App& cmd, SwarmNetOptions& o) {
  cmd.add_option("--swarm", o.swarm, "Swarm id: robots of other swarms are never seen")->capture_default_str();
  cmd.add_option("--swarm-domain", o.swarm_domain, "DDS domain of the swarm topics (default 42; with --keys, theirs)");
  cmd.add_option("--ros-domain", o.ros_domain, "DDS domain of the ROS 2 topics (default $ROS_DOMAIN_ID, else 0)");
  cmd.add_option("--interface", o.interface, "Network interface (name or address); lo = this machine only")
      ->capture_default_str();
  CLI::Option* keys = cmd.add_option("--keys", o.keys, "Keys directory (dsswarm keys): the swarm topics use DDS Security");
  cmd.add_flag("--secure-ros", o.secure_ros,
               "The ROS 2 topics too, on the secured swarm domain: viewers need a certificate of the swarm "
               "(dsswarm keys add DIR viewer) and ROS 2 security set up with it")
      ->needs(keys);
  cmd.add_option("--lease", o.lease,
                 "Seconds the swarm keeps a silent robot (DDS participant lease): a robot restarted after a crash "
                 "is reachable once its old process's lease has run out")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
}

// The link the runtime holds: forwards to the current DDS link, which
// maintain() may replace (with its participant) while the runtime runs.
class SwarmNet::StableLink : public protocol::SwarmLink {
 public:
  explicit StableLink(SwarmNet& net) : net_(net) {}
  bool send(const std::string& recipient, std::span<const std::uint8_t> bytes) override {
    std::shared_lock lock(mutex);
    return net_.dds_link_->send(recipient, bytes);
  }
  bool reachable(const std::string& recipient) override {
    std::shared_lock lock(mutex);
    return net_.dds_link_->reachable(recipient);
  }
  std::vector<std::vector<std::uint8_t>> receive(std::chrono::milliseconds timeout) override {
    std::shared_lock lock(mutex);
    return net_.dds_link_->receive(timeout);
  }
  void wake() override {
    std::shared_lock lock(mutex);
    net_.dds_link_->wake();
  }
  std::shared_mutex mutex;

 private:
  SwarmNet& net_;
};

struct SwarmNet::Watch {
  security::HandshakeWatchdog watchdog;
  std::unique_ptr<security::DiscoveryProbe> probe;
};

SwarmNet::SwarmNet(const SwarmNetOptions& options, const std::string& name, bool listen)
    : options_(options), name_(name) {
  swarm_domain_ = options.swarm_domain.value_or(kDefaultSwarmDomain);
  link_config_.name = name;
  link_config_.listen = listen;
  link_config_.partition = net::swarm_partition(options.swarm);
  if (!options.keys.empty()) {
    secured_ = true;
    const int signed_for = security::secured_domain_id(options.keys);
    if (options.swarm_domain && *options.swarm_domain != signed_for)
      throw ConfigError(fmt::format("--swarm-domain {} but the keys in {} are for domain {}", *options.swarm_domain,
                                    options.keys, signed_for));
    swarm_domain_ = signed_for;
    security_xml_ = security::security_config_xml(options.keys, name);
    link_config_.partition = "";  // the secured domain is the swarm's alone; permissions grant the default partition
  }
  if (options.secure_ros && !secured_) throw ConfigError("--secure-ros needs --keys (a secured swarm)");
  if (options.secure_ros && options.ros_domain)
    throw ConfigError("--secure-ros puts the ROS 2 topics on the secured swarm domain: leave out --ros-domain");
  if (!options.secure_ros && swarm_domain_ == ros_domain_of(options.ros_domain) && secured_)
    throw ConfigError(fmt::format("the secured swarm domain {} is also the ROS 2 domain: give --ros-domain another",
                                  swarm_domain_));
  open_swarm();
  link_ = std::make_unique<StableLink>(*this);
}

SwarmNet::~SwarmNet() = default;

void SwarmNet::open_swarm() {
  dds_link_.reset();
  swarm_.reset();
  swarm_ = std::make_unique<net::Participant>(participant(swarm_domain_, options_.interface, security_xml_, options_.lease));
  dds_link_ = std::make_unique<net::DdsSwarmLink>(*swarm_, link_config_);
  if (!secured_) return;
  if (!watch_) watch_ = std::make_unique<Watch>();
  watch_->probe = std::make_unique<security::DiscoveryProbe>(swarm_->handle(), dds_link_->writers(), dds_link_->readers());
}

protocol::SwarmLink& SwarmNet::link() { return *link_; }

bool SwarmNet::maintain() {
  if (!watch_ || !watch_->probe || !security::handshake_stuck(*watch_->probe, watch_->watchdog)) return false;
  spdlog::warn("{}: a peer stays unmatched after its security handshake (Cyclone 0.10.2, cyclonedds #1895): "
               "recreating the swarm participant",
               name_);
  std::unique_lock lock(link_->mutex);
  watch_->probe.reset();
  open_swarm();
  watch_->watchdog.recreated(security::HandshakeWatchdog::Clock::now());
  return true;
}

std::size_t SwarmNet::recreations() const { return watch_ ? watch_->watchdog.recreations() : 0; }

net::Participant& SwarmNet::ros() {
  if (!ros_ && options_.secure_ros) {
    // A participant of its own with the robot's identity: the swarm's may be
    // recreated (maintain()) under the ROS writers.
    ros_ = std::make_unique<net::Participant>(participant(swarm_domain_, options_.interface, security_xml_, options_.lease));
  }
  if (!ros_) {
    const int domain = ros_domain_of(options_.ros_domain);
    ros_ = domain == swarm_domain_ && !secured_ ? nullptr
                                                : std::make_unique<net::Participant>(participant(domain, options_.interface));
    if (!ros_) return *swarm_;  // one domain, one participant
  }
  return *ros_;
}

}  // namespace dsswarm
