#pragma once
// How a robot process (or a swarm tool: proximity, trigger, status) reaches
// the swarm and its own ROS 2 side: two DDS participants, because the swarm
// may be secured (DDS Security) while ROS 2 viewers cannot join a secured
// Cyclone domain (../shared/notes/ros2-dds.md).
//   swarm:  domain --swarm-domain (default 42), partition "dsswarm.<--swarm>";
//           with --keys DIR: the domain the keys are signed for, secured.
//   ROS 2:  domain --ros-domain (default $ROS_DOMAIN_ID, else 0), unsecured.
#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>

#include "net/dds.hpp"
#include "net/swarm_link.hpp"

namespace dsswarm {

struct SwarmNetOptions {
  std::string swarm = "default";  // swarm id (partition)
  std::optional<int> swarm_domain;
  std::optional<int> ros_domain;
  std::string interface = "auto";  // network interface; "lo" = this machine only
  std::string keys;                // keys directory (dsswarm keys): secure the swarm topics
  // The ROS 2 topics too: they move to the secured swarm domain, where only
  // holders of a certificate of the swarm's CA (dsswarm keys add) see them.
  bool secure_ros = false;
  // Seconds peers keep a silent robot's swarm participant (DDS lease; Cyclone's
  // default is 10). A robot killed without a goodbye stays matched that long,
  // and messages to its restarted process wait behind what it never took.
  // Our heartbeats (1 s) and discovery (every 0.8 lease) keep live robots in it.
  double lease = 4.0;
};

void add_swarm_net_options(CLI::App& command, SwarmNetOptions& options);

class SwarmNet {
 public:
  // `name`: this robot's (or tool's) identity; `listen`: read an inbox and heartbeats.
  SwarmNet(const SwarmNetOptions& options, const std::string& name, bool listen = true);
  ~SwarmNet();
  net::Participant& ros();  // made on first use
  // Stays valid across recreations of the swarm participant (maintain()).
  protocol::SwarmLink& link();
  bool secured() const { return secured_; }
  int swarm_domain() const { return swarm_domain_; }

  // Works around Cyclone 0.10.2's lost security handshakes (cyclonedds
  // #1895, docs/security.md): call every second or so; when a peer has been
  // alive in discovery but never matched for a while, the swarm participant
  // is recreated with all its endpoints (a fresh handshake with everyone).
  // Returns whether it did. Does nothing on an unsecured swarm.
  bool maintain();
  std::size_t recreations() const;

 private:
  class StableLink;
  void open_swarm();

  SwarmNetOptions options_;
  std::string name_;
  bool secured_ = false;
  int swarm_domain_ = 0;
  std::string security_xml_;
  net::SwarmLinkConfig link_config_;
  std::unique_ptr<net::Participant> swarm_, ros_;
  std::unique_ptr<net::DdsSwarmLink> dds_link_;
  std::unique_ptr<StableLink> link_;
  struct Watch;
  std::unique_ptr<Watch> watch_;
};

}  // namespace dsswarm
