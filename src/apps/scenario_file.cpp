#include "apps/scenario_file.hpp"

#include <cmath>
#include <system_error>

namespace dsswarm::scenario_detail {

namespace fs = std::filesystem;

void ScenarioFile::fail(const YAML::Node& node, const std::string& context, const std::string& key,
                        const std::string& what) const {
  throw InputError(fmt::format("{}: line {}: {}key '{}': {}", file_, node.Mark().line + 1, prefix(context), key,
                               what));
}

void ScenarioFile::fail_missing(const YAML::Node& parent, const std::string& context, const std::string& key,
                                const std::string& what) const {
  throw InputError(fmt::format("{}: line {}: {}missing key '{}'{}", file_, parent.Mark().line + 1,
                               prefix(context), key, what.empty() ? "" : " (" + what + ")"));
}

void ScenarioFile::check_keys(const YAML::Node& map, const std::string& context, const std::string& what,
                              const std::set<std::string>& allowed) const {
  if (!map.IsMap()) {
    throw InputError(fmt::format("{}: line {}: {}expected {} (a mapping of keys)", file_, map.Mark().line + 1,
                                 prefix(context), what));
  }
  std::set<std::string> seen;
  for (const auto& entry : map) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : std::string("?");
    if (!allowed.count(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(entry.first, context, key, fmt::format("unknown key (expected one of: {})", list));
    }
    if (!seen.insert(key).second) fail(entry.first, context, key, "given twice");
  }
}

std::string ScenarioFile::text(const YAML::Node& node, const std::string& context, const std::string& key) const {
  if (!node.IsScalar()) fail(node, context, key, "expected a single value");
  if (node.Scalar().empty()) fail(node, context, key, "empty value");
  return node.Scalar();
}

double ScenarioFile::number(const YAML::Node& node, const std::string& context, const std::string& key) const {
  const std::string t = text(node, context, key);
  double value = 0.0;
  try {
    value = node.as<double>();
  } catch (const YAML::Exception&) {
    fail(node, context, key, fmt::format("'{}' is not a number", t));
  }
  if (!std::isfinite(value)) fail(node, context, key, fmt::format("'{}' is not a finite number", t));
  return value;
}

double ScenarioFile::non_negative(const YAML::Node& node, const std::string& context, const std::string& key) const {
  const double v = number(node, context, key);
  if (v < 0.0) fail(node, context, key, fmt::format("{} is negative (a time in seconds >= 0 is needed)", v));
  return v;
}

double ScenarioFile::fraction(const YAML::Node& node, const std::string& context, const std::string& key) const {
  const double v = number(node, context, key);
  if (v < 0.0 || v > 1.0) fail(node, context, key, fmt::format("{} is outside [0, 1]", v));
  return v;
}

fs::path ScenarioFile::existing_file(const YAML::Node& node, const std::string& context, const std::string& key,
                                     bool folder_ok) const {
  const fs::path given = text(node, context, key);
  const fs::path resolved = given.is_absolute() ? given : fs::path(file_).parent_path() / given;
  std::error_code ec;
  if (!fs::is_regular_file(resolved, ec) && !(folder_ok && fs::is_directory(resolved, ec))) {
    fail(node, context, key, fmt::format("file not found: {}", resolved.string()));
  }
  return resolved.lexically_normal();
}

}  // namespace dsswarm::scenario_detail
