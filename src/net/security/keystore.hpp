#pragma once
// `dsswarm keys init|add|revoke` as library calls: make a swarm's CA and
// signed governance, issue a robot's key, certificate and signed permissions,
// revoke a robot (CRL). The directory layout is in keys_index.hpp.
//
// Errors: ConfigError for a bad argument (name, swarm id, days), InputError
// for the directory's state (missing, not a keys directory, robot already
// there or unknown, damaged files). Every file is written atomically; a
// command that fails leaves the directory as it was.
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "net/security/keys_index.hpp"

namespace dsswarm::security {

// Certificates, CRLs and permissions start this long before "now": a robot
// whose clock lags the machine that made its keys (no RTC, NTP not yet
// synced) still accepts them.
inline constexpr std::chrono::hours kClockSkewAllowance{24};

struct KeysInitOptions {
  int swarm_id = 1;  // also the DDS domain id of the secured swarm (0-232)
  int days = 3650;   // validity of the CA, hence of everything it signs
  GovernanceOptions governance;  // its domain_id is set to swarm_id
};

struct RobotKeyOptions {
  std::optional<int> days;  // default: until the CA expires
  // Explicit periods (tests: expired or not-yet-valid grants); override `days`.
  std::optional<Validity> certificate_validity;
  std::optional<Validity> permissions_validity;
};

// Creates `dir` (it must not exist, or be an empty directory; its parent must
// exist) holding a new CA, the signed governance and an empty CRL.
SwarmKeys init_keys(const std::filesystem::path& dir, const KeysInitOptions& options);

// Issues robot `name` a key, certificate and signed permissions under
// dir/robots/name/. A name already issued (even if revoked) is refused.
RobotRecord add_robot(const std::filesystem::path& dir, const std::string& name, const RobotKeyOptions& options = {});

// Revokes robot `name`'s certificate: records it in swarm.json and rewrites
// dir/crl.pem. Peers loading the new CRL refuse that robot.
RobotRecord revoke_robot(const std::filesystem::path& dir, const std::string& name);

// Throws ConfigError unless `name` is 1-63 of [A-Za-z0-9_-], starting with a
// letter or digit (it goes into file names, certificate subjects and XML).
void validate_robot_name(const std::string& name);

}  // namespace dsswarm::security
