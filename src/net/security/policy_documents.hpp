#pragma once
// The two OMG DDS Security policy documents, as XML text (unsigned; the
// keystore signs them): the swarm's governance (what is protected, and how)
// and a robot's permissions (what that certificate may do).
#include <string>
#include <vector>

#include "net/security/pki.hpp"

namespace dsswarm::security {

enum class ProtectionKind { kNone, kSign, kEncrypt };

// "NONE", "SIGN", "ENCRYPT" (the governance spelling).
const char* protection_name(ProtectionKind kind);

// Topic names the swarm owns; the governance protects them and the
// permissions grant them. Cyclone matches these fnmatch-style ('*' also
// matches '/'), so every swarm topic name must start with "dsswarm".
inline const std::vector<std::string>& swarm_topic_expressions() {
  static const std::vector<std::string> kTopics{"dsswarm*"};
  return kTopics;
}

struct GovernanceOptions {
  int domain_id = 1;
  // Whole-message protection of discovery, liveliness and every RTPS message.
  ProtectionKind discovery = ProtectionKind::kEncrypt;
  ProtectionKind liveliness = ProtectionKind::kEncrypt;
  ProtectionKind rtps = ProtectionKind::kEncrypt;
  // Per-sample protection of the swarm topics' payload and submessages.
  ProtectionKind swarm_data = ProtectionKind::kEncrypt;
  ProtectionKind swarm_metadata = ProtectionKind::kEncrypt;
};

// Governance for one domain: authenticated participants only, join access
// control, the swarm topics protected and access-controlled; every other
// topic on the secured domain access-controlled too (and no one is granted
// one), so nothing unplanned leaks onto it.
std::string governance_xml(const GovernanceOptions& options);

struct PermissionsOptions {
  std::string grant_name;
  std::string subject;  // "CN=robot1,O=dsswarm-1", compared field by field by Cyclone
  int domain_id = 1;
  Validity validity;
  std::vector<std::string> topics = swarm_topic_expressions();  // publish and subscribe
};

// One grant for `subject`: publish and subscribe on `topics` in the domain
// during `validity`, everything else denied.
std::string permissions_xml(const PermissionsOptions& options);

// `s` with & < > " as XML entities.
std::string xml_escape(const std::string& s);

// "2025-01-31T12:00:00Z": the XML date form the permissions use (UTC, whole seconds).
std::string utc_text(TimePoint t);
// Inverse of utc_text(); throws InputError naming `what` on anything else.
TimePoint parse_utc_text(const std::string& text, const std::string& what);

}  // namespace dsswarm::security
