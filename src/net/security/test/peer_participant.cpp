#include "net/security/test/peer_participant.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace dsswarm::sectest {

double ms_since_start() {
  static const auto start = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::string loopback_config(int domain, const std::string& security) {
  return "<CycloneDDS><Domain Id=\"" + std::to_string(domain) +
         "\"><General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
         "<AllowMulticast>false</AllowMulticast></General>"
         "<Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>30</MaxAutoParticipantIndex>"
         "<Peers><Peer Address=\"127.0.0.1\"/></Peers></Discovery>" +
         security + "</Domain></CycloneDDS>";
}

PeerParticipant::PeerParticipant(int domain, const std::string& security, std::string topic, bool keep_all,
                                 double recover_s)
    : topic_name_(std::move(topic)), keep_all_(keep_all) {
  if (recover_s > 0) {
    security::HandshakeWatchdogConfig c;
    c.stuck_after_s = recover_s;
    c.first_backoff_s = 2 * recover_s;
    c.max_backoff_s = std::max(c.max_backoff_s, c.first_backoff_s);
    watchdog_.emplace(c);
  }
  domain_id_ = static_cast<dds_domainid_t>(domain);
  domain_ = dds_create_domain(domain_id_, loopback_config(domain, security).c_str());
  if (domain_ < 0) {
    create_result_ = domain_;
    return;
  }
  create();
}

PeerParticipant::~PeerParticipant() {
  destroy();
  if (domain_ > 0) dds_delete(domain_);
}

bool PeerParticipant::create() {
  participant_ = dds_create_participant(domain_id_, nullptr, nullptr);
  if (participant_ < 0) {
    create_result_ = participant_;
    participant_ = 0;
    return false;
  }
  topic_ = dds_create_topic(participant_, &dsswarm_sectest_Blob_desc, topic_name_.c_str(), nullptr, nullptr);
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(10));
  // KEEP_LAST by default: a reliable KEEP_ALL writer blocks in dds_write
  // while a dead peer's reader stays matched (until its lease expires).
  if (keep_all_) {
    dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
  } else {
    dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 8);
  }
  reader_ = dds_create_reader(participant_, topic_, qos, nullptr);
  writer_ = dds_create_writer(participant_, topic_, qos, nullptr);
  dds_delete_qos(qos);
  create_result_ = topic_ < 0 ? topic_ : reader_ < 0 ? reader_ : writer_ < 0 ? writer_ : 0;
  if (ok() && watchdog_) {
    probe_ = std::make_unique<security::DiscoveryProbe>(participant_, std::vector<dds_entity_t>{writer_},
                                                        std::vector<dds_entity_t>{reader_});
  }
  return ok();
}

void PeerParticipant::destroy() {
  probe_.reset();
  if (participant_ > 0) dds_delete(participant_);
  participant_ = topic_ = reader_ = writer_ = 0;
  last_matched_ = -1;
}

bool PeerParticipant::recreate() {
  destroy();
  const bool ok_now = create();
  std::printf("recreated %.1f\n", ms_since_start());
  return ok_now;
}

void PeerParticipant::write(const std::string& origin, unsigned long long incarnation, uint32_t seq,
                            std::vector<unsigned char>& payload) {
  dsswarm_sectest_Blob s{};
  s.origin = const_cast<char*>(origin.c_str());
  s.incarnation = incarnation;
  s.seq = seq;
  s.sent_ns = dds_time();
  s.payload._buffer = payload.data();
  s.payload._length = s.payload._maximum = static_cast<uint32_t>(payload.size());
  s.payload._release = false;
  dds_write(writer_, &s);
}

void PeerParticipant::take(const std::function<void(const dsswarm_sectest_Blob&)>& on_sample) {
  constexpr int kBatch = 16;
  void* samples[kBatch] = {};
  dds_sample_info_t infos[kBatch];
  for (;;) {
    const dds_return_t n = dds_take(reader_, samples, infos, kBatch, kBatch);
    if (n <= 0) return;
    for (int i = 0; i < n; ++i)
      if (infos[i].valid_data) on_sample(*static_cast<const dsswarm_sectest_Blob*>(samples[i]));
    dds_return_loan(reader_, samples, n);
  }
}

void PeerParticipant::report_matches() {
  dds_publication_matched_status_t st;
  if (dds_get_publication_matched_status(writer_, &st) != DDS_RETCODE_OK) return;
  if (static_cast<int32_t>(st.current_count) != last_matched_) {
    last_matched_ = static_cast<int32_t>(st.current_count);
    std::printf("matched %d %.1f\n", st.current_count, ms_since_start());
  }
  if (watchdog_ && probe_ && security::handshake_stuck(*probe_, *watchdog_)) {
    for (const auto& p : watchdog_->stuck(security::HandshakeWatchdog::Clock::now())) std::printf("stuck %s\n", p.c_str());
    recreate();
    watchdog_->recreated(security::HandshakeWatchdog::Clock::now());
  }
}

}  // namespace dsswarm::sectest
