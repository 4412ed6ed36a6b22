#include "apps/keys_command.hpp"

#include <fmt/core.h>

#include <memory>
#include <optional>
#include <string>

#include "common/errors.hpp"
#include "net/security/keystore.hpp"

namespace dsswarm {

namespace {

using namespace dsswarm::security;

struct KeysArgs {
  std::string dir;
  std::string name;
  int swarm = 1;
  std::optional<int> days;
  std::string protection = "encrypt";
};

GovernanceOptions governance_for(const std::string& protection) {
  GovernanceOptions g;
  if (protection == "sign") {
    g.discovery = g.liveliness = g.rtps = g.swarm_metadata = ProtectionKind::kSign;
  } else if (protection != "encrypt") {
    throw ConfigError("--protection " + protection + ": use encrypt or sign");
  }
  return g;
}

void init(const KeysArgs& a) {
  KeysInitOptions o;
  o.swarm_id = a.swarm;
  o.days = a.days.value_or(o.days);
  o.governance = governance_for(a.protection);
  const SwarmKeys keys = init_keys(a.dir, o);
  const KeysLayout layout{a.dir};
  fmt::print("swarm {} keys in {}: CA {} (valid {} days), governance for DDS domain {} ({} discovery and messages, "
             "swarm topics {} encrypted), empty CRL\n",
             keys.swarm_id, a.dir, layout.ca_certificate().string(), o.days, keys.domain_id, a.protection,
             swarm_topic_expressions().front());
  fmt::print("keep {} off the robots; add robots with `dsswarm keys add {} NAME`\n", layout.ca_key().string(), a.dir);
}

void add(const KeysArgs& a) {
  RobotKeyOptions o;
  o.days = a.days;
  const RobotRecord r = add_robot(a.dir, a.name, o);
  const KeysLayout layout{a.dir};
  fmt::print("robot {}: certificate serial {} for {}, valid {} to {}, files in {}\n", r.name, r.serial, r.subject,
             utc_text(r.validity.not_before), utc_text(r.validity.not_after), layout.robot(r.name).dir.string());
  fmt::print("copy to the robot: swarm.json ca.pem governance.p7s crl.pem robots/{}/ (never ca_key.pem)\n", r.name);
}

void revoke(const KeysArgs& a) {
  const RobotRecord r = revoke_robot(a.dir, a.name);
  fmt::print("robot {} (serial {}) revoked on {}; {} updated: copy it to every robot and restart their agents\n",
             r.name, r.serial, utc_text(*r.revoked_at), KeysLayout{a.dir}.crl().string());
}

CLI::App* keys_subcommand(CLI::App& keys, const char* name, const char* help, std::shared_ptr<KeysArgs> args) {
  CLI::App* cmd = keys.add_subcommand(name, help);
  cmd->add_option("dir", args->dir, "Keys directory")->required();
  return cmd;
}

}  // namespace

void add_keys_command(CLI::App& app) {
  auto args = std::make_shared<KeysArgs>();
  CLI::App* keys = app.add_subcommand("keys", "DDS Security for the swarm: CA, robot certificates, revocation");
  keys->require_subcommand(1);

  CLI::App* init_cmd = keys_subcommand(*keys, "init",
                                       "Make a swarm CA, the signed governance and an empty CRL in a new directory",
                                       args);
  init_cmd->add_option("--swarm", args->swarm, "Swarm id = DDS domain id of the secured swarm (0-232)")
      ->capture_default_str();
  init_cmd->add_option("--days", args->days, "Validity of the CA and everything it signs (default 3650)");
  init_cmd->add_option("--protection", args->protection,
                       "Discovery, liveliness, whole-message and submessage protection: encrypt or sign (swarm data "
                       "is always encrypted; sign saves ~8% CPU, see docs/security.md)")
      ->capture_default_str();
  init_cmd->callback([args] { init(*args); });

  CLI::App* add_cmd = keys_subcommand(
      *keys, "add", "Issue a robot its key, certificate and signed permissions under DIR/robots/NAME/", args);
  add_cmd->add_option("name", args->name, "Robot name (letters, digits, '_', '-')")->required();
  add_cmd->add_option("--days", args->days, "Validity (default: until the CA expires)");
  add_cmd->callback([args] { add(*args); });

  CLI::App* revoke_cmd =
      keys_subcommand(*keys, "revoke", "Revoke a robot's certificate: rewrites DIR/crl.pem (copy it to every robot)",
                      args);
  revoke_cmd->add_option("name", args->name, "Robot name")->required();
  revoke_cmd->callback([args] { revoke(*args); });
}

}  // namespace dsswarm
