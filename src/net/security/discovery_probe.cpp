#include "net/security/discovery_probe.hpp"

#include <fmt/format.h>

#include <utility>

namespace dsswarm::security {

namespace {

constexpr std::size_t kMaxMatched = 256;  // endpoints per entity looked at per poll
constexpr int kTakeBatch = 32;

std::string entity_name(const dds_qos_t* qos) {
  char* name = nullptr;
  if (qos == nullptr || !dds_qget_entity_name(qos, &name) || name == nullptr) return "";
  std::string out(name);
  dds_free(name);
  return out;
}

template <typename GetHandles, typename GetData>
void add_participants_of(dds_entity_t entity, std::set<std::string>& matched, GetHandles get_handles, GetData get_data) {
  dds_instance_handle_t handles[kMaxMatched];
  const dds_return_t n = get_handles(entity, handles, kMaxMatched);
  for (dds_return_t i = 0; i < n && i < static_cast<dds_return_t>(kMaxMatched); ++i) {
    if (dds_builtintopic_endpoint_t* ep = get_data(entity, handles[i])) {
      matched.insert(guid_text(ep->participant_key));
      dds_builtintopic_free_endpoint(ep);
    }
  }
}

}  // namespace

std::string guid_text(const dds_guid_t& guid) {
  std::string out;
  for (const uint8_t b : guid.v) out += fmt::format("{:02x}", b);
  return out;
}

DiscoveryProbe::DiscoveryProbe(dds_entity_t participant, std::vector<dds_entity_t> writers,
                               std::vector<dds_entity_t> readers, std::function<bool(const std::string&)> counts)
    : writers_(std::move(writers)), readers_(std::move(readers)), counts_(std::move(counts)) {
  dds_guid_t own;
  if (dds_get_guid(participant, &own) == DDS_RETCODE_OK) own_guid_ = guid_text(own);
  reader_ = dds_create_reader(participant, DDS_BUILTIN_TOPIC_DCPSPARTICIPANT, nullptr, nullptr);
}

DiscoveryProbe::~DiscoveryProbe() {
  if (reader_ > 0) dds_delete(reader_);
}

void DiscoveryProbe::read_participants() {
  void* samples[kTakeBatch] = {};
  dds_sample_info_t infos[kTakeBatch];
  dds_return_t n;
  while ((n = dds_take(reader_, samples, infos, kTakeBatch, kTakeBatch)) > 0) {
    for (dds_return_t i = 0; i < n; ++i) {
      const auto* p = static_cast<const dds_builtintopic_participant_t*>(samples[i]);
      if (infos[i].instance_state != DDS_IST_ALIVE) {
        alive_.erase(infos[i].instance_handle);
      } else if (infos[i].valid_data) {
        const std::string guid = guid_text(p->key);
        if (guid != own_guid_ && (!counts_ || counts_(entity_name(p->qos)))) alive_[infos[i].instance_handle] = guid;
      }
    }
    dds_return_loan(reader_, samples, n);
  }
}

void DiscoveryProbe::add_matched_readers_of(dds_entity_t writer, std::set<std::string>& matched) const {
  add_participants_of(writer, matched, dds_get_matched_subscriptions, dds_get_matched_subscription_data);
}

void DiscoveryProbe::add_matched_writers_of(dds_entity_t reader, std::set<std::string>& matched) const {
  add_participants_of(reader, matched, dds_get_matched_publications, dds_get_matched_publication_data);
}

void DiscoveryProbe::poll(std::set<std::string>& alive, std::set<std::string>& matched) {
  read_participants();
  alive.clear();
  matched.clear();
  for (const auto& [handle, guid] : alive_) alive.insert(guid);
  for (const dds_entity_t w : writers_) add_matched_readers_of(w, matched);
  for (const dds_entity_t r : readers_) add_matched_writers_of(r, matched);
}

bool handshake_stuck(DiscoveryProbe& probe, HandshakeWatchdog& watchdog, HandshakeWatchdog::Clock::time_point now) {
  std::set<std::string> alive, matched;
  probe.poll(alive, matched);
  return watchdog.update(alive, matched, now);
}

}  // namespace dsswarm::security
