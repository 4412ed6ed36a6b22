#pragma once
// FNV-1a: a fixed, platform-independent hash of a string, for deriving
// reproducible seeds from names (std::hash may differ between builds).
#include <cstdint>
#include <string_view>

namespace dsswarm {

constexpr std::uint64_t fnv1a64(std::string_view s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : s) {
    h ^= static_cast<std::uint8_t>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

}  // namespace dsswarm
