#include "net/security/keystore.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <system_error>

#include <fmt/format.h>

#include "common/errors.hpp"
#include "io/atomic_file.hpp"
#include "net/security/openssl_util.hpp"
#include "net/security/pki.hpp"

namespace dsswarm::security {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxDomainId = 232;  // highest DDS domain id with the standard port mapping
constexpr int kMaxDays = 36500;
constexpr std::size_t kMaxNameLength = 63;

// Serialises commands on one keys directory (two `keys add` at once would
// otherwise hand out the same serial number).
class DirLock {
 public:
  explicit DirLock(const fs::path& dir) : fd_(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ < 0) throw InputError("keys directory " + dir.string() + " does not exist");
    if (::flock(fd_, LOCK_EX) != 0) {
      ::close(fd_);
      throw InputError("cannot lock " + dir.string());
    }
  }
  ~DirLock() { ::close(fd_); }
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;

 private:
  int fd_;
};

// A private (0700) directory where a command assembles its files before one
// rename publishes them all; removed if the command fails before that.
class StagingDir {
 public:
  explicit StagingDir(const fs::path& final_path) : final_(final_path), path_(final_path) {
    path_.replace_filename(fmt::format(".{}.tmp-{}", final_path.filename().string(), ::getpid()));
    fs::remove_all(path_);
    fs::create_directory(path_);
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::replace);
  }
  ~StagingDir() {
    std::error_code ignored;
    if (!committed_) fs::remove_all(path_, ignored);
  }
  StagingDir(const StagingDir&) = delete;
  StagingDir& operator=(const StagingDir&) = delete;

  const fs::path& path() const { return path_; }
  void commit() {
    std::error_code ec;
    fs::rename(path_, final_, ec);  // replaces final_ only if it is an empty directory
    if (ec) throw InputError("cannot create " + final_.string() + ": " + ec.message());
    committed_ = true;
  }

 private:
  fs::path final_, path_;
  bool committed_ = false;
};

struct Ca {
  CertPtr cert;
  KeyPtr key;
};

Ca load_ca(const KeysLayout& layout) {
  const auto cert_file = layout.ca_certificate(), key_file = layout.ca_key();
  return {parse_certificate(read_text_file(cert_file), cert_file.string()),
          parse_private_key(read_text_file(key_file), key_file.string())};
}

void write_private_key(const fs::path& path, EVP_PKEY* key) {
  write_file_atomically(path, pem_of(key));
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace);
}

// The readable document and its signed form, side by side.
void write_signed(const fs::path& source, const fs::path& signed_path, const std::string& xml, const Ca& ca) {
  write_file_atomically(source, xml);
  write_file_atomically(signed_path, smime_sign_text(xml, ca.cert.get(), ca.key.get()));
}

// Rebuilds the CRL from the index: every revoked robot, valid until the CA expires.
void write_crl(const KeysLayout& layout, const SwarmKeys& keys, const Ca& ca) {
  std::vector<RevokedCertificate> revoked;
  for (const auto& r : keys.robots)
    if (r.revoked_at) revoked.push_back({r.serial, *r.revoked_at});
  const auto now = std::chrono::system_clock::now();
  const Validity validity{now - kClockSkewAllowance, certificate_not_after(ca.cert.get())};
  write_file_atomically(layout.crl(), pem_of(make_crl(ca.cert.get(), ca.key.get(), revoked, validity, keys.crl_number).get()));
}

std::string organization(int swarm_id) { return "dsswarm-" + std::to_string(swarm_id); }

void validate_init(const fs::path& dir, const KeysInitOptions& o) {
  if (o.swarm_id < 0 || o.swarm_id > kMaxDomainId) {
    throw ConfigError("--swarm " + std::to_string(o.swarm_id) + ": must be 0-" + std::to_string(kMaxDomainId) +
                      " (it is the DDS domain id)");
  }
  if (o.days < 1 || o.days > kMaxDays) throw ConfigError("--days " + std::to_string(o.days) + ": must be 1-36500");
  const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
  if (!fs::is_directory(parent)) throw InputError("cannot create " + dir.string() + ": " + parent.string() + " does not exist");
  if (fs::exists(KeysLayout{dir}.index())) {
    throw InputError(dir.string() + " already holds a swarm's keys (swarm.json): refusing to replace its CA");
  }
  if (fs::exists(dir) && (!fs::is_directory(dir) || !fs::is_empty(dir))) {
    throw InputError(dir.string() + " exists and is not an empty directory");
  }
}

}  // namespace

void validate_robot_name(const std::string& name) {
  const auto ok_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; };
  if (name.empty() || name.size() > kMaxNameLength || !std::isalnum(static_cast<unsigned char>(name[0])) ||
      !std::all_of(name.begin(), name.end(), ok_char)) {
    throw ConfigError("robot name '" + name + "': use 1-63 letters, digits, '_' or '-', starting with a letter or digit");
  }
}

SwarmKeys init_keys(const fs::path& dir_in, const KeysInitOptions& o) {
  const fs::path dir = fs::absolute(dir_in).lexically_normal();
  const fs::path target = dir.has_filename() ? dir : dir.parent_path();  // "keys/" names "keys"
  validate_init(target, o);
  StagingDir staging(target);
  const KeysLayout layout{staging.path()};
  const auto now = std::chrono::system_clock::now();
  Ca ca{nullptr, generate_ec_key()};
  const CertificateSpec spec{organization(o.swarm_id) + " CA", organization(o.swarm_id), 1,
                             {now - kClockSkewAllowance, now + std::chrono::days(o.days)}, true};
  ca.cert = make_certificate(spec, ca.key.get(), nullptr, ca.key.get());
  write_private_key(layout.ca_key(), ca.key.get());
  write_file_atomically(layout.ca_certificate(), pem_of(ca.cert.get()));

  GovernanceOptions governance = o.governance;
  governance.domain_id = o.swarm_id;
  write_signed(layout.governance_source(), layout.governance(), governance_xml(governance), ca);

  SwarmKeys keys;
  keys.swarm_id = keys.domain_id = o.swarm_id;
  write_crl(layout, keys, ca);
  fs::create_directory(layout.robots());
  save_swarm_keys(layout.dir, keys);
  staging.commit();
  return keys;
}

namespace {

Validity robot_validity(const RobotKeyOptions& o, X509* ca_cert) {
  const auto now = std::chrono::system_clock::now();
  const TimePoint ca_end = certificate_not_after(ca_cert);
  if (ca_end <= now) throw InputError("the swarm CA expired on " + utc_text(ca_end) + ": make new keys with `keys init`");
  if (!o.days) return {now - kClockSkewAllowance, ca_end};
  if (*o.days < 1 || *o.days > kMaxDays) throw ConfigError("--days " + std::to_string(*o.days) + ": must be 1-36500");
  const TimePoint end = now + std::chrono::days(*o.days);
  if (end > ca_end) {
    throw ConfigError("--days " + std::to_string(*o.days) + ": reaches past the swarm CA's expiry (" + utc_text(ca_end) + ")");
  }
  return {now - kClockSkewAllowance, end};
}

void check_new_robot(const KeysLayout& layout, const SwarmKeys& keys, const std::string& name) {
  if (const RobotRecord* r = keys.find(name)) {
    if (r->revoked_at) {
      throw InputError("robot " + name + " was revoked on " + utc_text(*r->revoked_at) +
                       "; a revoked name is not issued again: choose another name");
    }
    throw InputError("robot " + name + " already has keys in " + layout.robot(name).dir.string());
  }
  if (fs::exists(layout.robot(name).dir)) {
    throw InputError(layout.robot(name).dir.string() + " exists but is not in swarm.json: remove it or choose another name");
  }
}

}  // namespace

RobotRecord add_robot(const fs::path& dir, const std::string& name, const RobotKeyOptions& o) {
  validate_robot_name(name);
  DirLock lock(dir);
  SwarmKeys keys = load_swarm_keys(dir);
  const KeysLayout layout{dir};
  check_new_robot(layout, keys, name);
  const Ca ca = load_ca(layout);

  RobotRecord record{name, keys.next_serial, "CN=" + name + ",O=" + organization(keys.swarm_id),
                     o.certificate_validity.value_or(robot_validity(o, ca.cert.get())), std::nullopt};
  StagingDir staging(layout.robot(name).dir);
  const RobotFiles staged{staging.path()};
  KeyPtr key = generate_ec_key();
  const CertificateSpec spec{name, organization(keys.swarm_id), record.serial, record.validity, false};
  const CertPtr cert = make_certificate(spec, key.get(), ca.cert.get(), ca.key.get());
  write_private_key(staged.key(), key.get());
  write_file_atomically(staged.certificate(), pem_of(cert.get()));
  const PermissionsOptions permissions{name, record.subject, keys.domain_id,
                                       o.permissions_validity.value_or(record.validity), swarm_topic_expressions()};
  write_signed(staged.permissions_source(), staged.permissions(), permissions_xml(permissions), ca);
  staging.commit();

  keys.robots.push_back(record);
  ++keys.next_serial;
  save_swarm_keys(dir, keys);
  return record;
}

RobotRecord revoke_robot(const fs::path& dir, const std::string& name) {
  validate_robot_name(name);
  DirLock lock(dir);
  SwarmKeys keys = load_swarm_keys(dir);
  RobotRecord* r = keys.find(name);
  if (r == nullptr) {
    std::string known;
    for (const auto& k : keys.robots) {
      if (!known.empty()) known += ", ";
      known += k.name;
    }
    throw InputError("no robot " + name + " in " + dir.string() + " (robots: " + (known.empty() ? "none" : known) + ")");
  }
  if (r->revoked_at) throw InputError("robot " + name + " is already revoked (on " + utc_text(*r->revoked_at) + ")");
  r->revoked_at = std::chrono::system_clock::now();
  const RobotRecord revoked = *r;
  ++keys.crl_number;
  // CRL first: if the index write fails, re-running revoke writes the same CRL again.
  write_crl(KeysLayout{dir}, keys, load_ca(KeysLayout{dir}));
  save_swarm_keys(dir, keys);
  return revoked;
}

}  // namespace dsswarm::security
