#include "config/key_suggestion.hpp"

#include <algorithm>
#include <cctype>
#include <numeric>

namespace dsswarm {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  auto fold = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const std::size_t substitute = diagonal + (fold(a[i - 1]) == fold(b[j - 1]) ? 0 : 1);
      row[j] = std::min({above + 1, row[j - 1] + 1, substitute});
      diagonal = above;
    }
  }
  return row[b.size()];
}

namespace {

// Close enough to be a misspelling rather than another word.
bool near_enough(std::size_t distance, std::string_view written) {
  return distance * 3 <= std::max<std::size_t>(written.size(), 3);
}

struct Nearest {
  std::size_t distance = static_cast<std::size_t>(-1);
  std::string name;
  void offer(std::size_t d, std::string n) {
    if (d >= distance) return;
    distance = d;
    name = std::move(n);
  }
};

std::optional<std::string> nearest_section(const KnownKeys& known, std::string_view section) {
  Nearest best;
  for (const auto& [name, keys] : known) best.offer(edit_distance(section, name), name);
  if (best.name.empty() || !near_enough(best.distance, section)) return std::nullopt;
  return best.name;
}

}  // namespace

std::optional<std::string> suggest_key(const KnownKeys& known, std::string_view section, std::string_view key) {
  if (key.empty()) return nearest_section(known, section);
  if (known.contains(key)) return std::string(key);
  for (const auto& [name, keys] : known)
    if (name != section && std::find(keys.begin(), keys.end(), key) != keys.end()) return name + "." + std::string(key);
  Nearest same, any;
  for (const auto& [name, keys] : known)
    for (const std::string& k : keys) {
      const std::size_t d = edit_distance(key, k);
      if (name == section) same.offer(d, name + "." + k);
      any.offer(d, name + "." + k);
    }
  if (!same.name.empty() && near_enough(same.distance, key)) return same.name;
  if (!any.name.empty() && near_enough(any.distance, key)) return any.name;
  return std::nullopt;
}

}  // namespace dsswarm
