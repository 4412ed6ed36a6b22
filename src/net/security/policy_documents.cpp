#include "net/security/policy_documents.hpp"

#include <fmt/format.h>

#include <ctime>
#include <iomanip>
#include <sstream>

#include "common/errors.hpp"

namespace dsswarm::security {

namespace {

constexpr const char* kHeader =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\"\n"
    "     xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-SECURITY/20170901/{}\">\n";

std::string topic_rule(const std::string& expression, ProtectionKind metadata, ProtectionKind data) {
  return fmt::format(
      "        <topic_rule>\n"
      "          <topic_expression>{}</topic_expression>\n"
      "          <enable_discovery_protection>true</enable_discovery_protection>\n"
      "          <enable_liveliness_protection>true</enable_liveliness_protection>\n"
      "          <enable_read_access_control>true</enable_read_access_control>\n"
      "          <enable_write_access_control>true</enable_write_access_control>\n"
      "          <metadata_protection_kind>{}</metadata_protection_kind>\n"
      "          <data_protection_kind>{}</data_protection_kind>\n"
      "        </topic_rule>\n",
      xml_escape(expression), protection_name(metadata), protection_name(data));
}

std::string topic_list(const std::vector<std::string>& topics) {
  std::string out;
  for (const auto& t : topics) out += fmt::format("<topic>{}</topic>", xml_escape(t));
  return out;
}

}  // namespace

std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

const char* protection_name(ProtectionKind kind) {
  switch (kind) {
    case ProtectionKind::kNone: return "NONE";
    case ProtectionKind::kSign: return "SIGN";
    case ProtectionKind::kEncrypt: return "ENCRYPT";
  }
  return "ENCRYPT";
}

std::string governance_xml(const GovernanceOptions& o) {
  std::string rules;
  for (const auto& t : swarm_topic_expressions()) rules += topic_rule(t, o.swarm_metadata, o.swarm_data);
  rules += topic_rule("*", o.swarm_metadata, o.swarm_data);  // first match wins: the swarm's rules come first
  return fmt::format(kHeader, "omg_shared_ca_governance.xsd") +
         fmt::format(
             "  <domain_access_rules>\n"
             "    <domain_rule>\n"
             "      <domains><id>{}</id></domains>\n"
             "      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
             "      <enable_join_access_control>true</enable_join_access_control>\n"
             "      <discovery_protection_kind>{}</discovery_protection_kind>\n"
             "      <liveliness_protection_kind>{}</liveliness_protection_kind>\n"
             "      <rtps_protection_kind>{}</rtps_protection_kind>\n"
             "      <topic_access_rules>\n{}"
             "      </topic_access_rules>\n"
             "    </domain_rule>\n"
             "  </domain_access_rules>\n"
             "</dds>\n",
             o.domain_id, protection_name(o.discovery), protection_name(o.liveliness), protection_name(o.rtps), rules);
}

std::string permissions_xml(const PermissionsOptions& o) {
  const std::string topics = topic_list(o.topics);
  return fmt::format(kHeader, "omg_shared_ca_permissions.xsd") +
         fmt::format(
             "  <permissions>\n"
             "    <grant name=\"{}\">\n"
             "      <subject_name>{}</subject_name>\n"
             "      <validity>\n"
             "        <not_before>{}</not_before>\n"
             "        <not_after>{}</not_after>\n"
             "      </validity>\n"
             "      <allow_rule>\n"
             "        <domains><id>{}</id></domains>\n"
             "        <publish><topics>{}</topics></publish>\n"
             "        <subscribe><topics>{}</topics></subscribe>\n"
             "      </allow_rule>\n"
             "      <default>DENY</default>\n"
             "    </grant>\n"
             "  </permissions>\n"
             "</dds>\n",
             xml_escape(o.grant_name), xml_escape(o.subject), utc_text(o.validity.not_before),
             utc_text(o.validity.not_after), o.domain_id, topics, topics);
}

std::string utc_text(TimePoint t) {
  const std::time_t secs = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  gmtime_r(&secs, &tm);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}Z", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday, tm.tm_hour,
                     tm.tm_min, tm.tm_sec);
}

TimePoint parse_utc_text(const std::string& text, const std::string& what) {
  std::tm tm{};
  std::istringstream in(text);
  in >> std::get_time(&tm, "%Y-%m-%dT%H:%M:%SZ");
  if (in.fail() || in.peek() != std::char_traits<char>::eof()) {
    throw InputError(what + ": '" + text + "' is not a UTC time like 2025-01-31T12:00:00Z");
  }
  return std::chrono::system_clock::from_time_t(timegm(&tm));
}

}  // namespace dsswarm::security
