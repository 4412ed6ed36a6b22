#include "net/swarm_link.hpp"

#include <algorithm>

#include "common/agent_name.hpp"
#include "common/errors.hpp"

namespace dsswarm::net {
namespace {

Qos heartbeat_qos() {
  Qos q;
  q.best_effort().volatile_durability().keep_last(8);
  return q;
}

}  // namespace

std::string swarm_partition(const std::string& swarm_id) {
  if (!is_valid_agent_name(swarm_id))
    throw ConfigError("'" + swarm_id + "' is not a valid swarm id (letters, digits, '_', '-', '.')");
  return "dsswarm." + swarm_id;
}
std::string inbox_topic(const std::string& robot) { return "dsswarm_inbox_" + robot; }

struct DdsSwarmLink::InboxWriter {
  InboxWriter(Participant& p, const std::string& robot, const Qos& qos, const std::string& partition)
      : topic(p, inbox_topic(robot)), writer(topic, qos, partition) {}
  Topic<SwarmPacket> topic;
  Writer<SwarmPacket> writer;
  std::uint64_t last_use = 0;
};

DdsSwarmLink::DdsSwarmLink(Participant& participant, const SwarmLinkConfig& config)
    : participant_(participant),
      config_(config),
      partition_(config.partition),
      heartbeat_topic_(participant, kHeartbeatTopic),
      heartbeat_writer_(heartbeat_topic_, heartbeat_qos(), partition_) {
  if (!is_valid_agent_name(config_.name))
    throw ConfigError("'" + config_.name + "' is not a valid robot name (letters, digits, '_', '-', '.')");
  waitset_ = Entity(check(dds_create_waitset(participant.handle()), "dds_create_waitset"));
  guard_ = Entity(check(dds_create_guardcondition(participant.handle()), "dds_create_guardcondition"));
  check(dds_waitset_attach(waitset_.get(), guard_.get(), guard_.get()), "dds_waitset_attach");
  if (!config_.listen) return;
  inbox_topic_ = std::make_unique<Topic<SwarmPacket>>(participant, inbox_topic(config_.name));
  inbox_reader_ = std::make_unique<Reader<SwarmPacket>>(
      *inbox_topic_, swarm_reliable(config_.inbox_depth, config_.max_blocking), partition_);
  heartbeat_reader_ = std::make_unique<Reader<SwarmPacket>>(heartbeat_topic_, heartbeat_qos(), partition_);
  for (const ReaderBase* r : {static_cast<const ReaderBase*>(inbox_reader_.get()),
                              static_cast<const ReaderBase*>(heartbeat_reader_.get())}) {
    const dds_entity_t cond = check(dds_create_readcondition(r->handle(), DDS_ANY_STATE), "dds_create_readcondition");
    check(dds_waitset_attach(waitset_.get(), cond, cond), "dds_waitset_attach");
  }
}

DdsSwarmLink::~DdsSwarmLink() = default;

DdsSwarmLink::InboxWriter& DdsSwarmLink::writer_for(const std::string& recipient) {
  auto it = writers_.find(recipient);
  if (it == writers_.end()) {
    if (writers_.size() >= config_.max_writers) {
      auto oldest = std::min_element(writers_.begin(), writers_.end(),
                                     [](const auto& a, const auto& b) { return a.second->last_use < b.second->last_use; });
      writers_.erase(oldest);
    }
    it = writers_
             .emplace(recipient, std::make_unique<InboxWriter>(participant_, recipient,
                                                               swarm_reliable(config_.inbox_depth, config_.max_blocking),
                                                               partition_))
             .first;
  }
  it->second->last_use = ++uses_;
  return *it->second;
}

bool DdsSwarmLink::send(const std::string& recipient, std::span<const std::uint8_t> bytes) {
  const SwarmPacket packet = packet_view(bytes);
  if (recipient.empty()) return heartbeat_writer_.try_write(packet);
  if (!is_valid_agent_name(recipient)) return false;
  std::lock_guard lock(writers_mutex_);
  InboxWriter& w = writer_for(recipient);
  if (w.writer.matched() == 0 && !w.writer.wait_for_readers(1, config_.match_wait)) return false;
  return w.writer.try_write(packet);
}

bool DdsSwarmLink::reachable(const std::string& recipient) {
  if (recipient.empty() || !is_valid_agent_name(recipient)) return false;
  std::lock_guard lock(writers_mutex_);
  const auto it = writers_.find(recipient);
  return it != writers_.end() && it->second->writer.matched() > 0;
}

std::vector<std::vector<std::uint8_t>> DdsSwarmLink::receive(std::chrono::milliseconds timeout) {
  std::vector<std::vector<std::uint8_t>> out;
  auto take_all = [&] {
    for (const Reader<SwarmPacket>* r : {inbox_reader_.get(), heartbeat_reader_.get()})
      if (r)
        r->take(1024, [&](const SwarmPacket& p, const dds_sample_info_t&) {
          const auto bytes = packet_payload(p);
          out.emplace_back(bytes.begin(), bytes.end());
        });
  };
  take_all();
  if (!out.empty()) return out;
  check(dds_waitset_wait(waitset_.get(), nullptr, 0, to_duration(timeout)), "dds_waitset_wait");
  bool triggered = false;
  dds_read_guardcondition(guard_.get(), &triggered);
  if (triggered) dds_set_guardcondition(guard_.get(), false);
  take_all();
  return out;
}

void DdsSwarmLink::wake() { dds_set_guardcondition(guard_.get(), true); }

std::vector<dds_entity_t> DdsSwarmLink::readers() const {
  std::vector<dds_entity_t> out;
  if (inbox_reader_) out.push_back(inbox_reader_->handle());
  if (heartbeat_reader_) out.push_back(heartbeat_reader_->handle());
  return out;
}

}  // namespace dsswarm::net
