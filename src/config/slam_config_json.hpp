#pragma once
// SlamConfig <-> JSON, for `--config FILE` and for recording the configuration
// a run used. Every key is optional (missing = default); an unknown key or a
// value of the wrong type is an error naming the key, so a typo never silently
// falls back to a default.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "slam/slam.hpp"

namespace dsswarm {

nlohmann::json to_json(const SlamConfig& config);

// Applies the keys present in `j` on top of `config`. Throws ConfigError.
void apply_json(const nlohmann::json& j, SlamConfig& config, const std::string& source = "config");

// Reads a JSON file and applies it on top of `config` (then validates).
void load_slam_config(const std::filesystem::path& path, SlamConfig& config);

}  // namespace dsswarm
