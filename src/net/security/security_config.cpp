#include "net/security/security_config.hpp"

#include <fmt/format.h>

#include "common/errors.hpp"
#include "net/security/keys_index.hpp"
#include "net/security/keystore.hpp"
#include "net/security/policy_documents.hpp"

namespace dsswarm::security {

namespace fs = std::filesystem;

namespace {

std::string file_uri(const fs::path& p) { return xml_escape("file:" + p.string()); }

}  // namespace

SecurityFiles robot_security_files(const fs::path& keys_dir, const std::string& name) {
  validate_robot_name(name);
  const fs::path dir = fs::absolute(keys_dir).lexically_normal();
  const SwarmKeys keys = load_swarm_keys(dir);
  const RobotRecord* r = keys.find(name);
  if (r == nullptr) throw InputError("no robot " + name + " in " + dir.string() + " (add it with `dsswarm keys add`)");
  if (r->revoked_at) throw InputError("robot " + name + " was revoked on " + utc_text(*r->revoked_at));
  const KeysLayout layout{dir};
  const RobotFiles robot = layout.robot(name);
  const SecurityFiles files{layout.ca_certificate(), robot.certificate(), robot.key(),   layout.crl(),
                            layout.ca_certificate(), layout.governance(),  robot.permissions()};
  for (const fs::path* p : {&files.identity_ca, &files.identity_certificate, &files.private_key, &files.crl,
                            &files.governance, &files.permissions}) {
    if (!fs::is_regular_file(*p)) throw InputError("robot " + name + ": " + p->string() + " is missing");
  }
  return files;
}

std::string security_config_xml(const SecurityFiles& f) {
  return fmt::format(
      "<Security>"
      "<Authentication>"
      "<IdentityCA>{}</IdentityCA>"
      "<IdentityCertificate>{}</IdentityCertificate>"
      "<PrivateKey>{}</PrivateKey>"
      "<CRL>{}</CRL>"
      "</Authentication>"
      "<AccessControl>"
      "<PermissionsCA>{}</PermissionsCA>"
      "<Governance>{}</Governance>"
      "<Permissions>{}</Permissions>"
      "</AccessControl>"
      "<Cryptographic/>"
      "</Security>",
      file_uri(f.identity_ca), file_uri(f.identity_certificate), file_uri(f.private_key), file_uri(f.crl),
      file_uri(f.permissions_ca), file_uri(f.governance), file_uri(f.permissions));
}

std::string security_config_xml(const fs::path& keys_dir, const std::string& name) {
  return security_config_xml(robot_security_files(keys_dir, name));
}

int secured_domain_id(const fs::path& keys_dir) { return load_swarm_keys(keys_dir).domain_id; }

}  // namespace dsswarm::security
