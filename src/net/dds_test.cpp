#include "net/dds.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "common/errors.hpp"
#include "net/net_test_util.hpp"
#include "net/qos.hpp"
#include "net/ros2_types.hpp"
#include "net/swarm_types.hpp"

namespace dsswarm::net {
namespace {

using namespace std::chrono_literals;
using test::loopback_config;
using test::test_namespace;

constexpr auto kMatchTimeout = 5s;

std::vector<std::uint8_t> bytes(std::initializer_list<int> values) {
  std::vector<std::uint8_t> out;
  for (int v : values) out.push_back(static_cast<std::uint8_t>(v));
  return out;
}

// Takes every packet within `timeout`, stopping once `count` arrived.
std::vector<std::vector<std::uint8_t>> take_packets(const Reader<SwarmPacket>& reader, std::size_t count,
                                                    std::chrono::milliseconds timeout) {
  std::vector<std::vector<std::uint8_t>> got;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (got.size() < count && std::chrono::steady_clock::now() < deadline) {
    reader.wait(10ms);
    reader.take(16, [&](const SwarmPacket& p, const dds_sample_info_t&) {
      const auto payload = packet_payload(p);
      got.emplace_back(payload.begin(), payload.end());
    });
  }
  return got;
}

// Tests running side by side must not share a domain: each claim holds its
// domain's lock file, which nobody else can take while the test runs.
TEST(TestDomain, AClaimedDomainIsTheTestsAloneAndStaysTheSame) {
  const std::uint32_t first = test::test_domain(0), second = test::test_domain(1);
  EXPECT_NE(first, second);
  EXPECT_EQ(test::test_domain(0), first);
  for (const std::uint32_t domain : {first, second}) {
    EXPECT_GE(domain, test::kFirstTestDomain);
    EXPECT_LT(domain, test::kFirstTestDomain + test::kTestDomains);
    const auto lock = std::filesystem::temp_directory_path() / "dsswarm-test-domains" / (std::to_string(domain) + ".lock");
    const int fd = ::open(lock.c_str(), O_RDWR | O_CLOEXEC);
    ASSERT_GE(fd, 0) << lock;
    EXPECT_NE(::flock(fd, LOCK_EX | LOCK_NB), 0) << domain << " could be claimed twice";
    ::close(fd);
  }
}

TEST(DomainConfig, LoopbackUsesUnicastDiscoveryOn127001) {
  ParticipantConfig config;
  config.domain_id = 7;
  config.interface = "lo";
  const std::string xml = domain_config_xml(config);
  EXPECT_NE(xml.find("<NetworkInterface name=\"lo\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<AllowMulticast>false</AllowMulticast>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<Peer address=\"127.0.0.1\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<ParticipantIndex>auto</ParticipantIndex>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<MaxAutoParticipantIndex>31</MaxAutoParticipantIndex>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<LeaseDuration>10000 ms</LeaseDuration>"), std::string::npos) << xml;
}

TEST(DomainConfig, AutoInterfaceKeepsMulticastAndTakesTheSecurityFragment) {
  ParticipantConfig config;
  config.security_xml = "<Security><Authentication/></Security>";
  const std::string xml = domain_config_xml(config);
  EXPECT_EQ(xml.find("NetworkInterface"), std::string::npos) << xml;
  EXPECT_EQ(xml.find("AllowMulticast"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<Security><Authentication/></Security></Domain>"), std::string::npos) << xml;
  config.interface = "192.168.1.20";
  EXPECT_NE(domain_config_xml(config).find("<NetworkInterface address=\"192.168.1.20\"/>"), std::string::npos);
}

TEST(DomainConfig, RejectsWhatCannotBeConfigured) {
  ParticipantConfig config;
  config.domain_id = 233;
  EXPECT_THROW(domain_config_xml(config), ConfigError);
  config.domain_id = 0;
  config.interface = "eth0\"/><x";
  EXPECT_THROW(domain_config_xml(config), ConfigError);
  config.interface = "auto";
  config.max_processes = 0;
  EXPECT_THROW(domain_config_xml(config), ConfigError);
  config.max_processes = 32;
  config.lease = std::chrono::milliseconds(0);
  EXPECT_THROW(domain_config_xml(config), ConfigError);
}

TEST(Participant, SharesADomainOnlyWithTheSameConfiguration) {
  const ParticipantConfig config = loopback_config();
  Participant a(config);
  Participant b(config);
  ParticipantConfig other = config;
  other.max_processes = 16;
  EXPECT_THROW(Participant c(other), ConfigError);
}

TEST(Participant, AnUnknownInterfaceIsAConfigError) {
  ParticipantConfig config = loopback_config();
  config.interface = "no_such_interface0";
  EXPECT_THROW(Participant p(config), ConfigError);
}

TEST(Participant, TheSecurityFragmentReachesCyclone) {
  ParticipantConfig config = loopback_config();
  config.security_xml =
      "<Security><Authentication><IdentityCertificate>file:/nonexistent/id.pem</IdentityCertificate>"
      "<IdentityCA>file:/nonexistent/ca.pem</IdentityCA><PrivateKey>file:/nonexistent/key.pem</PrivateKey>"
      "</Authentication><AccessControl><Governance>file:/nonexistent/gov.p7s</Governance>"
      "<PermissionsCA>file:/nonexistent/ca.pem</PermissionsCA><Permissions>file:/nonexistent/perm.p7s</Permissions>"
      "</AccessControl><Cryptographic/></Security>";
  EXPECT_THROW(Participant p(config), ConfigError);  // Cyclone tried to load the files
  Participant plain(loopback_config());               // and the domain was released
}

TEST(Dds, CycloneErrorsCarryTheCallAndTheReason) {
  Participant p(loopback_config());
  try {
    Topic<SwarmPacket> bad(p, "");
    FAIL() << "an empty topic name was accepted";
  } catch (const DdsError& e) {
    EXPECT_NE(std::string(e.what()).find("dds_create_topic"), std::string::npos) << e.what();
    EXPECT_LT(e.code(), 0);
  }
}

TEST(Dds, PacketsGoFromOneParticipantToAnotherInOrder) {
  Participant sender(loopback_config());
  Participant receiver(loopback_config());
  const std::string name = "dsswarm" + test_namespace();
  Topic<SwarmPacket> tx_topic(sender, name);
  Topic<SwarmPacket> rx_topic(receiver, name);
  Writer<SwarmPacket> writer(tx_topic, swarm_reliable());
  Reader<SwarmPacket> reader(rx_topic, swarm_reliable());
  ASSERT_TRUE(writer.wait_for_readers(1, kMatchTimeout));
  ASSERT_TRUE(reader.wait_for_writers(1, kMatchTimeout));
  EXPECT_EQ(writer.matched(), 1);

  const std::vector<std::vector<std::uint8_t>> sent = {bytes({1, 2, 3}), {}, bytes({255})};
  for (const auto& payload : sent) writer.write(packet_view(payload));
  EXPECT_EQ(take_packets(reader, sent.size(), 5s), sent);
}

TEST(Dds, PartitionsKeepSwarmsApart) {
  Participant sender(loopback_config());
  Participant receiver(loopback_config());
  const std::string name = "dsswarm" + test_namespace();
  Topic<SwarmPacket> tx_topic(sender, name);
  Topic<SwarmPacket> rx_topic(receiver, name);
  Writer<SwarmPacket> writer_a(tx_topic, swarm_reliable(), "swarm_a");
  Writer<SwarmPacket> writer_b(tx_topic, swarm_reliable(), "swarm_b");
  Reader<SwarmPacket> reader_b(rx_topic, swarm_reliable(), "swarm_b");
  ASSERT_TRUE(writer_b.wait_for_readers(1, kMatchTimeout));
  std::this_thread::sleep_for(200ms);  // time enough for a wrong match to show
  EXPECT_EQ(writer_a.matched(), 0);
  writer_a.write(packet_view(bytes({0xa})));
  writer_b.write(packet_view(bytes({0xb})));
  EXPECT_EQ(take_packets(reader_b, 2, 500ms), std::vector<std::vector<std::uint8_t>>{bytes({0xb})});
}

TEST(Qos, SwarmPacketsThrottleTheWriterOfAStalledReaderInsteadOfPilingUp) {
  Participant sender(loopback_config());
  Participant receiver(loopback_config());
  const std::string name = "dsswarm" + test_namespace();
  Topic<SwarmPacket> tx_topic(sender, name);
  Topic<SwarmPacket> rx_topic(receiver, name);
  Writer<SwarmPacket> writer(tx_topic, swarm_reliable(4, 150ms));
  Reader<SwarmPacket> reader(rx_topic, swarm_reliable(4, 150ms));
  ASSERT_TRUE(writer.wait_for_readers(1, kMatchTimeout));
  const auto payload = bytes({1, 2, 3, 4});
  int accepted = 0;
  const auto t0 = std::chrono::steady_clock::now();
  while (accepted < 100 && writer.try_write(packet_view(payload))) ++accepted;
  EXPECT_GE(accepted, 4);
  EXPECT_LT(accepted, 100) << "nothing bounds the queue";
  EXPECT_GE(std::chrono::steady_clock::now() - t0, 140ms) << "the last write blocked for max_blocking_time";
  EXPECT_EQ(take_packets(reader, 100, 300ms).size(), static_cast<std::size_t>(accepted));
  EXPECT_TRUE(writer.try_write(packet_view(payload))) << "room again once the reader took its packets";
}

// What Nav2 and rviz2 see of our presets: matched (or not) endpoint counts.
struct MatchCase {
  const char* what;
  Qos writer;
  Qos reader;
  bool matches;
};

TEST(Qos, PresetsMatchAsRosToolsExpect) {
  Participant p(loopback_config());
  Participant q(loopback_config());
  const std::vector<MatchCase> cases = {
      {"transient-local /map writer, Nav2's transient-local reader", ros_transient_local(1), ros_transient_local(1),
       true},
      {"transient-local /map writer, rviz2's volatile reader", ros_transient_local(1), ros_default(5), true},
      {"volatile writer, Nav2's transient-local reader", ros_default(1), ros_transient_local(1), false},
      {"reliable writer, sensor-data reader", ros_default(10), ros_sensor_data(), true},
      {"sensor-data writer, reliable reader", ros_sensor_data(), ros_default(10), false},
      {"/tf writer, tf listener", ros_tf(), ros_tf(), true},
      {"/tf_static broadcaster, static listener", ros_tf_static(1), ros_tf_static(100), true},
  };
  int index = 0;
  for (const auto& c : cases) {
    const std::string name = "rt" + test_namespace() + "/qos" + std::to_string(index++);
    Topic<ros::OccupancyGrid> wt(p, name);
    Topic<ros::OccupancyGrid> rt(q, name);
    Writer<ros::OccupancyGrid> writer(wt, c.writer);
    Reader<ros::OccupancyGrid> reader(rt, c.reader);
    if (c.matches) {
      EXPECT_TRUE(writer.wait_for_readers(1, kMatchTimeout)) << c.what;
    } else {
      // A QoS mismatch is reported as an incompatible QoS; wait for the report.
      const auto deadline = std::chrono::steady_clock::now() + kMatchTimeout;
      dds_offered_incompatible_qos_status_t status{};
      while (status.total_count == 0 && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(5ms);
        dds_get_offered_incompatible_qos_status(writer.handle(), &status);
      }
      EXPECT_GT(status.total_count, 0u) << c.what;
      EXPECT_EQ(writer.matched(), 0) << c.what;
    }
  }
}

// ROS 2 (Iron and later) reads "typehash=RIHS01_<hash>;" from endpoint USER_DATA.
TEST(Qos, RosEndpointsAdvertiseTheirTypeHash) {
  Participant p(loopback_config());
  Topic<ros::LaserScan> topic(p, "rt" + test_namespace() + "/scan");
  Writer<ros::LaserScan> writer(topic, ros_sensor_data());
  const dds_entity_t builtin = dds_create_reader(p.handle(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr);
  ASSERT_GT(builtin, 0);
  const std::string expected = "typehash=RIHS01_64c191398013af96509d518dac71d5164f9382553fce5c1f8cca5be7924bd828;";
  std::string found;
  const auto deadline = std::chrono::steady_clock::now() + kMatchTimeout;
  while (found.empty() && std::chrono::steady_clock::now() < deadline) {
    void* samples[8] = {};
    dds_sample_info_t infos[8];
    const int n = dds_take(builtin, samples, infos, 8, 8);
    for (int i = 0; i < n; ++i) {
      const auto* ep = static_cast<const dds_builtintopic_endpoint_t*>(samples[i]);
      void* data = nullptr;
      size_t size = 0;
      if (infos[i].valid_data && std::string(ep->topic_name) == topic.name() &&
          dds_qget_userdata(ep->qos, &data, &size)) {
        found.assign(static_cast<const char*>(data), size);
        dds_free(data);
      }
    }
    if (n > 0) dds_return_loan(builtin, samples, n);
    std::this_thread::sleep_for(5ms);
  }
  dds_delete(builtin);
  EXPECT_EQ(found, expected);
}

}  // namespace
}  // namespace dsswarm::net
