#include "net/security/keys_index.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>

#include "common/errors.hpp"
#include "io/atomic_file.hpp"
#include "net/security/openssl_util.hpp"

namespace dsswarm::security {

namespace {

constexpr const char* kFormat = "dsswarm-keys";
constexpr int kVersion = 1;

nlohmann::json robot_json(const RobotRecord& r) {
  nlohmann::json j = {{"name", r.name},
                      {"serial", r.serial},
                      {"subject", r.subject},
                      {"not_before", utc_text(r.validity.not_before)},
                      {"not_after", utc_text(r.validity.not_after)}};
  j["revoked_at"] = r.revoked_at ? nlohmann::json(utc_text(*r.revoked_at)) : nlohmann::json(nullptr);
  return j;
}

RobotRecord robot_from(const nlohmann::json& j, const std::string& where) {
  RobotRecord r;
  r.name = j.at("name").get<std::string>();
  r.serial = j.at("serial").get<std::uint64_t>();
  r.subject = j.at("subject").get<std::string>();
  r.validity.not_before = parse_utc_text(j.at("not_before").get<std::string>(), where + " not_before");
  r.validity.not_after = parse_utc_text(j.at("not_after").get<std::string>(), where + " not_after");
  if (!j.at("revoked_at").is_null()) r.revoked_at = parse_utc_text(j.at("revoked_at").get<std::string>(), where);
  return r;
}

SwarmKeys keys_from(const nlohmann::json& j, const std::string& file) {
  if (j.value("format", "") != kFormat || j.value("version", 0) != kVersion) {
    throw InputError(file + ": not a dsswarm keys index (format '" + std::string(kFormat) + "', version " +
                     std::to_string(kVersion) + " expected)");
  }
  SwarmKeys k;
  k.swarm_id = j.at("swarm_id").get<int>();
  k.domain_id = j.at("domain_id").get<int>();
  k.next_serial = j.at("next_serial").get<std::uint64_t>();
  k.crl_number = j.at("crl_number").get<std::uint64_t>();
  const auto& robots = j.at("robots");
  for (std::size_t i = 0; i < robots.size(); ++i) {
    k.robots.push_back(robot_from(robots.at(i), file + ": robots[" + std::to_string(i) + "]"));
  }
  return k;
}

}  // namespace

const RobotRecord* SwarmKeys::find(const std::string& name) const {
  const auto it = std::find_if(robots.begin(), robots.end(), [&](const RobotRecord& r) { return r.name == name; });
  return it == robots.end() ? nullptr : &*it;
}

RobotRecord* SwarmKeys::find(const std::string& name) {
  return const_cast<RobotRecord*>(static_cast<const SwarmKeys*>(this)->find(name));
}

SwarmKeys load_swarm_keys(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(dir)) throw InputError("keys directory " + dir.string() + " does not exist");
  const KeysLayout layout{dir};
  if (!fs::exists(layout.index())) {
    throw InputError(dir.string() + " is not a dsswarm keys directory (no swarm.json; make one with `dsswarm keys init`)");
  }
  const std::string file = layout.index().string();
  try {
    return keys_from(nlohmann::json::parse(read_text_file(layout.index())), file);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file + ": " + e.what());
  }
}

void save_swarm_keys(const std::filesystem::path& dir, const SwarmKeys& k) {
  nlohmann::json robots = nlohmann::json::array();
  for (const auto& r : k.robots) robots.push_back(robot_json(r));
  const nlohmann::json j = {{"format", kFormat},
                            {"version", kVersion},
                            {"swarm_id", k.swarm_id},
                            {"domain_id", k.domain_id},
                            {"next_serial", k.next_serial},
                            {"crl_number", k.crl_number},
                            {"robots", robots}};
  write_file_atomically(KeysLayout{dir}.index(), j.dump(2) + "\n");
}

}  // namespace dsswarm::security
