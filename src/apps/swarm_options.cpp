#include "apps/swarm_options.hpp"

#include <fmt/format.h>

#include <cstdlib>

#include "common/errors.hpp"
#include "net/security/security_config.hpp"

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

net::ParticipantConfig participant(int domain, const std::string& interface, std::string security = {}) {
  if (domain < 0 || domain > 232) throw ConfigError(fmt::format("DDS domain {} is outside 0..232", domain));
  net::ParticipantConfig c;
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
  cmd.add_option("--keys", o.keys, "Keys directory (dsswarm keys): the swarm topics use DDS Security");
}

SwarmNet::SwarmNet(const SwarmNetOptions& options, const std::string& name, bool listen) : options_(options) {
  std::string security;
  swarm_domain_ = options.swarm_domain.value_or(kDefaultSwarmDomain);
  net::SwarmLinkConfig link;
  link.name = name;
  link.listen = listen;
  link.partition = net::swarm_partition(options.swarm);
  if (!options.keys.empty()) {
    secured_ = true;
    const int signed_for = security::secured_domain_id(options.keys);
    if (options.swarm_domain && *options.swarm_domain != signed_for)
      throw ConfigError(fmt::format("--swarm-domain {} but the keys in {} are for domain {}", *options.swarm_domain,
                                    options.keys, signed_for));
    swarm_domain_ = signed_for;
    security = security::security_config_xml(options.keys, name);
    link.partition = "";  // the secured domain is the swarm's alone; permissions grant the default partition
  }
  if (swarm_domain_ == ros_domain_of(options.ros_domain) && secured_)
    throw ConfigError(fmt::format("the secured swarm domain {} is also the ROS 2 domain: give --ros-domain another",
                                  swarm_domain_));
  swarm_ = std::make_unique<net::Participant>(participant(swarm_domain_, options.interface, security));
  link_ = std::make_unique<net::DdsSwarmLink>(*swarm_, link);
}

net::Participant& SwarmNet::ros() {
  if (!ros_) {
    const int domain = ros_domain_of(options_.ros_domain);
    ros_ = domain == swarm_domain_ && !secured_ ? nullptr
                                                : std::make_unique<net::Participant>(participant(domain, options_.interface));
    if (!ros_) return *swarm_;  // one domain, one participant
  }
  return *ros_;
}

}  // namespace dsswarm
