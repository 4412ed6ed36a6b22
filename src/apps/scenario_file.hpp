#pragma once
// Reading a swarm scenario's YAML (swarm_scenario.cpp): keys checked against
// what is allowed, values checked as they are read, and every mistake an
// InputError that points at the file, the line and the key.
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>
#include <string>
#include <utility>

#include "common/errors.hpp"

namespace dsswarm::scenario_detail {

// Error messages: "FILE: line N: CONTEXT key 'KEY': WHAT", where CONTEXT says
// which agent or encounter ("agents[1] (robot2):").
class ScenarioFile {
 public:
  explicit ScenarioFile(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& context, const std::string& key,
                         const std::string& what) const;

  [[noreturn]] void fail_missing(const YAML::Node& parent, const std::string& context, const std::string& key,
                                 const std::string& what = "") const;

  // Unknown keys are errors: a misspelt `from` must not silently play the whole log.
  void check_keys(const YAML::Node& map, const std::string& context, const std::string& what,
                  const std::set<std::string>& allowed) const;

  std::string text(const YAML::Node& node, const std::string& context, const std::string& key) const;

  double number(const YAML::Node& node, const std::string& context, const std::string& key) const;

  double non_negative(const YAML::Node& node, const std::string& context, const std::string& key) const;

  double fraction(const YAML::Node& node, const std::string& context, const std::string& key) const;

  // An existing file named relative to the scenario's folder.
  // `folder_ok`: a folder will do (a ROS 2 bag is one).
  std::filesystem::path existing_file(const YAML::Node& node, const std::string& context, const std::string& key,
                                      bool folder_ok = false) const;

  const std::string& file() const { return file_; }

 private:
  static std::string prefix(const std::string& context) { return context.empty() ? "" : context + " "; }

  std::string file_;
};

// `load` parses the scenario's YAML (from its file or from text).
template <typename Load>
YAML::Node load_root(const std::filesystem::path& yaml, Load load) {
  YAML::Node root;
  try {
    root = load();
  } catch (const YAML::ParserException& e) {
    throw InputError(fmt::format("{}: line {}: invalid YAML: {}", yaml.string(), e.mark.line + 1, e.msg));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}: cannot read scenario: {}", yaml.string(), e.what()));
  }
  if (!root.IsMap()) {
    throw InputError(fmt::format("{}: expected a scenario (a mapping with 'agents' and optionally 'name', "
                                 "'config', 'relations', 'encounters')",
                                 yaml.string()));
  }
  return root;
}

}  // namespace dsswarm::scenario_detail
