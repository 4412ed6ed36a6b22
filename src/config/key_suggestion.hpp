#pragma once
// "Did you mean …?" for a configuration key that is not known: the known key
// closest to what was written, so a typo or a key put in the wrong section is
// a one-look fix rather than a hunt through the documentation.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dsswarm {

// Known keys, section → its keys.
using KnownKeys = std::map<std::string, std::vector<std::string>, std::less<>>;

// Levenshtein distance (insertions, deletions, substitutions), ASCII case
// folded: "Hit_Occupied" is one fix away from nothing but the case.
std::size_t edit_distance(std::string_view a, std::string_view b);

// The known "section.key" (or "section") that `section`.`key` most likely
// meant, or nothing when none is close. `key` empty: a section name was not
// known. Tried in order: a section written as a key (e.g. "map.evidence" for
// the top-level "evidence"); the key in another section; the nearest spelling
// in the same section, then in any section (at most a third of the name's
// letters wrong).
std::optional<std::string> suggest_key(const KnownKeys& known, std::string_view section, std::string_view key);

}  // namespace dsswarm
