#pragma once
// A swarm's keys directory: where each file lives, and swarm.json, the index
// of what the CA has issued (robots, serial numbers, revocations). The index
// is the single source of truth: the CRL is rebuilt from it on each revoke,
// and serial numbers are never reused.
//
//   DIR/swarm.json          the index (this file's SwarmKeys)
//   DIR/ca.pem              the swarm CA certificate (identity CA and permissions CA)
//   DIR/ca_key.pem          the CA private key, mode 0600: never copy it to a robot
//   DIR/governance.xml      the governance document (readable copy)
//   DIR/governance.p7s      the same, S/MIME-signed by the CA: what DDS reads
//   DIR/crl.pem             the CA's certificate revocation list
//   DIR/robots/NAME/cert.pem         the robot's certificate (CN=NAME,O=dsswarm-<swarm>)
//   DIR/robots/NAME/key.pem          its private key, mode 0600
//   DIR/robots/NAME/permissions.xml  its permissions (readable copy)
//   DIR/robots/NAME/permissions.p7s  the same, signed by the CA
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "net/security/policy_documents.hpp"

namespace dsswarm::security {

// One robot's files (DIR/robots/NAME/...).
struct RobotFiles {
  std::filesystem::path dir;

  std::filesystem::path certificate() const { return dir / "cert.pem"; }
  std::filesystem::path key() const { return dir / "key.pem"; }
  std::filesystem::path permissions_source() const { return dir / "permissions.xml"; }
  std::filesystem::path permissions() const { return dir / "permissions.p7s"; }
};

struct KeysLayout {
  std::filesystem::path dir;

  std::filesystem::path index() const { return dir / "swarm.json"; }
  std::filesystem::path ca_certificate() const { return dir / "ca.pem"; }
  std::filesystem::path ca_key() const { return dir / "ca_key.pem"; }
  std::filesystem::path governance_source() const { return dir / "governance.xml"; }
  std::filesystem::path governance() const { return dir / "governance.p7s"; }
  std::filesystem::path crl() const { return dir / "crl.pem"; }
  std::filesystem::path robots() const { return dir / "robots"; }
  RobotFiles robot(const std::string& name) const { return {robots() / name}; }
};

struct RobotRecord {
  std::string name;
  std::uint64_t serial = 0;
  std::string subject;  // as granted in the permissions: "CN=NAME,O=dsswarm-<swarm>"
  Validity validity;    // the certificate's
  std::optional<TimePoint> revoked_at;
};

struct SwarmKeys {
  int swarm_id = 1;
  int domain_id = 1;  // the DDS domain the governance and permissions are signed for
  std::uint64_t next_serial = 2;  // the CA is serial 1
  std::uint64_t crl_number = 1;   // of the CRL in crl.pem
  std::vector<RobotRecord> robots;

  const RobotRecord* find(const std::string& name) const;
  RobotRecord* find(const std::string& name);
};

// Reads DIR/swarm.json. InputError (naming the file and field) when DIR is
// missing, is not a keys directory, or the index is damaged.
SwarmKeys load_swarm_keys(const std::filesystem::path& dir);

// Writes DIR/swarm.json atomically.
void save_swarm_keys(const std::filesystem::path& dir, const SwarmKeys& keys);

}  // namespace dsswarm::security
