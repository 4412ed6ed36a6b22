#pragma once
// What the handshake watchdog needs from Cyclone DDS (C API): the remote
// participants discovery shows alive, and those with at least one endpoint
// matched to ours (which, on a secured domain, happens only after their
// security handshake with us succeeded).
#include <dds/dds.h>

#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "net/security/handshake_watchdog.hpp"

namespace dsswarm::security {

// A remote participant's GUID as 32 hex digits.
std::string guid_text(const dds_guid_t& guid);

class DiscoveryProbe {
 public:
  // Watches `participant`'s discovery; `writers` and `readers` are ours (the
  // swarm topics). `counts(entity_name)` selects which remote participants
  // matter (by their ENTITY_NAME QoS, "" if none); default: all of them.
  DiscoveryProbe(dds_entity_t participant, std::vector<dds_entity_t> writers, std::vector<dds_entity_t> readers,
                 std::function<bool(const std::string&)> counts = {});
  ~DiscoveryProbe();
  DiscoveryProbe(const DiscoveryProbe&) = delete;
  DiscoveryProbe& operator=(const DiscoveryProbe&) = delete;

  bool ok() const { return reader_ > 0; }

  // Reads discovery news, then fills the two sets (GUID text).
  void poll(std::set<std::string>& alive, std::set<std::string>& matched);

 private:
  void read_participants();
  void add_matched_writers_of(dds_entity_t reader, std::set<std::string>& matched) const;
  void add_matched_readers_of(dds_entity_t writer, std::set<std::string>& matched) const;

  dds_entity_t reader_ = 0;
  std::string own_guid_;
  std::vector<dds_entity_t> writers_, readers_;
  std::function<bool(const std::string&)> counts_;
  std::map<dds_instance_handle_t, std::string> alive_;  // instance -> GUID text
};

// The recipe in one call: poll `probe`, ask `watchdog`; true when the caller
// must recreate its participant (with every endpoint and a new probe) and
// then call watchdog.recreated().
bool handshake_stuck(DiscoveryProbe& probe, HandshakeWatchdog& watchdog,
                     HandshakeWatchdog::Clock::time_point now = HandshakeWatchdog::Clock::now());

}  // namespace dsswarm::security
