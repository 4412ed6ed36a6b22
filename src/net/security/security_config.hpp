#pragma once
// What a secured participant is configured with: the Cyclone DDS
// `<Security>` element for one robot of a keys directory. The DDS wrapper
// splices this string into its `<CycloneDDS><Domain>` configuration.
//
// A robot needs only these files from the keys directory (never ca_key.pem):
// swarm.json, ca.pem, governance.p7s, crl.pem and robots/NAME/.
#include <filesystem>
#include <string>

namespace dsswarm::security {

struct SecurityFiles {
  std::filesystem::path identity_ca;           // ca.pem
  std::filesystem::path identity_certificate;  // robots/NAME/cert.pem
  std::filesystem::path private_key;           // robots/NAME/key.pem
  std::filesystem::path crl;                   // crl.pem
  std::filesystem::path permissions_ca;        // ca.pem (one CA plays both roles)
  std::filesystem::path governance;            // governance.p7s
  std::filesystem::path permissions;           // robots/NAME/permissions.p7s
};

// Absolute paths of robot `name`'s files. Throws ConfigError for a bad name,
// InputError when the directory is not a keys directory, the robot is
// unknown or revoked, or one of its files is missing.
SecurityFiles robot_security_files(const std::filesystem::path& keys_dir, const std::string& name);

// "<Security><Authentication>...</Authentication><AccessControl>...
// </AccessControl><Cryptographic/></Security>" with file: URIs; the
// built-in plugins (shipped with Cyclone) are used.
std::string security_config_xml(const SecurityFiles& files);

// Both of the above.
std::string security_config_xml(const std::filesystem::path& keys_dir, const std::string& name);

// The DDS domain id the keys directory's documents are signed for.
int secured_domain_id(const std::filesystem::path& keys_dir);

}  // namespace dsswarm::security
