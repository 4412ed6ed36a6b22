#pragma once
// The test peer's DDS entities (Cyclone C API): a domain configured for
// loopback with an optional <Security> fragment, one participant, and a
// reliable reader and writer of Blob on one topic. Test code only; the
// swarm's own DDS wrapper lives in src/net.
#include <dds/dds.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "net/security/discovery_probe.hpp"
#include "net/security/handshake_watchdog.hpp"
#include "security_test_types.h"

namespace dsswarm::sectest {

// Milliseconds since the first call (the peer calls it at start-up).
double ms_since_start();

// A Cyclone configuration for domain `domain` on the loopback interface,
// unicast discovery, with `security` (a <Security> element, or "") spliced in.
std::string loopback_config(int domain, const std::string& security);

class PeerParticipant {
 public:
  // keep_all: KEEP_ALL history (throughput runs), else KEEP_LAST 8.
  // recover_s > 0 enables the handshake watchdog with that stuck time.
  PeerParticipant(int domain, const std::string& security, std::string topic, bool keep_all, double recover_s);
  ~PeerParticipant();
  PeerParticipant(const PeerParticipant&) = delete;
  PeerParticipant& operator=(const PeerParticipant&) = delete;

  bool ok() const { return writer_ > 0; }
  dds_return_t create_result() const { return create_result_; }

  void write(const std::string& origin, unsigned long long incarnation, uint32_t seq,
             std::vector<unsigned char>& payload);
  void take(const std::function<void(const dsswarm_sectest_Blob&)>& on_sample);
  // Prints "matched <n> <ms>" when the writer's matched count changed, and
  // lets the watchdog recreate the participant ("recreated <ms>").
  void report_matches();
  // Deletes the participant (and its endpoints) and creates it again: new
  // GUID, fresh handshakes with every peer. Prints "recreated <ms>".
  bool recreate();
  // The writer's matched-reader count at the last report_matches().
  int32_t matched() const { return last_matched_; }

 private:
  bool create();
  void destroy();

  std::string topic_name_;
  dds_domainid_t domain_id_ = 0;
  bool keep_all_ = false;
  dds_entity_t domain_ = 0, participant_ = 0, topic_ = 0, reader_ = 0, writer_ = 0;
  dds_return_t create_result_ = 0;
  int32_t last_matched_ = -1;
  std::optional<security::HandshakeWatchdog> watchdog_;
  std::unique_ptr<security::DiscoveryProbe> probe_;
};

}  // namespace dsswarm::sectest
