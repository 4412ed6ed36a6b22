#pragma once
// The swarm's bytes over DDS (protocol::SwarmLink): every robot reads its
// own inbox topic, dsswarm_inbox_<name>, and the broadcast topic
// dsswarm_heartbeat, all in the swarm's partition ("dsswarm.<swarm id>"), so
// swarms sharing a network never see each other. Messages to one robot go to
// its inbox only: robots that never meet never exchange a byte beyond
// heartbeats. Inboxes are reliable with bounded history (a slow robot slows
// its senders, it does not make them queue without bound); heartbeats are
// best effort.
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "net/dds.hpp"
#include "net/swarm_types.hpp"
#include "protocol/link.hpp"

namespace dsswarm::net {

std::string swarm_partition(const std::string& swarm_id);

struct SwarmLinkConfig {
  // The swarm's partition (swarm_partition(id)). A secured swarm is its own
  // domain that only its members can join: it uses the default partition "",
  // the one the permissions grant.
  std::string partition = swarm_partition("default");
  std::string name;  // this robot (or tool, e.g. "proximity"): its inbox
  bool listen = true;  // false: a tool that only sends (no inbox, no heartbeats read)
  // A message to a robot whose inbox has no reader yet waits this long for
  // discovery (DDS drops volatile samples written before a reader matched).
  std::chrono::milliseconds match_wait{2000};
  std::int32_t inbox_depth = 256;   // messages held per inbox writer
  std::chrono::milliseconds max_blocking{500};
  std::size_t max_writers = 64;     // inboxes written to; the least used is closed beyond
};

std::string inbox_topic(const std::string& robot);
inline constexpr const char* kHeartbeatTopic = "dsswarm_heartbeat";

class DdsSwarmLink : public protocol::SwarmLink {
 public:
  // Throws ConfigError for an invalid name or swarm id.
  DdsSwarmLink(Participant& participant, const SwarmLinkConfig& config);
  ~DdsSwarmLink() override;

  bool send(const std::string& recipient, std::span<const std::uint8_t> bytes) override;
  bool reachable(const std::string& recipient) override;  // an inbox reader is matched
  std::vector<std::vector<std::uint8_t>> receive(std::chrono::milliseconds timeout) override;
  void wake() override;

  // The endpoints every peer of the swarm matches (the broadcast topic's, and
  // our inbox), for watching whether peers' security handshakes succeeded.
  std::vector<dds_entity_t> writers() const { return {heartbeat_writer_.handle()}; }
  std::vector<dds_entity_t> readers() const;

 private:
  struct InboxWriter;
  InboxWriter& writer_for(const std::string& recipient);

  Participant& participant_;
  SwarmLinkConfig config_;
  std::string partition_;
  Topic<SwarmPacket> heartbeat_topic_;
  Writer<SwarmPacket> heartbeat_writer_;
  std::unique_ptr<Topic<SwarmPacket>> inbox_topic_;
  std::unique_ptr<Reader<SwarmPacket>> inbox_reader_;
  std::unique_ptr<Reader<SwarmPacket>> heartbeat_reader_;
  Entity waitset_, guard_;
  std::mutex writers_mutex_;
  std::map<std::string, std::unique_ptr<InboxWriter>> writers_;
  std::uint64_t uses_ = 0;
};

}  // namespace dsswarm::net
