#include "apps/stale_outputs.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <fstream>
#include <string>
#include <system_error>

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

// What write_swarm_outputs writes per agent (swarm_runner.hpp lists them).
constexpr std::array<const char*, 7> kAgentFiles = {"trajectory.tum",  "map.pgm",         "map.yaml",
                                                    "merged_map.pgm",  "merged_map.yaml", "merged_map.png",
                                                    "ground_truth.tum"};

// An agent name from a file we did not check: only plain folder names are trusted.
bool plain_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos;
}

std::vector<std::string> previous_agents(const fs::path& dir) {
  std::ifstream in(dir / "stats.json");
  if (!in) return {};
  const nlohmann::json stats = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  std::vector<std::string> names;
  if (!stats.is_object() || !stats.contains("agents") || !stats["agents"].is_array()) return names;
  for (const nlohmann::json& agent : stats["agents"]) {
    if (!agent.is_object() || !agent.contains("name") || !agent["name"].is_string()) continue;
    const std::string name = agent["name"].get<std::string>();
    if (plain_name(name)) names.push_back(name);
  }
  return names;
}

void remove_if_empty(const fs::path& folder) {
  std::error_code ec;
  if (fs::is_directory(folder, ec) && fs::is_empty(folder, ec)) fs::remove(folder, ec);
}

}  // namespace

std::vector<fs::path> previous_swarm_outputs(const fs::path& dir) {
  const std::vector<std::string> agents = previous_agents(dir);
  std::vector<fs::path> files;
  if (agents.empty()) return files;
  for (const std::string& name : agents) {
    for (const char* f : kAgentFiles) files.push_back(dir / "agents" / name / f);
    files.push_back(dir / "joint" / (name + ".tum"));
  }
  files.push_back(dir / "evaluation.json");
  return files;
}

void remove_stale_outputs(const fs::path& dir, const std::vector<fs::path>& previous, const OutputFiles& written) {
  const auto& now = written.files();
  for (const fs::path& p : previous) {
    if (std::any_of(now.begin(), now.end(), [&](const OutputFiles::File& f) { return f.path == p; })) continue;
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(p, ec))) fs::remove(p, ec);
    if (p.parent_path().parent_path() == dir / "agents") remove_if_empty(p.parent_path());
  }
  remove_if_empty(dir / "agents");
  remove_if_empty(dir / "joint");
}

}  // namespace dsswarm
