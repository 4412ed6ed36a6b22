// `agent --secure-ros`: the robot's ROS 2 topics move to the secured swarm
// domain. A viewer holding a certificate of the swarm's CA gets /map there;
// nothing of it reaches the robot's unsecured local ROS 2 domain, where a
// robot without the flag (the control) does publish its map.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "multiprocess.hpp"
#include "net/dds.hpp"
#include "net/qos.hpp"
#include "net/ros_names.hpp"
#include "net/ros2_types.hpp"
#include "net/security/keystore.hpp"
#include "net/security/security_config.hpp"

namespace dsswarm::mp {
namespace {

net::ParticipantConfig on(int domain, std::string security = {}) {
  net::ParticipantConfig c;
  c.domain_id = static_cast<std::uint32_t>(domain);
  c.interface = "lo";
  c.security_xml = std::move(security);
  return c;
}

// Whether a map arrives on `ns`/map within `timeout` (Nav2's QoS: a late
// joiner gets the newest).
bool map_arrives(net::Participant& p, const std::string& ns, std::chrono::milliseconds timeout) {
  net::Topic<net::ros::OccupancyGrid> topic(p, net::ros_topic_name(ns, "map"));
  net::Reader<net::ros::OccupancyGrid> reader(topic, net::ros_transient_local(1));
  bool got = false;
  wait_until(
      [&] {
        reader.take(1, [&](const net::ros::OccupancyGrid& m, const dds_sample_info_t&) { got = m.info.width > 0; });
        return got;
      },
      timeout);
  return got;
}

std::vector<std::string> robot_args(const SimAgent& a, const std::string& ns) {
  std::vector<std::string> args = agent_args(a);
  std::erase(args, std::string("--no-ros-output"));
  args.insert(args.end(), {"--namespace", ns});
  return args;
}

TEST(SecureRosMultiProcess, TheMapGoesOnlyToHoldersOfASwarmCertificate) {
  Rig rig;
  const int swarm_domain = test_domain(0), ros_domain = test_domain(1);
  ASSERT_NE(swarm_domain, ros_domain);
  security::KeysInitOptions keys_options;
  keys_options.swarm_id = swarm_domain;
  const fs::path keys = rig.dir() / "keys";
  security::init_keys(keys, keys_options);
  for (const char* name : {"secured", "plain", "viewer"}) security::add_robot(keys, name);
  ::setenv("ROS_DOMAIN_ID", std::to_string(ros_domain).c_str(), 1);  // the robots' local ROS 2 domain

  const std::string secured_ns = fmt::format("/secured_{}", getpid()), plain_ns = fmt::format("/plain_{}", getpid());
  SimAgent a;
  a.name = "secured";
  a.robots = 2;
  a.rate = 4.0;
  a.start_at = unix_in(3.0);
  a.out = rig.dir() / "secured";
  a.keys = keys;
  a.extra = {"--secure-ros", "--duration", "30"};
  SimAgent b = a;
  b.name = "plain";
  b.robot = 2;
  b.out = rig.dir() / "plain";
  b.extra = {"--duration", "30"};
  rig.start("secured", robot_args(a, secured_ns));
  rig.start("plain", robot_args(b, plain_ns));

  {  // a secured viewer of the swarm (its own process would be the usual case: one identity per domain here)
    net::Participant viewer(on(swarm_domain, security::security_config_xml(keys, "viewer")));
    EXPECT_TRUE(map_arrives(viewer, secured_ns, 40s)) << rig.all_logs();
  }
  net::Participant local(on(ros_domain));
  EXPECT_TRUE(map_arrives(local, plain_ns, 40s)) << "the control: without --secure-ros the map is on the local domain\n"
                                                 << rig.all_logs();
  EXPECT_FALSE(map_arrives(local, secured_ns, 3s)) << "the --secure-ros robot's map reached the unsecured domain";
  ::unsetenv("ROS_DOMAIN_ID");
}

TEST(SecureRosMultiProcess, WithoutKeysOrWithARosDomainItIsAConfigError) {
  Rig rig;
  SimAgent a;
  a.name = "robot";
  a.robots = 1;
  a.rate = 4.0;
  a.start_at = unix_in(1.0);
  a.domain = test_domain(0);
  a.out = rig.dir() / "robot";
  a.extra = {"--secure-ros"};
  EXPECT_EQ(rig.wait(rig.start("nokeys", robot_args(a, "/r")), 30s), 2) << rig.log_tail("nokeys");

  security::KeysInitOptions keys_options;
  keys_options.swarm_id = test_domain(0);
  security::init_keys(rig.dir() / "keys", keys_options);
  security::add_robot(rig.dir() / "keys", "robot");
  a.keys = rig.dir() / "keys";
  a.extra = {"--secure-ros", "--ros-domain", std::to_string(test_domain(1))};
  EXPECT_EQ(rig.wait(rig.start("rosdomain", robot_args(a, "/r")), 30s), 2) << rig.log_tail("rosdomain");
  EXPECT_NE(rig.log_tail("rosdomain").find("--secure-ros"), std::string::npos) << rig.log_tail("rosdomain");
}

}  // namespace
}  // namespace dsswarm::mp
