#pragma once
// The configuration file: every component's plain config struct <-> JSON,
// for `--config FILE` and for recording the configuration a run used. One
// file serves every command (`dsswarm config` prints it with the defaults):
// the SLAM sections (filter, map, evidence, matcher, points, slam) and the
// swarm sections (encounter, swarm), which single-robot runs ignore. Every
// key is optional (missing = default); an unknown key or a value of the wrong
// type is an error naming the key, so a typo never silently falls back to a
// default.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "slam/slam.hpp"
#include "swarm/swarm_config.hpp"

namespace dsswarm {

nlohmann::json to_json(const SwarmConfig& config);  // every section
nlohmann::json to_json(const SlamConfig& config);   // the SLAM sections

// Applies the keys present in `j` on top of `config`. Throws ConfigError.
void apply_json(const nlohmann::json& j, SwarmConfig& config, const std::string& source = "config");
// The same for a single robot: the swarm sections are checked, then ignored.
void apply_json(const nlohmann::json& j, SlamConfig& config, const std::string& source = "config");

// Reads a JSON file and applies it on top of `config` (then validates).
void load_config(const std::filesystem::path& path, SwarmConfig& config);
void load_slam_config(const std::filesystem::path& path, SlamConfig& config);

// The same as load_config for JSON text in memory; `source` names it in errors.
void parse_config(std::string_view text, const std::string& source, SwarmConfig& config);

}  // namespace dsswarm
