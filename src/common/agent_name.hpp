#pragma once
// Robot names: they name output folders, DDS topics and certificate subjects,
// so they are kept to a portable alphabet.
#include <algorithm>
#include <cstddef>
#include <string_view>

namespace dsswarm {

inline constexpr std::size_t kMaxAgentNameLength = 64;

// Letters, digits, '_', '-', '.'; not "." or ".."; 1 to kMaxAgentNameLength characters.
inline bool is_valid_agent_name(std::string_view name) {
  if (name.empty() || name.size() > kMaxAgentNameLength || name == "." || name == "..") return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.';
  });
}

}  // namespace dsswarm
